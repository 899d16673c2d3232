// Sampling policies of the half-space random walk: how the next direction and flight
// distance are drawn, and the weight factor that keeps the estimator unbiased.
//
// The walk (halfspace.cpp) owns the geometry, the Fresnel boundary, Russian roulette
// and the tallies; a policy only samples. A policy P provides
//   Flight fly(const Vec3d& direction, double depth, Rng& rng) const;
//     a flight along a given direction (after entry, or after a Fresnel reflection);
//   Flight scatter(const Vec3d& direction_in, double depth, Rng& rng) const;
//     a scattering event at `depth` (>= 0 below z = 0): new direction and its flight.
// Flight::weight is (physical density) / (sampling density) of what was sampled,
// times the single-scattering albedo for a scattering event (implicit capture), so
// that the walk multiplies its path weight by it. The walk is templated on P: no
// virtual call per step. Dwivedi's zero-variance guiding (Krivanek & d'Eon 2014;
// METHODS.md section 4) and its one-sample MIS with classical sampling are further
// policies of this shape; they sample direction and distance jointly, which is why
// scatter() returns both.
#pragma once

#include <cmath>
#include <limits>

#include "dermis/core/rng.h"
#include "dermis/core/vec.h"
#include "dermis/sss/halfspace/hg_phase.h"

namespace dermis::sss {

// The medium below z = 0.
struct HalfspaceMedium {
  double albedo = 0.5;   // single-scattering albedo sigma_s / sigma_t
  double sigma_t = 1.0;  // extinction coefficient (1 / mean free path)
  double g = 0.0;        // Henyey-Greenstein anisotropy
};

// One straight flight. When reaches_boundary, distance is the distance to z = 0 and
// the walk meets the boundary there; otherwise the flight ends in a collision.
struct Flight {
  Vec3d direction;
  double distance = 0;
  double weight = 1;
  bool reaches_boundary = false;
};

// Distance along unit direction d from depth (>= 0 below z = 0) to the plane z = 0.
inline double distance_to_boundary(const Vec3d& d, double depth) {
  return d.z > 0 ? depth / d.z : std::numeric_limits<double>::infinity();
}

enum class WalkSampling {
  Classical,  // analog distances and phase-function directions (ClassicalSampling)
};

// Classical sampling: distance s = -ln(xi) / sigma_t (Beer-Lambert), direction from the
// HG phase function about the propagation direction (METHODS.md section 4). The
// sampled densities equal the physical ones, so only the albedo remains in the weight.
class ClassicalSampling {
 public:
  explicit ClassicalSampling(const HalfspaceMedium& medium) : medium_(medium) {}

  Flight fly(const Vec3d& direction, double depth, Rng& rng) const {
    // Free path -ln(1 - xi) / sigma_t with xi in [0, 1): finite (Beer-Lambert law).
    const double s = -std::log1p(-rng.uniform_double()) / medium_.sigma_t;
    const double boundary = distance_to_boundary(direction, depth);
    if (s >= boundary) return {direction, boundary, 1.0, true};
    return {direction, s, 1.0, false};
  }

  Flight scatter(const Vec3d& direction_in, double depth, Rng& rng) const {
    const double cos_theta = sample_hg_cos(rng.uniform_double(), medium_.g);
    const double phi = 2 * kPiD * rng.uniform_double();
    Flight flight = fly(direction_about(direction_in, cos_theta, phi), depth, rng);
    flight.weight *= medium_.albedo;  // implicit capture: the absorbed fraction is tallied, not sampled
    return flight;
  }

 private:
  HalfspaceMedium medium_;
};

}  // namespace dermis::sss
