// Values sampled on a regular grid over the unit cube and read with trilinear interpolation,
// as pbrt-v4's SampledGrid reads a grid medium's values: sample (x, y, z) of an nx x ny x nz
// grid sits at ((x + 1/2) / nx, (y + 1/2) / ny, (z + 1/2) / nz), x varying fastest in
// `values`, and a sample outside the grid reads as zero (the value fades to zero over the
// outer half-cell).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "dermis/core/vec.h"

namespace dermis {

template <class T>
struct VoxelGrid {
  int nx = 0, ny = 0, nz = 0;
  std::vector<T> values;  // nx * ny * nz, x fastest, then y, then z

  bool empty() const { return values.empty(); }

  // Sample (x, y, z), or T{} (zero) outside the grid.
  const T& sample(int x, int y, int z) const {
    static const T zero{};
    if (x < 0 || y < 0 || z < 0 || x >= nx || y >= ny || z >= nz) return zero;
    return values[(std::size_t(z) * std::size_t(ny) + std::size_t(y)) * std::size_t(nx) + std::size_t(x)];
  }

  // The value at p in [0, 1]^3, each sample read through convert (a sample's value at a
  // path's wavelengths, say): trilinear interpolation between the eight samples around p.
  template <class F>
  auto lookup(Vec3 p, F convert) const {
    const float sx = p.x * float(nx) - 0.5f, sy = p.y * float(ny) - 0.5f, sz = p.z * float(nz) - 0.5f;
    const int x = int(std::floor(sx)), y = int(std::floor(sy)), z = int(std::floor(sz));
    const float dx = sx - float(x), dy = sy - float(y), dz = sz - float(z);
    auto at = [&](int i, int j, int k) { return convert(sample(x + i, y + j, z + k)); };
    auto lerp = [](float t, auto a, auto b) { return a * (1 - t) + b * t; };
    const auto d00 = lerp(dx, at(0, 0, 0), at(1, 0, 0)), d10 = lerp(dx, at(0, 1, 0), at(1, 1, 0));
    const auto d01 = lerp(dx, at(0, 0, 1), at(1, 0, 1)), d11 = lerp(dx, at(0, 1, 1), at(1, 1, 1));
    return lerp(dz, lerp(dy, d00, d10), lerp(dy, d01, d11));
  }
  T lookup(Vec3 p) const {
    return lookup(p, [](const T& v) { return v; });
  }

  // The largest of value(sample) over the samples whose interpolation reaches into the box
  // [lo, hi] of the unit cube: a bound on what lookup() returns in that box when every
  // value is at least zero (the zeros outside the grid can only lower it).
  template <class F>
  auto max_over(Vec3 lo, Vec3 hi, F value) const {
    const int res[3] = {nx, ny, nz};
    int first[3], last[3];
    for (int a = 0; a < 3; ++a) {
      first[a] = int(std::floor(lo[a] * float(res[a]) - 0.5f));
      last[a] = int(std::floor(hi[a] * float(res[a]) - 0.5f)) + 1;
      first[a] = std::clamp(first[a], 0, res[a] - 1);
      last[a] = std::clamp(last[a], 0, res[a] - 1);
    }
    auto best = value(sample(first[0], first[1], first[2]));
    for (int z = first[2]; z <= last[2]; ++z)
      for (int y = first[1]; y <= last[1]; ++y)
        for (int x = first[0]; x <= last[0]; ++x) best = std::max(best, value(sample(x, y, z)));
    return best;
  }
};

}  // namespace dermis
