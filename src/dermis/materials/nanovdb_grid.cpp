#include "dermis/materials/nanovdb_grid.h"

// clang-format off
#include <iostream>  // before GridValidator.h, which uses std::cerr without including it (NanoVDB 32.4)
#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/GridValidator.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/SampleFromVoxels.h>
// clang-format on

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <stdexcept>
#include <vector>

namespace dermis {

namespace {

using FloatGrid = nanovdb::FloatGrid;
using Tree = FloatGrid::TreeType;
using Root = Tree::RootType;
using Upper = Root::ChildNodeType;
using Lower = Upper::ChildNodeType;
using Leaf = Lower::ChildNodeType;

std::runtime_error corrupt(const std::string& what) { return std::runtime_error("corrupt .nvdb file: " + what); }

// The file's segment headers and grid metadata, checked before NanoVDB's reader sees them:
// it reads a grid name up to a NUL it does not check for, and allocates whatever size a
// header claims before finding the file shorter.
void check_file_headers(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw std::runtime_error("not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open the file");
  in.seekg(0, std::ios::end);
  const uint64_t size = uint64_t(in.tellg());
  in.seekg(0);
  if (size < sizeof(nanovdb::io::Header)) throw std::runtime_error("not an .nvdb file (too short)");
  uint64_t pos = 0;
  while (pos < size) {
    nanovdb::io::Header h;
    if (size - pos < sizeof(h) || !in.read(reinterpret_cast<char*>(&h), sizeof(h))) throw corrupt("truncated header");
    pos += sizeof(h);
    if (h.magic != NANOVDB_MAGIC_NUMBER) throw std::runtime_error("not an .nvdb file (no NanoVDB magic number)");
    if (h.version.getMajor() != NANOVDB_MAJOR_VERSION_NUMBER)
      throw std::runtime_error("NanoVDB file format version " + std::to_string(h.version.getMajor()) +
                               ", this build reads version " + std::to_string(NANOVDB_MAJOR_VERSION_NUMBER));
    if (h.codec != nanovdb::io::Codec::NONE && h.codec != nanovdb::io::Codec::ZIP)
      throw std::runtime_error("compressed with a codec other than ZIP (pbrt-v4 reads none or ZIP)");
    uint64_t data_bytes = 0;
    std::vector<uint64_t> block_bytes;
    for (uint16_t i = 0; i < h.gridCount; ++i) {
      nanovdb::io::MetaData m;
      if (size - pos < sizeof(m) || !in.read(reinterpret_cast<char*>(&m), sizeof(m)))
        throw corrupt("truncated grid metadata");
      pos += sizeof(m);
      if (m.nameSize == 0 || m.nameSize > size - pos) throw corrupt("a grid name's size is wrong");
      std::string name(m.nameSize, '\0');
      if (!in.read(name.data(), std::streamsize(m.nameSize)) || name.back() != '\0')
        throw corrupt("a grid name is not terminated");
      pos += m.nameSize;
      // Deflate compresses at most ~1032:1.
      if (m.fileSize > size || m.gridSize == 0 || (h.codec == nanovdb::io::Codec::NONE && m.gridSize != m.fileSize) ||
          (h.codec == nanovdb::io::Codec::ZIP && m.gridSize / 1100 > m.fileSize))
        throw corrupt("a grid's size is implausible");
      data_bytes += m.fileSize;
      block_bytes.push_back(m.fileSize);
    }
    if (data_bytes > size - pos) throw corrupt("the file is shorter than its grids");
    if (h.codec == nanovdb::io::Codec::ZIP) {
      for (uint64_t bytes : block_bytes) {  // each compressed block starts with its size
        uint64_t zipped = 0;
        if (bytes < sizeof(zipped) || !in.read(reinterpret_cast<char*>(&zipped), sizeof(zipped)) ||
            zipped > bytes - sizeof(zipped))
          throw corrupt("a compressed block's size is implausible");
        in.seekg(std::streamoff(bytes - sizeof(zipped)), std::ios::cur);
      }
    } else {
      in.seekg(std::streamoff(data_bytes), std::ios::cur);
    }
    pos += data_bytes;
  }
}

// Every node a lookup can reach lies inside the buffer, aligned (NanoVDB follows offsets
// without checking them; its validator trusts the tile count and skips the leaves).
void check_structure(const nanovdb::GridHandle<>& handle) {
  const uint64_t size = handle.size();
  const uintptr_t base = reinterpret_cast<uintptr_t>(handle.data());
  auto inside = [&](uintptr_t p, uint64_t n) {
    return p >= base && p - base <= size && n <= size - (p - base) && p % NANOVDB_DATA_ALIGNMENT == 0;
  };
  auto address = [](const void* p) { return reinterpret_cast<uintptr_t>(p); };
  if (!handle.data() || size < sizeof(FloatGrid) + sizeof(Tree) + sizeof(Root)) throw corrupt("grid too small");
  const auto* data = reinterpret_cast<const nanovdb::GridData*>(handle.data());
  if (data->mMagic != NANOVDB_MAGIC_NUMBER) throw corrupt("bad grid magic number");
  if (data->mGridType >= nanovdb::GridType::End || data->mGridClass >= nanovdb::GridClass::End)
    throw corrupt("invalid grid type or class");
  if (data->mGridType != nanovdb::GridType::Float)
    throw std::runtime_error(std::string("the grid holds ") + nanovdb::toStr(data->mGridType) +
                             " values; a medium's density is a float grid");
  if (data->mGridClass != nanovdb::GridClass::FogVolume && data->mGridClass != nanovdb::GridClass::Unknown)
    throw std::runtime_error(std::string("the grid is a ") + nanovdb::toStr(data->mGridClass) +
                             ", not a fog volume (as pbrt-v4 requires)");
  if (data->mGridSize > size) throw corrupt("grid larger than its buffer");
  const FloatGrid& grid = *reinterpret_cast<const FloatGrid*>(handle.data());
  const uintptr_t tree = address(&grid.tree());
  const auto* td = grid.tree().data();
  auto at_tree = [&](uint64_t offset, uint64_t n) { return offset <= size && inside(tree + offset, n); };
  if (!at_tree(td->mNodeOffset[3], sizeof(Root))) throw corrupt("root node out of range");
  const Root& root = grid.tree().root();
  if (uint64_t(root.tileCount()) > size / sizeof(Root::Tile) ||
      !inside(address(&root), sizeof(Root) + uint64_t(root.tileCount()) * sizeof(Root::Tile)))
    throw corrupt("root tiles out of range");
  const uint64_t node_bytes[3] = {sizeof(Leaf), sizeof(Lower), sizeof(Upper)};
  for (int level = 0; level < 3; ++level)
    if (td->mNodeCount[level] && (td->mNodeCount[level] > size / node_bytes[level] ||
                                  !at_tree(td->mNodeOffset[level], td->mNodeCount[level] * node_bytes[level])))
      throw corrupt("node array out of range");
  auto child_inside = [&](uintptr_t parent, int64_t offset, uint64_t n) {
    return offset > 0 && uint64_t(offset) <= size && inside(parent + uint64_t(offset), n);
  };
  for (uint32_t t = 0; t < root.tileCount(); ++t) {
    const auto* tile = root.data()->tile(t);
    if (!tile->isChild()) continue;
    if (!child_inside(address(root.data()), tile->child, sizeof(Upper))) throw corrupt("node pointer out of range");
    const Upper* upper = root.data()->getChild(tile);
    for (auto it = upper->childMask().beginOn(); it; ++it) {
      if (!child_inside(address(upper->data()), upper->data()->mTable[*it].child, sizeof(Lower)))
        throw corrupt("node pointer out of range");
      const Lower* lower = upper->data()->getChild(*it);
      for (auto jt = lower->childMask().beginOn(); jt; ++jt)
        if (!child_inside(address(lower->data()), lower->data()->mTable[*jt].child, sizeof(Leaf)))
          throw corrupt("leaf pointer out of range");
    }
  }
  const auto box = grid.worldBBox();
  const auto voxel = grid.voxelSize();
  const auto index = grid.indexBBox();
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(box.min()[a]) || !std::isfinite(box.max()[a]) || !(voxel[a] > 0) || !std::isfinite(voxel[a]) ||
        index.min()[a] > index.max()[a])
      throw corrupt("invalid bounding box or voxel size");
}

// Every value a lookup reads (the leaves' inactive ones too, tiles, the background) is
// finite and at least 0: a density.
void check_values(const FloatGrid& grid) {
  const Tree& tree = grid.tree();
  if (!grid.isSequential<0>()) throw std::runtime_error("the grid's leaves are not stored in sequence");
  auto check = [](float v) {
    if (!std::isfinite(v)) throw std::runtime_error("the grid holds NaN or infinite values");
    if (v < 0) throw std::runtime_error("the grid holds negative values (a density must be at least 0)");
  };
  const Leaf* leaves = tree.getFirstLeaf();
  for (uint32_t i = 0; i < tree.nodeCount(0); ++i)
    for (uint32_t n = 0; n < Leaf::SIZE; ++n) check(leaves[i].getValue(n));
  const Root& root = tree.root();
  check(root.background());
  for (uint32_t t = 0; t < root.tileCount(); ++t) {
    const auto* tile = root.data()->tile(t);
    if (!tile->isChild()) {
      check(tile->value);
      continue;
    }
    const Upper* upper = root.data()->getChild(tile);
    for (auto it = upper->childMask().beginOff(); it; ++it) check(upper->data()->getValue(*it));
    for (auto it = upper->childMask().beginOn(); it; ++it) {
      const Lower* lower = upper->data()->getChild(*it);
      for (auto jt = lower->childMask().beginOff(); jt; ++jt) check(lower->data()->getValue(*jt));
    }
  }
}

// The slots of `node` whose children overlap the index box b.
template <class Node, class F>
void for_overlapping_slots(const Node& node, const nanovdb::CoordBBox& b, F f) {
  constexpr int child_log2 = Node::ChildNodeType::TOTAL, log2 = Node::LOG2DIM, n = 1 << log2;
  const nanovdb::Coord o = node.origin();
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::max(0, (b.min()[a] - o[a]) >> child_log2);
    hi[a] = std::min(n - 1, (b.max()[a] - o[a]) >> child_log2);
    if (lo[a] > hi[a]) return;
  }
  for (int i = lo[0]; i <= hi[0]; ++i)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int k = lo[2]; k <= hi[2]; ++k) f(uint32_t((i << (2 * log2)) | (j << log2) | k));
}

// The largest value of the voxels of the index box b (tiles and the background included),
// visiting only the nodes that overlap it.
float max_in_index_box(const FloatGrid& grid, const nanovdb::CoordBBox& b) {
  const Root& root = grid.tree().root();
  float m = root.background();
  for (uint32_t t = 0; t < root.tileCount(); ++t) {
    const auto* tile = root.data()->tile(t);
    const nanovdb::Coord o = tile->origin();
    if (!b.hasOverlap(nanovdb::CoordBBox(o, o.offsetBy(Upper::DIM - 1)))) continue;
    if (!tile->isChild()) {
      m = std::max(m, tile->value);
      continue;
    }
    const Upper* upper = root.data()->getChild(tile);
    for_overlapping_slots(*upper, b, [&](uint32_t n) {
      if (!upper->data()->isChild(n)) {
        m = std::max(m, upper->data()->getValue(n));
        return;
      }
      const Lower* lower = upper->data()->getChild(n);
      for_overlapping_slots(*lower, b, [&](uint32_t k) {
        if (!lower->data()->isChild(k)) {
          m = std::max(m, lower->data()->getValue(k));
          return;
        }
        const Leaf* leaf = lower->data()->getChild(k);
        nanovdb::CoordBBox c(leaf->origin(), leaf->origin().offsetBy(Leaf::DIM - 1));
        c.intersect(b);
        for (int x = c.min()[0]; x <= c.max()[0]; ++x)
          for (int y = c.min()[1]; y <= c.max()[1]; ++y)
            for (int z = c.min()[2]; z <= c.max()[2]; ++z) m = std::max(m, leaf->getValue(nanovdb::Coord(x, y, z)));
      });
    });
  }
  return m;
}

}  // namespace

struct NanoVdbGrid::Impl {
  nanovdb::GridHandle<> handle;  // owns the grid's memory
  const FloatGrid* grid = nullptr;
};

NanoVdbGrid::NanoVdbGrid(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
NanoVdbGrid::~NanoVdbGrid() = default;

std::shared_ptr<const NanoVdbGrid> NanoVdbGrid::load(const std::string& path, const std::string& name, bool optional) {
  auto impl = std::make_unique<Impl>();
  try {
    check_file_headers(path);
    impl->handle = nanovdb::io::readGrid<nanovdb::HostBuffer>(path, name);
  } catch (const std::bad_alloc&) {
    throw corrupt("a size field is implausible");
  }
  if (!impl->handle) {
    if (optional) return nullptr;
    std::string names;
    for (const auto& m : nanovdb::io::readGridMetaData(path))
      names += (names.empty() ? "\"" : ", \"") + m.gridName + "\"";
    throw std::runtime_error("no grid named \"" + name + "\" (the file has " + (names.empty() ? "none" : names) + ")");
  }
  check_structure(impl->handle);
  impl->grid = reinterpret_cast<const FloatGrid*>(impl->handle.data());
  if (const std::string why = nanovdb::GridValidator<float>::check(*impl->grid, true); !why.empty()) throw corrupt(why);
  check_values(*impl->grid);
  return std::shared_ptr<const NanoVdbGrid>(new NanoVdbGrid(std::move(impl)));
}

Vec3 NanoVdbGrid::world_min() const {
  const auto b = impl_->grid->worldBBox();
  return Vec3(float(b.min()[0]), float(b.min()[1]), float(b.min()[2]));
}

Vec3 NanoVdbGrid::world_max() const {
  const auto b = impl_->grid->worldBBox();
  return Vec3(float(b.max()[0]), float(b.max()[1]), float(b.max()[2]));
}

float NanoVdbGrid::value(Vec3 p) const {
  const FloatGrid& g = *impl_->grid;
  const nanovdb::Vec3f index = g.worldToIndexF(nanovdb::Vec3f(p.x, p.y, p.z));
  return nanovdb::SampleFromVoxels<Tree, 1, false>(g.tree())(index);
}

float NanoVdbGrid::max_over(Vec3 lo, Vec3 hi) const {
  const FloatGrid& g = *impl_->grid;
  // The index-space box of the world box's eight corners (the map may rotate), widened by a
  // voxel: trilinear interpolation at index x reads voxels floor(x) and floor(x) + 1.
  float low[3] = {std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                  std::numeric_limits<float>::max()};
  float high[3] = {-low[0], -low[1], -low[2]};
  for (int c = 0; c < 8; ++c) {
    const nanovdb::Vec3f corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    const nanovdb::Vec3f i = g.worldToIndexF(corner);
    for (int a = 0; a < 3; ++a) low[a] = std::min(low[a], i[a]), high[a] = std::max(high[a], i[a]);
  }
  const auto index = g.indexBBox();
  nanovdb::Coord from, to;
  for (int a = 0; a < 3; ++a) {
    from[a] = std::max(int(std::floor(low[a])) - 1, index.min()[a] - 1);
    to[a] = std::min(int(std::floor(high[a])) + 2, index.max()[a] + 1);
    if (from[a] > to[a]) return std::max(0.0f, g.tree().root().background());
  }
  return std::max(0.0f, max_in_index_box(g, nanovdb::CoordBBox(from, to)));
}

std::size_t NanoVdbGrid::bytes() const { return std::size_t(impl_->handle.size()); }

}  // namespace dermis
