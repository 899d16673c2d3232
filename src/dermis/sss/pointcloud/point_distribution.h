// Points over a triangle mesh for point-cloud diffusion (METHODS 3, pre-pass):
// area-uniform candidates thinned to blue noise by weighted sample elimination
// (Yuksel 2015, "Sample Elimination for Generating Poisson Disk Sample Sets").
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "dermis/core/vec.h"

namespace dermis::sss::pointcloud {

struct SurfacePoint {
  Vec3 position;
  Vec3 normal;     // the unit geometric normal of the triangle it lies on
  float area = 0;  // A_p: the mesh area divided by the point count (equal shares)
  uint32_t triangle = 0;
};

// Total area of the triangles (indices: three per triangle into positions).
double mesh_area(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices);

// The number of points a density given as points per mean free path squared asks for:
// ceil(area * points_per_mfp2 / mfp^2), at least 1 (a double: it may exceed any budget,
// which the caller applies).
double point_count_for_density(double area, double mean_free_path, double points_per_mfp2);

struct DistributionOptions {
  int candidates_per_point = 5;  // candidates = this x count (Yuksel uses 5)
  // Called now and then (every few thousand steps, from the calling thread) with the steps
  // done of distribution_steps(count, ...): for a progress display. It may throw to stop the
  // distribution (Ctrl-C); the exception leaves distribute_points as it is.
  std::function<void(std::size_t done)> progress;
};

// The steps distribute_points reports through DistributionOptions::progress: each candidate
// drawn, weighed and (for all but `count`) eliminated.
std::size_t distribution_steps(std::size_t count, const DistributionOptions& options = {});

// `count` points over the mesh, blue-noise distributed; deterministic for a seed.
// Degenerate (zero-area) triangles receive no points. Throws std::invalid_argument on an
// empty or zero-area mesh, indices out of range or not a multiple of three, count 0.
std::vector<SurfacePoint> distribute_points(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices,
                                            std::size_t count, uint64_t seed, DistributionOptions options = {});

// Area-uniform points with no thinning (white noise): the baseline of the blue-noise test.
std::vector<SurfacePoint> uniform_random_points(const std::vector<Vec3>& positions,
                                                const std::vector<uint32_t>& indices, std::size_t count, uint64_t seed);

}  // namespace dermis::sss::pointcloud
