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
// METHODS.md section 4) and its one-sample MIS with classical sampling are the policy
// GuidedSampling: it samples direction and distance jointly (which is why scatter()
// returns both) with the step math shared with the renderer's walk (walk/walk_step.h).
#pragma once

#include <cmath>
#include <limits>

#include "dermis/core/rng.h"
#include "dermis/core/vec.h"
#include "dermis/sss/walk/walk_step.h"

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

// WalkSampling (walk/walk_step.h) selects the policy: Classical -> ClassicalSampling,
// Dwivedi and Mis -> GuidedSampling with guided choice probability 1 or p_guided.

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
    const double cos_theta = sample_henyey_greenstein_cos(rng.uniform_double(), medium_.g);
    const double phi = 2 * kPiD * rng.uniform_double();
    Flight flight = fly(direction_about(direction_in, cos_theta, phi), depth, rng);
    flight.weight *= medium_.albedo;  // implicit capture: the absorbed fraction is tallied, not sampled
    return flight;
  }

 private:
  HalfspaceMedium medium_;
};

// Dwivedi-guided sampling (p_guided = 1) or its one-sample MIS with classical sampling
// (0 < p_guided < 1), principal axis the boundary normal +z: MixtureWalkStep<1> samples
// and weighs, this policy supplies the distance to the plane z = 0.
class GuidedSampling {
 public:
  GuidedSampling(const HalfspaceMedium& medium, double p_guided)
      : step_({medium.sigma_t}, {medium.albedo}, medium.g, p_guided) {}

  Flight fly(const Vec3d& direction, double depth, Rng& rng) const {
    return finish(step_.propose_flight(direction, axis_, kOneChannel, rng), depth);
  }

  Flight scatter(const Vec3d& direction_in, double depth, Rng& rng) const {
    return finish(step_.propose_scatter(direction_in, axis_, kOneChannel, rng), depth);
  }

 private:
  static constexpr std::array<double, 1> kOneChannel{1.0};

  Flight finish(const FlightProposal& p, double depth) const {
    const double boundary = distance_to_boundary(p.direction, depth);
    if (p.distance >= boundary)
      return {p.direction, boundary, step_.passage_weights(p, axis_, boundary, kOneChannel)[0], true};
    return {p.direction, p.distance, step_.collision_weights(p, axis_, kOneChannel)[0], false};
  }

  MixtureWalkStep<1> step_;
  GuideAxes<1> axis_{Framed(Vec3d{0, 0, 1})};  // outward normal of the boundary z = 0
};

}  // namespace dermis::sss
