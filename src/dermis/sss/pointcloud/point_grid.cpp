#include "dermis/sss/pointcloud/point_grid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace dermis::sss::pointcloud {

uint64_t PointGrid::key(int64_t ix, int64_t iy, int64_t iz) {
  // 21 bits per axis (two's complement, wrapped): collisions only merge far cells,
  // which the distance test then rejects.
  const uint64_t m = (1ull << 21) - 1;
  return (uint64_t(ix) & m) | ((uint64_t(iy) & m) << 21) | ((uint64_t(iz) & m) << 42);
}

PointGrid::PointGrid(std::span<const Vec3> positions, double cell_size) : cell_(cell_size) {
  if (!(cell_size > 0) || !std::isfinite(cell_size))
    throw std::invalid_argument("PointGrid: cell size must be positive and finite, got " + std::to_string(cell_size));
  const std::size_t n = positions.size();
  std::vector<uint64_t> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p = positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw std::invalid_argument("PointGrid: point " + std::to_string(i) + " is not finite");
    keys[i] = key(coord(p.x), coord(p.y), coord(p.z));
  }
  original_.resize(n);
  std::iota(original_.begin(), original_.end(), 0u);
  std::stable_sort(original_.begin(), original_.end(), [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
  positions_.resize(n);
  for (std::size_t i = 0; i < n; ++i) positions_[i] = positions[original_[i]];
  cells_.reserve(n / 2 + 1);
  for (uint32_t i = 0; i < n;) {
    uint32_t j = i;
    while (j < n && keys[original_[j]] == keys[original_[i]]) ++j;
    cells_.emplace(keys[original_[i]], Range{i, j});
    i = j;
  }
}

double PointGrid::kth_nearest_distance(Vec3 x, int k) const {
  if (k < 1 || k > kMaxK)
    throw std::invalid_argument("PointGrid::kth_nearest_distance: k must be in [1, " + std::to_string(kMaxK) +
                                "], got " + std::to_string(k));
  if (positions_.size() < std::size_t(k)) return std::numeric_limits<double>::infinity();
  // Grow a cube of cells (shell by shell) around x; once k points are known, the k-th
  // distance is final when it is no larger than the distance to the cube's boundary.
  std::array<double, kMaxK> heap;  // the k smallest squared distances so far, a max-heap
  std::size_t count = 0;
  const int64_t c[3] = {coord(x.x), coord(x.y), coord(x.z)};
  for (int64_t s = 0;; ++s) {
    for (int64_t ix = c[0] - s; ix <= c[0] + s; ++ix)
      for (int64_t iy = c[1] - s; iy <= c[1] + s; ++iy)
        for (int64_t iz = c[2] - s; iz <= c[2] + s; ++iz) {
          if (std::max({std::abs(ix - c[0]), std::abs(iy - c[1]), std::abs(iz - c[2])}) != s) continue;
          const Range* r = cell(ix, iy, iz);
          if (!r) continue;
          for (uint32_t i = r->begin; i < r->end; ++i) {
            const double d2 = length_squared(Vec3d(positions_[i] - x));
            if (count < std::size_t(k)) {
              heap[count++] = d2;
              std::push_heap(heap.begin(), heap.begin() + count);
            } else if (d2 < heap[0]) {
              std::pop_heap(heap.begin(), heap.begin() + count);
              heap[count - 1] = d2;
              std::push_heap(heap.begin(), heap.begin() + count);
            }
          }
        }
    if (count == std::size_t(k)) {
      // Distance from x to the outside of the (2s+1)^3 block: s whole cells plus x's offset.
      double reach = std::numeric_limits<double>::infinity();
      for (int a = 0; a < 3; ++a) {
        const double lo = double(c[a] - s) * cell_, hi = double(c[a] + s + 1) * cell_;
        reach = std::min({reach, double(x[a]) - lo, hi - double(x[a])});
      }
      if (heap[0] <= reach * reach) return std::sqrt(heap[0]);
    }
  }
}

std::size_t PointGrid::memory_bytes() const {
  return positions_.capacity() * sizeof(Vec3) + original_.capacity() * sizeof(uint32_t) +
         cells_.size() * (sizeof(uint64_t) + sizeof(Range) + 2 * sizeof(void*)) + cells_.bucket_count() * sizeof(void*);
}

}  // namespace dermis::sss::pointcloud
