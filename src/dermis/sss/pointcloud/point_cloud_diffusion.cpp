#include "dermis/sss/pointcloud/point_cloud_diffusion.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dermis::sss::pointcloud {
namespace {

std::vector<Vec3> positions_of(std::span<const SurfacePoint> points) {
  std::vector<Vec3> p(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) p[i] = points[i].position;
  return p;
}

const DiffusionOptions& validated(const DiffusionOptions& o) {
  if (!(o.epsilon >= 0) || !std::isfinite(o.epsilon))
    throw std::invalid_argument("point cloud diffusion: epsilon must be finite and >= 0");
  if (o.k_nearest < 1 || o.k_nearest > PointGrid::kMaxK)
    throw std::invalid_argument("point cloud diffusion: k_nearest must be in [1, " + std::to_string(PointGrid::kMaxK) +
                                "]");
  if (!(o.alpha_scale > 0) || !std::isfinite(o.alpha_scale))
    throw std::invalid_argument("point cloud diffusion: alpha_scale must be positive");
  return o;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

PointCloudDiffusion::PointCloudDiffusion(std::span<const SurfacePoint> points, std::span<const RGB> irradiance,
                                         ProfileRGB profile, DiffusionOptions options)
    : options_(validated(options)),
      profile_(std::move(profile)),
      octree_(points, irradiance, options.octree),
      tables_(profile_, options.table_entries) {
  // Cells of about k points on a surface: side sqrt(k x mean point area).
  const double mean_area = octree_.total_area() / double(points.size());
  double cell = std::sqrt(double(options.k_nearest) * mean_area);
  if (!(cell > 0)) cell = 1.0;
  grid_ = PointGrid(positions_of(points), cell);
  stats_.build_seconds = seconds_since(build_start_);
  stats_.point_count = octree_.point_count();
  stats_.octree_nodes = octree_.node_count();
  stats_.memory_bytes = octree_.memory_bytes() + grid_.memory_bytes() + tables_.memory_bytes();
}

double PointCloudDiffusion::disk_radius(Vec3 x) const {
  return options_.alpha_scale * grid_.kth_nearest_distance(x, options_.k_nearest);
}

RGB PointCloudDiffusion::radiant_exitance(Vec3 x, RGB irradiance_at_x) const {
  if (!options_.local_disk) return octree_.query(x, profile_, options_.epsilon);
  double alpha = disk_radius(x);
  if (!std::isfinite(alpha)) alpha = 0;  // fewer than k points: no disk
  // Langlands & Mertens (seed 001): local term with E(x) + octree sum weighted by wbar.
  return tables_.local_term(irradiance_at_x, alpha) + octree_.query_outside_disk(x, profile_, options_.epsilon, alpha);
}

RGB PointCloudDiffusion::radiant_exitance(Vec3 x, RGB irradiance_at_x, const ProfileRGB& profile_at_x) const {
  if (!options_.local_disk) return octree_.query(x, profile_at_x, options_.epsilon);
  double alpha = disk_radius(x);
  if (!std::isfinite(alpha)) alpha = 0;  // fewer than k points: no disk
  RGB local;
  for (int c = 0; c < 3; ++c) local[c] = float(irradiance_at_x[c] * local_albedo_of(profile_at_x[c], alpha));
  return local + octree_.query_outside_disk(x, profile_at_x, options_.epsilon, alpha);
}

}  // namespace dermis::sss::pointcloud
