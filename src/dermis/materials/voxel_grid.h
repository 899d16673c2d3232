// Values sampled on a regular grid over the unit cube and read with trilinear interpolation,
// as pbrt-v4's SampledGrid reads a grid medium's values: sample (x, y, z) of an nx x ny x nz
// grid sits at ((x + 1/2) / nx, (y + 1/2) / ny, (z + 1/2) / nz), x varying fastest in
// the values, and a sample outside the grid reads as zero (the value fades to zero over the
// outer half-cell). T is float (one float per sample) or RGB (three), read from a FloatArray
// shared with the scene's description: the grid's values exist once.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "dermis/core/float_array.h"
#include "dermis/core/rgb.h"
#include "dermis/core/vec.h"

namespace dermis {

template <class T>
class VoxelGrid {
  static_assert(std::is_same_v<T, float> || std::is_same_v<T, RGB>, "a grid of floats or of colours");
  static_assert(sizeof(RGB) == 3 * sizeof(float), "a colour is its three floats");

 public:
  static constexpr std::size_t kFloatsPerSample = sizeof(T) / sizeof(float);  // float: 1, RGB: 3

  int nx = 0, ny = 0, nz = 0;

  VoxelGrid() = default;
  // nx * ny * nz samples of kFloatsPerSample floats each, x fastest, then y, then z (null or
  // empty: an empty grid). std::invalid_argument when the count differs.
  VoxelGrid(int nx, int ny, int nz, std::shared_ptr<const FloatArray> values)
      : nx(nx), ny(ny), nz(nz), values_(std::move(values)), data_(values_ ? values_->data() : nullptr) {
    if (!empty() && (nx < 1 || ny < 1 || nz < 1 ||
                     values_->size() != std::size_t(nx) * std::size_t(ny) * std::size_t(nz) * kFloatsPerSample))
      throw std::invalid_argument("VoxelGrid: the values are not nx * ny * nz samples");
  }

  bool empty() const { return !values_ || values_->empty(); }
  const std::shared_ptr<const FloatArray>& values() const { return values_; }

  // Sample (x, y, z), or T{} (zero) outside the grid: a plain read through the cached pointer.
  T sample(int x, int y, int z) const {
    if (x < 0 || y < 0 || z < 0 || x >= nx || y >= ny || z >= nz) return T{};
    const float* v = data_ + ((std::size_t(z) * std::size_t(ny) + std::size_t(y)) * std::size_t(nx) + std::size_t(x)) *
                                 kFloatsPerSample;
    if constexpr (kFloatsPerSample == 1)
      return *v;
    else
      return T(v[0], v[1], v[2]);
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
    return lookup(p, [](T v) { return v; });
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

  // Whether lookup() reads one value all over the box [lo, hi] of the unit cube, and which:
  // every sample whose interpolation reaches into the box holds it, and none of them lies
  // outside the grid (whose zeros would enter).
  bool uniform_over(Vec3 lo, Vec3 hi, T& value) const {
    const int res[3] = {nx, ny, nz};
    int first[3], last[3];
    for (int a = 0; a < 3; ++a) {
      first[a] = int(std::floor(lo[a] * float(res[a]) - 0.5f));
      last[a] = int(std::floor(hi[a] * float(res[a]) - 0.5f)) + 1;
      if (first[a] < 0 || last[a] > res[a] - 1) return false;
    }
    value = sample(first[0], first[1], first[2]);
    for (int z = first[2]; z <= last[2]; ++z)
      for (int y = first[1]; y <= last[1]; ++y)
        for (int x = first[0]; x <= last[0]; ++x)
          if (!(sample(x, y, z) == value)) return false;
    return true;
  }

 private:
  std::shared_ptr<const FloatArray> values_;
  const float* data_ = nullptr;  // values_->data(), cached: sample() is on the render's hot path
};

}  // namespace dermis
