// The volumetric random walk for the renderer's `subsurface` material, method
// `randomwalk` (Krivanek & d'Eon 2014; METHODS.md sections 4 and 5): from an entry
// point on a closed surface, walk through the homogeneous medium inside until a flight
// passes the boundary, with classical, Dwivedi-guided or MIS sampling and one-sample
// spectral MIS over the RGB channels. Geometry comes from a Tracer, so the same walk
// runs on meshes (the renderer) and analytic shapes (the tests). The per-step sampling
// and weights are MixtureWalkStep<3> (walk_step.h), shared with the half-space simulator.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "dermis/core/frame.h"
#include "dermis/core/rgb.h"
#include "dermis/core/rng.h"
#include "dermis/core/vec.h"
#include "dermis/sss/walk/walk_step.h"

namespace dermis::sss {

// Homogeneous medium, coefficients per scene unit (sigma_t >= sigma_s >= 0, sigma_t > 0).
struct WalkMedium {
  RGB sigma_s, sigma_t;
  float g = 0;  // Henyey-Greenstein anisotropy in (-1, 1)
};

struct WalkSettings {
  WalkSampling sampling = WalkSampling::Mis;
  // Guided choice probability for Mis (docs/random-walk.md: measured on the half-space
  // and on spheres). Higher values win on flat, thick media; on objects only a few mean
  // free paths across guiding toward the entry plane loses to classical sampling, least
  // so at 0.5, the compromise chosen.
  float p_guided = 0.5f;
  int max_steps = 1024;  // scattering events before the walk is stopped (truncated)
  // Russian roulette when the largest channel of the throughput drops below this.
  float roulette_threshold = 0.1f;
};

// The boundary seen from inside: the first hit of a ray, n the OUTWARD normal there.
struct BoundaryHit {
  bool hit = false;
  float t = 0;
  Vec3 p, n;
};

struct WalkResult {
  Vec3 exit_p, exit_n;      // where the walk met the boundary, outward normal there
  Vec3 exit_dir_in_medium;  // propagation direction of the last flight (pointing out)
  RGB weight;               // path throughput per channel; the caller applies Fresnel / the exit lobe
  int steps = 0;            // scattering events
  bool truncated = false;   // stopped at max_steps (the caller counts and reports these)
};

// Validated per-step sampler for a medium and settings; build it once per material
// (building it per walk costs a few Newton solves for nu0). Throws
// std::invalid_argument with an actionable message for bad coefficients or settings.
MixtureWalkStep<3> make_walk_step(const WalkMedium& medium, const WalkSettings& settings);

// Channel choice probabilities proportional to the throughput (METHODS.md section 5).
inline std::array<double, 3> channel_probabilities(const std::array<double, 3>& throughput) {
  const double sum = throughput[0] + throughput[1] + throughput[2];
  return {throughput[0] / sum, throughput[1] / sum, throughput[2] / sum};
}

// The walk (settings validated by make_walk_step). entry_n is the outward normal at entry_p (the principal axis of the
// guiding, as in the seed), dir_in the first propagation direction (into the medium).
// tracer(Vec3 origin, Vec3 unit_direction) -> BoundaryHit: the first boundary crossing
// with t > 0; for the first flight the origin lies on the boundary and the tracer must
// skip that surface (offset or ignore t ~ 0). Returns true when the walk left the
// medium (out filled); false when it was absorbed by Russian roulette, truncated
// (out.truncated) or lost (no boundary along an infinite flight). A caller that
// reflects the walk back at the boundary calls random_walk again from the exit point.
// `initial` is the throughput the walk starts with (a walk continued after an internal
// reflection passes what it has carried so far, so that the roulette and the channel
// choice see it); out.weight includes it.
template <class Tracer>
bool random_walk(const MixtureWalkStep<3>& step, const WalkSettings& settings, Vec3 entry_p, Vec3 entry_n,
                 Vec3 dir_in, Rng& rng, Tracer&& tracer, WalkResult& out, RGB initial = RGB(1.0f)) {
  out = WalkResult{};
  const Framed axis(normalize(Vec3d(entry_n)));
  const double roulette = settings.roulette_threshold;
  std::array<double, 3> throughput{initial[0], initial[1], initial[2]};
  if (!(throughput[0] + throughput[1] + throughput[2] > 0)) return false;
  Vec3d position(entry_p);
  std::array<double, 3> q = channel_probabilities(throughput);
  FlightProposal flight = step.propose_flight(normalize(Vec3d(dir_in)), axis, q, rng);
  for (int steps = 0;;) {
    const BoundaryHit hit = tracer(Vec3(position), Vec3(flight.direction));
    if (hit.hit && flight.distance >= double(hit.t)) {
      const std::array<double, 3> w = step.passage_weights(flight, double(hit.t), q);
      for (int c = 0; c < 3; ++c) out.weight[c] = float(throughput[c] * w[c]);
      out.exit_p = hit.p, out.exit_n = hit.n, out.exit_dir_in_medium = Vec3(flight.direction);
      out.steps = steps;
      return true;
    }
    if (!std::isfinite(flight.distance)) break;  // no boundary ahead of an endless flight: lost
    const std::array<double, 3> w = step.collision_weights(flight, q);
    for (int c = 0; c < 3; ++c) throughput[c] *= w[c];
    position += flight.direction * flight.distance;
    out.steps = steps;
    if (steps == settings.max_steps) {
      out.truncated = true;
      return false;
    }
    ++steps;
    // Russian roulette on the largest channel: survive with probability m / threshold (unbiased).
    const double m = std::max({throughput[0], throughput[1], throughput[2]});
    if (!(m > 0)) break;
    if (m < roulette) {
      if (rng.uniform_double() * roulette >= m) break;
      for (double& t : throughput) t *= roulette / m;
    }
    q = channel_probabilities(throughput);
    flight = step.propose_scatter(flight.direction, axis, q, rng);
  }
  return false;
}

template <class Tracer>
bool random_walk(const WalkMedium& medium, const WalkSettings& settings, Vec3 entry_p, Vec3 entry_n, Vec3 dir_in,
                 Rng& rng, Tracer&& tracer, WalkResult& out) {
  return random_walk(make_walk_step(medium, settings), settings, entry_p, entry_n, dir_in, rng,
                     std::forward<Tracer>(tracer), out);
}

}  // namespace dermis::sss
