// What the renderer calls for point-cloud diffusion (METHODS 3): a cloud of surface
// points with their irradiance, the octree of Jensen & Buehler 2002 over it, and
// optionally the local disk integral of Langlands & Mertens (seed 001).
//
//   auto points = distribute_points(positions, indices, count, seed);
//   std::vector<RGB> E(points.size());  // E[i] = irradiance entering at points[i]
//   PointCloudDiffusion diffusion(points, E, make_dipole_rgb(A, mfp, eta), {});
//   RGB M = diffusion.radiant_exitance(x, E_at_x);    // then L = Sw(wo) M (METHODS 0)
#pragma once

#include <chrono>
#include <span>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/sss/pointcloud/irradiance_octree.h"
#include "dermis/sss/pointcloud/local_disk.h"
#include "dermis/sss/pointcloud/point_distribution.h"
#include "dermis/sss/pointcloud/point_grid.h"
#include "dermis/sss/profiles/profile.h"

namespace dermis::sss::pointcloud {

struct DiffusionOptions {
  double epsilon = 0.05;     // solid-angle threshold of the octree (Jensen & Buehler 2002)
  bool local_disk = true;    // "localdisk": off = the plain octree sum
  int k_nearest = 10;        // alpha = alpha_scale x distance to the k-th nearest point
  double alpha_scale = 1.0;  // (Langlands & Mertens: k = 10, alpha proportional to it)
  OctreeOptions octree;
  int table_entries = LocalDiskTable::kDefaultEntries;
};

struct DiffusionStats {
  std::size_t point_count = 0;
  std::size_t octree_nodes = 0;
  std::size_t memory_bytes = 0;  // octree + kNN grid + local disk tables
  double build_seconds = 0;      // octree, grid and tables
};

class PointCloudDiffusion {
 public:
  // Throws std::invalid_argument on a bad cloud (see IrradianceOctree) or options.
  PointCloudDiffusion(std::span<const SurfacePoint> points, std::span<const RGB> irradiance, ProfileRGB profile,
                      DiffusionOptions options = {});

  // M(x): with the local disk, 2 pi E(x) int_0^alpha w R r dr + sum wbar R E_p A_p
  // (Langlands & Mertens); without it, sum R E_p A_p. irradiance_at_x = E(x), computed
  // by the caller at the shading point (unused without the local disk).
  RGB radiant_exitance(Vec3 x, RGB irradiance_at_x) const;
  // The same with the profile of the shading point x instead of the cloud's (textured
  // parameters: every cloud point's E_p A_p is spread with x's profile; the local term
  // by quadrature, local_albedo_of). Allocates nothing.
  RGB radiant_exitance(Vec3 x, RGB irradiance_at_x, const ProfileRGB& profile_at_x) const;
  // The plain octree sum at any epsilon, and the exact sum (references for tests).
  RGB octree_sum(Vec3 x, double epsilon) const { return octree_.query(x, profile_, epsilon); }
  RGB brute_force(Vec3 x) const { return octree_.brute_force(x, profile_); }

  // The local disk radius at x: alpha_scale x distance to the k-th nearest point.
  double disk_radius(Vec3 x) const;

  const DiffusionOptions& options() const { return options_; }
  const DiffusionStats& stats() const { return stats_; }
  const IrradianceOctree& octree() const { return octree_; }

 private:
  std::chrono::steady_clock::time_point build_start_ = std::chrono::steady_clock::now();  // first member
  DiffusionOptions options_;
  ProfileRGB profile_;
  IrradianceOctree octree_;
  PointGrid grid_;
  LocalDiskTableRGB tables_;
  DiffusionStats stats_;
};

}  // namespace dermis::sss::pointcloud
