#include "dermis/sss/pointcloud/illumination_detail.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "dermis/sss/pointcloud/point_grid.h"

namespace dermis::sss::pointcloud {

namespace {
constexpr float kSameSide = 0.7071f;  // cos 45 degrees between the normals
}  // namespace

double IlluminationDetail::relative_error() const { return std::sqrt(std::max(0.0, relative_squared_error)); }

IlluminationDetail illumination_detail(std::span<const SurfacePoint> points, std::span<const float> irradiance,
                                       std::span<const float> variance, int k) {
  const std::size_t n = points.size();
  if (irradiance.size() != n || variance.size() != n)
    throw std::invalid_argument("illumination_detail: one irradiance and one variance per point");
  if (k < 1 || k >= PointGrid::kMaxK)
    throw std::invalid_argument("illumination_detail: k must be in [1, " + std::to_string(PointGrid::kMaxK - 1) + "]");
  if (n < std::size_t(k) + 1)
    throw std::invalid_argument("illumination_detail: needs more than k points, got " + std::to_string(n));
  std::vector<Vec3> positions(n);
  double area = 0;
  for (std::size_t i = 0; i < n; ++i) {
    positions[i] = points[i].position;
    area += points[i].area;
  }
  // Cells of about k points on a surface, as the diffusion's own grid.
  double cell = std::sqrt(double(k) * area / double(n));
  if (!(cell > 0)) cell = 1.0;
  const PointGrid grid(positions, cell);

  IlluminationDetail d;
  for (std::size_t i = 0; i < n; ++i) d.mean_irradiance += irradiance[i];
  d.mean_irradiance /= double(n);
  std::vector<double> miss2(n, 0.0), noise(n, 0.0);
  std::size_t predicted_count = 0;
  std::vector<std::pair<uint32_t, double>> near;
  for (std::size_t p = 0; p < n; ++p) {
    // The k nearest others: the (k + 1)-th nearest point, counting p itself, bounds them.
    const double radius = grid.kth_nearest_distance(positions[p], k + 1);
    near.clear();
    // Only neighbours on the same side of a crease: across an edge of a box E changes with
    // the normal, which every point's own E carries exactly at any density.
    grid.for_each_within(positions[p], radius, [&](uint32_t j, double d2) {
      if (j != p && dot(points[j].normal, points[p].normal) >= kSameSide) near.emplace_back(j, std::sqrt(d2));
    });
    if (near.empty()) continue;  // a point alone on its facet: nothing predicts it
    predicted_count += 1;
    double wsum = 0, predicted = 0, w2var = 0;
    const double floor = 1e-6 * cell;  // coincident points: a large finite weight
    for (const auto& [j, dist] : near) wsum += 1.0 / std::max(dist, floor);
    for (const auto& [j, dist] : near) {
      const double w = 1.0 / std::max(dist, floor) / wsum;
      predicted += w * irradiance[j];
      w2var += w * w * variance[j];
    }
    const double miss = double(irradiance[p]) - predicted;
    miss2[p] = miss * miss;
    noise[p] = double(variance[p]) + w2var;  // Var(E_p - Ê_p): the estimates are independent
  }
  // Points with no prediction contribute 0 to both sums and are not counted.
  d.predicted = predicted_count;
  const double m = double(std::max<std::size_t>(predicted_count, 1));
  double q_sum = 0, q2_sum = 0;
  for (std::size_t p = 0; p < n; ++p) {
    d.mean_squared_miss += miss2[p] / m;
    d.noise += noise[p] / m;
  }
  if (!(d.mean_irradiance > 0) || predicted_count == 0) return d;  // no light: nothing to resolve
  const double scale = 1.0 / (d.mean_irradiance * d.mean_irradiance);
  for (std::size_t p = 0; p < n; ++p) {
    const double q = (miss2[p] - noise[p]) * scale;
    q_sum += q;
    q2_sum += q * q;
  }
  d.relative_squared_error = q_sum / m;
  const double spread = std::max(0.0, q2_sum / m - d.relative_squared_error * d.relative_squared_error);
  d.standard_error = std::sqrt(spread / m);
  return d;
}

std::size_t next_point_count(std::size_t current, double relative_error, double tolerance, std::size_t cap) {
  if (current >= cap || !(relative_error > tolerance)) return std::min(current, cap);
  const double growth = std::clamp((relative_error / tolerance) * (relative_error / tolerance), 2.0, 16.0);
  return std::size_t(std::min(double(cap), std::ceil(double(current) * growth)));
}

std::size_t pilot_point_count(std::size_t cap) { return std::min(cap, std::max<std::size_t>(1024, cap / 64)); }

}  // namespace dermis::sss::pointcloud
