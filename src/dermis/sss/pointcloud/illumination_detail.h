// How finely a cloud must sample the illumination (Langlands & Mertens, seed 001): with
// the local disk integral the cloud only has to represent the incident irradiance E, not
// the steep falloff of R_d, so its point count is chosen from the illumination's detail.
// The detail is measured by leave-one-out prediction: each point's E predicted from its
// nearest neighbours; the mean squared miss, less the Monte Carlo noise of the irradiance
// estimates, relative to the mean E, is how badly a cloud this dense represents E.
#pragma once

#include <cstddef>
#include <span>

#include "dermis/sss/pointcloud/point_distribution.h"

namespace dermis::sss::pointcloud {

struct IlluminationDetail {
  double mean_irradiance = 0;    // mean E over the points (the scale of the error)
  double mean_squared_miss = 0;  // mean (E_p - Ê_p)^2, noise included
  double noise = 0;              // mean Var(E_p - Ê_p) of the estimates (their own noise)
  // (mean_squared_miss - noise) / mean_irradiance^2: unbiased, may be negative by noise.
  double relative_squared_error = 0;
  double standard_error = 0;  // of relative_squared_error, from the spread of the misses
  std::size_t predicted = 0;  // points with a neighbour on their side of any crease
  // sqrt(max(0, relative_squared_error)); 0 when the object receives no light.
  double relative_error() const;
};

// Ê_p = sum_i w_i E_i over the k nearest other points whose normal is within 45 degrees of
// p's (not across a crease, where E changes with the normal: each point carries its own
// exactly), w_i proportional to 1/d_i (a mean that leans on the closest). Points with no
// such neighbour are left out of the means. `irradiance` is one value per point (e.g. luminance);
// `variance` the variance of each value's Monte Carlo estimate (0 for exact values).
// Throws std::invalid_argument on mismatched sizes, fewer than k + 1 points, k out of
// [1, PointGrid::kMaxK - 1].
IlluminationDetail illumination_detail(std::span<const SurfacePoint> points, std::span<const float> irradiance,
                                       std::span<const float> variance, int k = 8);

// The next point count of the refinement: the miss of a nearest-neighbour prediction
// falls like the spacing h ~ N^-1/2 where E is smooth (a gradient across h) and slower at
// shadow edges, so the count grows by (error / tolerance)^2, at least 2x and at most 16x
// a round, never beyond `cap`. Returns `current` when the error is within the tolerance
// or the count is at the cap.
std::size_t next_point_count(std::size_t current, double relative_error, double tolerance, std::size_t cap);

// The first (pilot) cloud's count: a 64th of the cap, at least 1024 (never above the cap).
std::size_t pilot_point_count(std::size_t cap);

}  // namespace dermis::sss::pointcloud
