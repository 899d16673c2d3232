// .nvdb files for tests (pbrt-v4's "nanovdb" media): a float fog-volume grid built from a
// function of the voxel, written with NanoVDB's own writer (header-only, libnanovdb-dev).
#pragma once

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridBuilder.h>
#include <nanovdb/util/IO.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace dermis::testing {

// One grid `name` over the voxels [0, n)^3, voxel (i, j, k) at world (i, j, k) * voxel + origin.
inline nanovdb::GridHandle<> nvdb_grid(const std::string& name, int n, double voxel, double origin,
                                       const std::function<float(int, int, int)>& value) {
  nanovdb::GridBuilder<float> builder(0.0f, nanovdb::GridClass::FogVolume);
  builder.setStats(nanovdb::StatsMode::All);
  builder.setChecksum(nanovdb::ChecksumMode::Full);
  builder([&](const nanovdb::Coord& c) { return value(c[0], c[1], c[2]); },
          nanovdb::CoordBBox(nanovdb::Coord(0), nanovdb::Coord(n - 1)));
  return builder.getHandle<nanovdb::AbsDiff, nanovdb::HostBuffer>(voxel, nanovdb::Vec3d(origin), name);
}

// The grids into one file (uncompressed).
inline void write_nvdb(const std::string& path, std::vector<nanovdb::GridHandle<>> grids) {
  nanovdb::io::writeGrids(path, grids);
}

}  // namespace dermis::testing
