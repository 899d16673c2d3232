#include "dermis/sss/pointcloud/point_distribution.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dermis/core/rng.h"
#include "dermis/sss/pointcloud/point_grid.h"

namespace dermis::sss::pointcloud {
namespace {

void validate_mesh(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices) {
  if (indices.empty() || indices.size() % 3 != 0)
    throw std::invalid_argument("distribute_points: the index list must hold three indices per triangle (got " +
                                std::to_string(indices.size()) + ")");
  for (std::size_t i = 0; i < indices.size(); ++i)
    if (indices[i] >= positions.size())
      throw std::invalid_argument("distribute_points: index " + std::to_string(indices[i]) + " at position " +
                                  std::to_string(i) + " is out of range (" + std::to_string(positions.size()) +
                                  " vertices)");
}

double triangle_area(Vec3d a, Vec3d b, Vec3d c) { return 0.5 * length(cross(b - a, c - a)); }

// Area-uniform candidates: triangle by its area, then uniform barycentrics by the
// square-root warp (Osada et al. 2002, "Shape distributions", eq. 1).
std::vector<SurfacePoint> sample_candidates(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices,
                                            std::size_t n, uint64_t seed, double* total_area) {
  const std::size_t triangles = indices.size() / 3;
  std::vector<double> cdf(triangles);
  double sum = 0;
  for (std::size_t t = 0; t < triangles; ++t) {
    sum += triangle_area(Vec3d(positions[indices[3 * t]]), Vec3d(positions[indices[3 * t + 1]]),
                         Vec3d(positions[indices[3 * t + 2]]));
    cdf[t] = sum;
  }
  if (!(sum > 0) || !std::isfinite(sum))
    throw std::invalid_argument("distribute_points: the mesh has no area (or a non-finite vertex)");
  *total_area = sum;
  std::vector<SurfacePoint> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    Rng rng(seed, 0x9017c10d, i);
    const double u = rng.uniform_double() * sum;
    std::size_t t = std::size_t(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin());
    t = std::min(t, triangles - 1);
    while (t > 0 && cdf[t] == cdf[t - 1]) --t;  // never a zero-area triangle
    const Vec3d a(positions[indices[3 * t]]), b(positions[indices[3 * t + 1]]), c(positions[indices[3 * t + 2]]);
    const double s = std::sqrt(rng.uniform_double()), v = rng.uniform_double();
    const double b0 = 1 - s, b1 = s * (1 - v), b2 = s * v;
    out[i].position = Vec3(a * b0 + b * b1 + c * b2);
    out[i].normal = Vec3(normalize(cross(b - a, c - a)));
    out[i].triangle = uint32_t(t);
  }
  return out;
}

// An indexed binary max-heap of (weight, index), ties broken by the smaller index, so
// that the elimination order is deterministic.
class EliminationHeap {
 public:
  explicit EliminationHeap(const std::vector<double>& weight) : w_(weight), heap_(weight.size()), pos_(weight.size()) {
    for (uint32_t i = 0; i < heap_.size(); ++i) heap_[i] = pos_[i] = i;
    for (std::size_t i = heap_.size() / 2; i-- > 0;) down(i);
  }
  uint32_t pop() {
    const uint32_t top = heap_[0];
    swap(0, heap_.size() - 1);
    heap_.pop_back();
    if (!heap_.empty()) down(0);
    pos_[top] = kRemoved;
    return top;
  }
  bool contains(uint32_t i) const { return pos_[i] != kRemoved; }
  void decrease(uint32_t i, double dw) {
    w_[i] -= dw;
    down(pos_[i]);
  }

 private:
  static constexpr uint32_t kRemoved = ~0u;
  bool above(uint32_t a, uint32_t b) const { return w_[a] > w_[b] || (w_[a] == w_[b] && a < b); }
  void swap(std::size_t a, std::size_t b) {
    std::swap(heap_[a], heap_[b]);
    pos_[heap_[a]] = uint32_t(a);
    pos_[heap_[b]] = uint32_t(b);
  }
  void down(std::size_t i) {
    for (;;) {
      std::size_t best = i;
      for (std::size_t c = 2 * i + 1; c <= 2 * i + 2 && c < heap_.size(); ++c)
        if (above(heap_[c], heap_[best])) best = c;
      if (best == i) return;
      swap(i, best);
      i = best;
    }
  }
  std::vector<double> w_;
  std::vector<uint32_t> heap_, pos_;
};

// Sorts points along a Morton curve of their bounding box, so that neighbours are close
// in memory during elimination (a stable sort: the order stays deterministic).
void spatial_order(std::vector<SurfacePoint>& points) {
  Vec3 lo = points[0].position, hi = lo;
  for (const auto& p : points) {
    lo = min(lo, p.position);
    hi = max(hi, p.position);
  }
  const float scale = 1048575.0f / std::max(max_component(hi - lo), 1e-30f);
  auto spread = [](uint64_t v) {  // 20 bits -> every third bit
    uint64_t x = v & 0xfffff;
    x = (x | x << 32) & 0x1f00000000ffffull;
    x = (x | x << 16) & 0x1f0000ff0000ffull;
    x = (x | x << 8) & 0x100f00f00f00f00full;
    x = (x | x << 4) & 0x10c30c30c30c30c3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
  };
  std::vector<std::pair<uint64_t, uint32_t>> keys(points.size());
  for (uint32_t i = 0; i < points.size(); ++i) {
    const Vec3 q = (points[i].position - lo) * scale;
    keys[i] = {spread(uint64_t(q.x)) | spread(uint64_t(q.y)) << 1 | spread(uint64_t(q.z)) << 2, i};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<SurfacePoint> sorted(points.size());
  for (std::size_t i = 0; i < keys.size(); ++i) sorted[i] = points[keys[i].second];
  points = std::move(sorted);
}

}  // namespace

double mesh_area(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices) {
  validate_mesh(positions, indices);
  double sum = 0;
  for (std::size_t t = 0; t < indices.size(); t += 3)
    sum +=
        triangle_area(Vec3d(positions[indices[t]]), Vec3d(positions[indices[t + 1]]), Vec3d(positions[indices[t + 2]]));
  return sum;
}

double point_count_for_density(double area, double mean_free_path, double points_per_mfp2) {
  if (!(area > 0) || !(mean_free_path > 0) || !(points_per_mfp2 > 0))
    throw std::invalid_argument(
        "point cloud: the object's area, its mean free path and \"pointdensity\" must be "
        "positive");
  return std::max(1.0, std::ceil(area * points_per_mfp2 / (mean_free_path * mean_free_path)));
}

std::vector<SurfacePoint> uniform_random_points(const std::vector<Vec3>& positions,
                                                const std::vector<uint32_t>& indices, std::size_t count,
                                                uint64_t seed) {
  validate_mesh(positions, indices);
  if (count == 0) throw std::invalid_argument("uniform_random_points: count must be positive");
  double area = 0;
  auto points = sample_candidates(positions, indices, count, seed, &area);
  for (auto& p : points) p.area = float(area / double(count));
  return points;
}

std::size_t distribution_steps(std::size_t count, const DistributionOptions& options) {
  const std::size_t m = count * std::size_t(std::max(options.candidates_per_point, 1));
  return m + m + (m - count);
}

std::vector<SurfacePoint> distribute_points(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices,
                                            std::size_t count, uint64_t seed, DistributionOptions options) {
  validate_mesh(positions, indices);
  if (count == 0) throw std::invalid_argument("distribute_points: count must be positive");
  if (options.candidates_per_point < 1)
    throw std::invalid_argument("distribute_points: candidates_per_point must be >= 1");
  const std::size_t m = count * std::size_t(options.candidates_per_point);
  // Progress every 4096 steps of the weighing and elimination loops (a call, not a draw).
  std::size_t done = 0;
  auto step = [&](std::size_t i) {
    if (options.progress && (i & 4095) == 4095) options.progress(done + i + 1);
  };
  double area = 0;
  std::vector<SurfacePoint> cand = sample_candidates(positions, indices, m, seed, &area);
  spatial_order(cand);
  done = m;
  if (options.progress) options.progress(done);
  if (m > count) {
    // Yuksel 2015, eq. 5 (2D sampling domain): r_max = sqrt(A / (2 sqrt(3) N)).
    const double r_max = std::sqrt(area / (2 * std::sqrt(3.0) * double(count)));
    // Yuksel 2015, sec. 3.3: r_min = r_max (1 - (N/M)^gamma) beta, gamma = 1.5, beta = 0.65.
    const double r_min = r_max * (1 - std::pow(double(count) / double(m), 1.5)) * 0.65;
    const double reach = 2 * r_max;
    // Yuksel 2015, eq. 2 with the r_min clamp: w(d) = (1 - max(d, 2 r_min) / (2 r_max))^8.
    auto weight = [&](double d2) {
      const double d = std::max(std::sqrt(d2), 2 * r_min);
      const double t2 = sqr(1 - d / reach), t4 = t2 * t2;
      return t4 * t4;
    };
    std::vector<Vec3> pos(m);
    for (std::size_t i = 0; i < m; ++i) pos[i] = cand[i].position;
    const PointGrid grid(pos, reach);
    std::vector<double> w(m, 0.0);
    for (uint32_t i = 0; i < m; ++i) {
      grid.for_each_within(pos[i], reach, [&](uint32_t j, double d2) {
        if (j != i) w[i] += weight(d2);
      });
      step(i);
    }
    done += m;
    EliminationHeap heap(w);
    for (std::size_t removed = 0; removed < m - count; ++removed) {
      step(removed);
      const uint32_t i = heap.pop();
      grid.for_each_within(pos[i], reach, [&](uint32_t j, double d2) {
        if (j != i && heap.contains(j)) heap.decrease(j, weight(d2));
      });
    }
    std::vector<SurfacePoint> kept;
    kept.reserve(count);
    for (uint32_t i = 0; i < m; ++i)
      if (heap.contains(i)) kept.push_back(cand[i]);
    cand = std::move(kept);
  }
  for (auto& p : cand) p.area = float(area / double(count));
  if (options.progress) options.progress(distribution_steps(count, options));
  return cand;
}

}  // namespace dermis::sss::pointcloud
