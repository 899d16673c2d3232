// A hashed uniform grid over 3D points: fixed-radius neighbour visits and k-nearest
// neighbour distances, for the blue-noise thinning and the local disk radius.
#pragma once

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "dermis/core/vec.h"

namespace dermis::sss::pointcloud {

class PointGrid {
 public:
  PointGrid() = default;
  // cell_size > 0 (scene units); the grid keeps a copy of the positions.
  PointGrid(std::span<const Vec3> positions, double cell_size);

  // Calls f(index, squared_distance) for every point within `radius` of x (radius <=
  // cell_size visits at most 27 cells).
  template <class F>
  void for_each_within(Vec3 x, double radius, F&& f) const;

  static constexpr int kMaxK = 64;
  // Distance from x to its k-th nearest point (1 <= k <= kMaxK), counting a point at x itself;
  // +inf if the grid has fewer than k points.
  double kth_nearest_distance(Vec3 x, int k) const;

  std::size_t size() const { return positions_.size(); }
  double cell_size() const { return cell_; }
  std::size_t memory_bytes() const;

 private:
  struct Range {
    uint32_t begin, end;
  };
  static uint64_t key(int64_t ix, int64_t iy, int64_t iz);
  int64_t coord(float v) const { return int64_t(std::floor(double(v) / cell_)); }
  const Range* cell(int64_t ix, int64_t iy, int64_t iz) const {
    auto it = cells_.find(key(ix, iy, iz));
    return it == cells_.end() ? nullptr : &it->second;
  }

  double cell_ = 1;
  std::vector<Vec3> positions_;     // in cell order
  std::vector<uint32_t> original_;  // cell order -> caller's index
  std::unordered_map<uint64_t, Range> cells_;
};

template <class F>
void PointGrid::for_each_within(Vec3 x, double radius, F&& f) const {
  const double r2 = radius * radius;
  const int64_t lo[3] = {coord(float(x.x - radius)), coord(float(x.y - radius)), coord(float(x.z - radius))};
  const int64_t hi[3] = {coord(float(x.x + radius)), coord(float(x.y + radius)), coord(float(x.z + radius))};
  for (int64_t ix = lo[0]; ix <= hi[0]; ++ix)
    for (int64_t iy = lo[1]; iy <= hi[1]; ++iy)
      for (int64_t iz = lo[2]; iz <= hi[2]; ++iz) {
        const Range* c = cell(ix, iy, iz);
        if (!c) continue;
        for (uint32_t i = c->begin; i < c->end; ++i) {
          const double d2 = length_squared(Vec3d(positions_[i] - x));
          if (d2 <= r2) f(original_[i], d2);
        }
      }
}

}  // namespace dermis::sss::pointcloud
