// A float grid of a NanoVDB file (.nvdb), as pbrt-v4's "nanovdb" medium reads it: loaded with
// Debian's NanoVDB (libnanovdb-dev, header-only; ZIP-compressed files through zlib) and
// checked before anything follows its offsets (a corrupt file is an error, never a crash),
// sampled trilinearly in index space (NanoVDB's SampleFromVoxels of order 1), its box the
// grid's world box, and bounded cell by cell for a majorant grid. The NanoVDB headers stay in
// the .cpp.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "dermis/core/vec.h"

namespace dermis {

class NanoVdbGrid {
 public:
  // The float grid `name` of the file at `path`. Throws std::runtime_error whose message says
  // what is wrong (missing, not an .nvdb file, truncated, corrupt, no grid of that name (the
  // names it has), not a float fog volume, NaN or negative values). `optional`: null where the
  // file has no grid of that name.
  static std::shared_ptr<const NanoVdbGrid> load(const std::string& path, const std::string& name,
                                                 bool optional = false);
  ~NanoVdbGrid();

  // The grid's box in its world space (the medium's space): NanoVDB's worldBBox.
  Vec3 world_min() const;
  Vec3 world_max() const;
  // The trilinear value at a point of the world space (zero far from the active voxels).
  float value(Vec3 p) const;
  // At least the largest value a point of the world box [lo, hi] reads (every voxel whose
  // interpolation reaches into it, one voxel of margin), and at least 0.
  float max_over(Vec3 lo, Vec3 hi) const;
  // The bytes of the grid in memory (the file's, uncompressed).
  std::size_t bytes() const;

 private:
  struct Impl;
  explicit NanoVdbGrid(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace dermis
