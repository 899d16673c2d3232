// The cache of imported meshes: the same mesh as the import, and a miss (never a wrong
// mesh or an error) whenever the file or the cache is not what the cache says.
#include "dermis/scene/mesh_cache.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

#include "dermis/source_hashes.h"

namespace dermis {
namespace {

namespace fs = std::filesystem;

// A quad with normals and uvs, a triangle, and a point (dropped, with a note).
constexpr const char* kObj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n"
    "vn 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "f 1/1/1 2/2/1 3/3/1 4/4/1\nf 1/1/1 2/2/1 5/1/1\np 3\n";

struct MeshCacheTest : ::testing::Test {
  fs::path dir, obj, cache;
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("dermis-mesh-cache-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    obj = dir / "quad.obj";
    cache = dir / "cache";
    write(kObj);
  }
  void TearDown() override { fs::remove_all(dir); }
  void write(const std::string& text) const { std::ofstream(obj, std::ios::binary) << text; }
  std::string cache_file() const { return mesh_cache_path(cache.string(), fs::canonical(obj).string()); }
};

void expect_same(const ImportedMesh& a, const ImportedMesh& b) {
  auto same_bits = [](const auto& x, const auto& y) {
    return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof x[0]) == 0);
  };
  EXPECT_TRUE(same_bits(a.mesh.positions, b.mesh.positions));
  EXPECT_TRUE(same_bits(a.mesh.normals, b.mesh.normals));
  EXPECT_TRUE(same_bits(a.mesh.uvs, b.mesh.uvs));
  EXPECT_EQ(a.mesh.indices, b.mesh.indices);
  EXPECT_EQ(a.notes, b.notes);
}

TEST_F(MeshCacheTest, TheCachedMeshIsTheImportBitForBit) {
  const ImportedMesh direct = import_mesh_assimp(obj.string());
  ASSERT_EQ(direct.mesh.indices.size(), 9u);  // the quad's two triangles and the triangle
  ASSERT_FALSE(direct.mesh.normals.empty());
  ASSERT_FALSE(direct.mesh.uvs.empty());
  ASSERT_EQ(direct.notes.size(), 1u);  // the point

  EXPECT_FALSE(load_cached_mesh(cache.string(), obj.string()));                         // nothing cached yet
  expect_same(import_mesh_cached(obj.string(), nullptr, cache.string(), 0.0), direct);  // imported, then cached
  ASSERT_TRUE(fs::exists(cache_file()));
  const std::optional<ImportedMesh> cached = load_cached_mesh(cache.string(), obj.string());
  ASSERT_TRUE(cached);
  expect_same(*cached, direct);
  expect_same(import_mesh_cached(obj.string(), nullptr, cache.string(), 0.0), direct);  // from the cache
}

TEST_F(MeshCacheTest, AFileEditedToTheSameSizeAndTimeIsImportedAgain) {
  import_mesh_cached(obj.string(), nullptr, cache.string(), 0.0);
  ASSERT_TRUE(load_cached_mesh(cache.string(), obj.string()));
  const auto time = fs::last_write_time(obj);
  std::string edited = kObj;
  edited.replace(edited.find("v 1 1 0"), 7, "v 2 1 0");  // one vertex moved, same size
  ASSERT_EQ(edited.size(), std::strlen(kObj));
  write(edited);
  fs::last_write_time(obj, time);  // as if the edit kept the time: the content's CRC still tells
  EXPECT_FALSE(load_cached_mesh(cache.string(), obj.string()));
  const ImportedMesh again = import_mesh_cached(obj.string(), nullptr, cache.string(), 0.0);
  expect_same(again, import_mesh_assimp(obj.string()));
  bool moved = false;
  for (const Vec3& p : again.mesh.positions) moved = moved || p.x == 2;
  EXPECT_TRUE(moved);
  ASSERT_TRUE(load_cached_mesh(cache.string(), obj.string()));  // rewritten for the new file
  expect_same(*load_cached_mesh(cache.string(), obj.string()), again);
}

// A mesh imported by other code (another build: its sources' hash in the header differs) is
// never read: the file is imported again and the cache rewritten by this code.
TEST_F(MeshCacheTest, AMeshImportedByOtherCodeIsImportedAgain) {
  const ImportedMesh direct = import_mesh_cached(obj.string(), nullptr, cache.string(), 0.0);
  const std::string path = cache_file();
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::size_t at = bytes.find(source_hash::kMeshImport);
  ASSERT_NE(at, std::string::npos) << "the header names the importer's code";
  std::string other = bytes;
  other[at] = other[at] == '0' ? '1' : '0';  // the same file, made by other code
  std::ofstream(path, std::ios::binary | std::ios::trunc) << other;
  EXPECT_FALSE(load_cached_mesh(cache.string(), obj.string()));
  expect_same(import_mesh_cached(obj.string(), nullptr, cache.string(), 0.0), direct);
  ASSERT_TRUE(load_cached_mesh(cache.string(), obj.string()));  // rewritten by this code
}

TEST_F(MeshCacheTest, ADamagedOrTruncatedCacheIsAMiss) {
  const ImportedMesh direct = import_mesh_cached(obj.string(), nullptr, cache.string(), 0.0);
  const std::string path = cache_file();
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ASSERT_GT(bytes.size(), 64u);
  for (std::size_t at : {std::size_t(3), bytes.size() / 2, bytes.size() - 1}) {
    std::string damaged = bytes;
    damaged[at] = char(damaged[at] ^ 0x20);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << damaged;
    EXPECT_FALSE(load_cached_mesh(cache.string(), obj.string())) << "byte " << at;
  }
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2);
  EXPECT_FALSE(load_cached_mesh(cache.string(), obj.string()));
  std::ofstream(path, std::ios::binary | std::ios::trunc) << "";
  EXPECT_FALSE(load_cached_mesh(cache.string(), obj.string()));
  // The import goes on as if nothing was cached, and replaces the damaged file.
  expect_same(import_mesh_cached(obj.string(), nullptr, cache.string(), 0.0), direct);
  ASSERT_TRUE(load_cached_mesh(cache.string(), obj.string()));
}

TEST_F(MeshCacheTest, NoCacheDirectoryImportsWithoutOne) {
  expect_same(import_mesh_cached(obj.string(), nullptr, "", 0.0), import_mesh_assimp(obj.string()));
  EXPECT_FALSE(fs::exists(cache));
  EXPECT_FALSE(load_cached_mesh("", obj.string()));
  EXPECT_FALSE(save_cached_mesh("", obj.string(), import_mesh_assimp(obj.string())));
}

TEST_F(MeshCacheTest, AMissingFileIsTheImportsError) {
  EXPECT_THROW(import_mesh_cached((dir / "missing.obj").string(), nullptr, cache.string(), 0.0), std::runtime_error);
  EXPECT_FALSE(fs::exists(cache));
}

TEST_F(MeshCacheTest, AHitReportsTheReadingStageAndStopsOnCtrlC) {
  import_mesh_cached(obj.string(), nullptr, cache.string(), 0.0);
  std::vector<std::pair<std::string, double>> calls;
  std::atomic<bool> cancel{false};
  LoadMonitor monitor;
  monitor.progress = [&](const std::string& stage, double f) { calls.emplace_back(stage, f); };
  monitor.cancel = &cancel;
  const ImportedMesh hit = import_mesh_cached(obj.string(), &monitor, cache.string(), 0.0);
  expect_same(hit, import_mesh_assimp(obj.string()));
  ASSERT_GE(calls.size(), 2u);
  EXPECT_EQ(calls.front(), std::make_pair(std::string("reading quad.obj"), 0.0));
  EXPECT_EQ(calls.back(), std::make_pair(std::string("reading quad.obj"), 1.0));
  // Cancelled at the stage's first report: Interrupted, as the import would be.
  monitor.progress = [&](const std::string&, double) { cancel = true; };
  EXPECT_THROW(import_mesh_cached(obj.string(), &monitor, cache.string(), 0.0), Interrupted);
}

TEST_F(MeshCacheTest, AnImportQuickerThanTheMinimumIsNotCached) {
  // No import takes a billion seconds (a threshold that no clock can make flaky).
  expect_same(import_mesh_cached(obj.string(), nullptr, cache.string(), 1e9), import_mesh_assimp(obj.string()));
  EXPECT_FALSE(fs::exists(cache_file()));
}

TEST_F(MeshCacheTest, SavingRemovesTheCachesOfFilesThatAreGone) {
  const fs::path other = dir / "other.obj";
  std::ofstream(other) << kObj;
  import_mesh_cached(other.string(), nullptr, cache.string(), 0.0);
  const std::string other_cache = mesh_cache_path(cache.string(), fs::canonical(other).string());
  ASSERT_TRUE(fs::exists(other_cache));
  std::ofstream(cache / "mesh-v1-notours.bin") << "not a cache file";
  fs::remove(other);
  import_mesh_cached(obj.string(), nullptr, cache.string(), 0.0);  // a save
  EXPECT_TRUE(fs::exists(cache_file()));
  EXPECT_FALSE(fs::exists(other_cache));
  EXPECT_FALSE(fs::exists(cache / "mesh-v1-notours.bin"));
}

}  // namespace
}  // namespace dermis
