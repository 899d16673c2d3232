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
#include <limits>
#include <utility>

#include "dermis/core/frame.h"
#include "dermis/core/rgb.h"
#include "dermis/core/rng.h"
#include "dermis/core/vec.h"
#include "dermis/sss/walk/boundary_hit.h"
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
  // Backward guiding (walk_step.h GuideAxes): guided flights also follow the importance
  // of the object's far side below the entry point, found by one ray against the entry
  // normal; the share of each side follows the depths (MixtureWalkStep::back_shares).
  bool backward_guiding = false;
  // Scattering events before the walk is stopped (truncated: its energy is lost, counted
  // and reported). A walk in a medium whose single-scattering albedo is near 1 lives
  // thousands of steps before its throughput reaches the roulette threshold; a cap of
  // 1024 truncated such walks on a wax sphere, 8192 none, for the same variance and time
  // (docs/random-walk.md).
  int max_steps = 8192;
  // Russian roulette when the largest channel of the throughput drops below this.
  float roulette_threshold = 0.1f;
  // The exponent k of the channel choice, throughput_c (1 - albedo_c)^-k
  // (MixtureWalkStep::channel_probabilities); 0: in proportion to the throughput.
  float channel_preference = 0.5f;
};

struct WalkResult {
  Vec3 exit_p, exit_n;      // where the walk met the boundary, outward normal there
  Vec3 exit_dir_in_medium;  // propagation direction of the last flight (pointing out)
  RGB weight;               // path throughput per channel; the caller applies Fresnel / the exit lobe
  int steps = 0;            // scattering events
  bool truncated = false;   // stopped at max_steps (the caller counts and reports these)
  // The last flight started at a scattering event of this walk (not where it started):
  // that event's position and the propagation direction it scattered from.
  bool from_collision = false;
  Vec3 last_collision, last_incoming;
};

// A walk's caller may act at every scattering event (after its weights and the roulette,
// before the next direction is drawn): on_collision(position, incoming propagation
// direction, throughput per channel). This one does nothing.
struct NoCollisionHook {
  void operator()(const Vec3d&, const Vec3d&, const std::array<double, 3>&) const {}
};

// Validated per-step sampler for a medium and settings; build it once per material
// (building it per walk costs a few Newton solves for nu0). Throws
// std::invalid_argument with an actionable message for bad coefficients or settings.
MixtureWalkStep<3> make_walk_step(const WalkMedium& medium, const WalkSettings& settings);

// Where a walk's guided flights point: the seed's principal axis, the outward normal at
// the entry point, and for backward guiding the far side below it (where a ray from the
// entry point against the entry normal leaves the medium, outward normal there).
struct WalkGuide {
  Vec3d entry_p, entry_n;
  bool has_far = false;
  Vec3d far_p, far_n;
};

// The guide of a walk from entry_p (outward normal entry_n). With backward guiding (and a
// guided sampling) it traces one ray from the entry point into the medium along -entry_n
// with the walk's tracer (which skips the surface the origin lies on).
template <class Tracer>
WalkGuide make_walk_guide(const WalkSettings& settings, Vec3 entry_p, Vec3 entry_n, Tracer&& tracer) {
  WalkGuide guide;
  guide.entry_p = Vec3d(entry_p);
  guide.entry_n = normalize(Vec3d(entry_n));
  if (settings.backward_guiding && settings.sampling != WalkSampling::Classical) {
    const BoundaryHit far = tracer(entry_p, -entry_n, std::numeric_limits<double>::infinity());
    // A ray leaving the medium meets a boundary facing along it: n_far . n_entry < 0.
    if (far.hit && dot(Vec3d(far.n), guide.entry_n) < 0) {
      guide.has_far = true;
      guide.far_p = Vec3d(far.p);
      guide.far_n = normalize(Vec3d(far.n));
    }
  }
  return guide;
}

// The walk (settings validated by make_walk_step). guide.entry_n is the outward normal at
// the entry point (the principal axis of the guiding, as in the seed), dir_in the first
// propagation direction (into the medium).
// tracer(Vec3 origin, Vec3 unit_direction, double max_t) -> BoundaryHit: the first
// boundary crossing with 0 < t <= max_t (a tracer may also report one farther away; the
// walk compares); for the first flight the origin lies on the boundary and the tracer must
// skip that surface (offset or ignore t ~ 0). max_t is the flight's sampled distance: a
// ray query bounded by it is much cheaper than the nearest boundary along an endless ray
// in a large mesh, and finds the same crossing whenever the flight reaches one. Returns true when the walk left the
// medium (out filled); false when it was absorbed by Russian roulette, truncated
// (out.truncated) or lost (no boundary along an infinite flight). A caller that
// reflects the walk back at the boundary calls random_walk again from the exit point.
// `rng` is a random stream (core/rng.h) or a pixel sampler (core/sampler.h): each
// uniform_double() is the next number.
// `initial` is the throughput the walk starts with (a walk continued after an internal
// reflection passes what it has carried so far, so that the roulette and the channel
// choice see it); out.weight includes it.
// `guide` (make_walk_guide) is made once per path at its entry point and kept for the
// walks that continue it; start_p is where this walk starts (the entry point, or the
// boundary point of an internal reflection).
// on_collision: called at every scattering event (NoCollisionHook).
template <class Random, class Tracer, class OnCollision>
bool random_walk(const MixtureWalkStep<3>& step, const WalkSettings& settings, const WalkGuide& guide, Vec3 start_p,
                 Vec3 dir_in, Random& rng, Tracer&& tracer, WalkResult& out, RGB initial, OnCollision&& on_collision) {
  out = WalkResult{};
  GuideAxes<3> axes{Framed(guide.entry_n)};
  if (guide.has_far) axes.back = Framed(guide.far_n), axes.has_back = true;
  // The back share depends on where a flight starts (depths below both planes).
  auto update_back_shares = [&](const Vec3d& x, const std::array<double, 3>& q) {
    if (axes.has_back)
      axes.back_share = step.back_shares(dot(guide.entry_p - x, guide.entry_n), dot(guide.far_p - x, guide.far_n), q);
  };
  const double roulette = settings.roulette_threshold;
  std::array<double, 3> throughput{initial[0], initial[1], initial[2]};
  if (!(throughput[0] + throughput[1] + throughput[2] > 0)) return false;
  Vec3d position(start_p);
  std::array<double, 3> q = step.channel_probabilities(throughput);
  update_back_shares(position, q);
  FlightProposal flight = step.propose_flight(normalize(Vec3d(dir_in)), axes, q, rng);
  Vec3d incoming;  // the direction of the flight that ended at `position` (after a collision)
  for (int steps = 0;;) {
    const BoundaryHit hit = tracer(Vec3(position), Vec3(flight.direction), flight.distance);
    if (hit.hit && flight.distance >= double(hit.t)) {
      const std::array<double, 3> w = step.passage_weights(flight, axes, double(hit.t), q);
      for (int c = 0; c < 3; ++c) out.weight[c] = float(throughput[c] * w[c]);
      out.exit_p = hit.p, out.exit_n = hit.n, out.exit_dir_in_medium = Vec3(flight.direction);
      out.steps = steps;
      out.from_collision = steps > 0;
      if (out.from_collision) out.last_collision = Vec3(position), out.last_incoming = Vec3(incoming);
      return true;
    }
    if (!std::isfinite(flight.distance)) break;  // no boundary ahead of an endless flight: lost
    const std::array<double, 3> w = step.collision_weights(flight, axes, q);
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
    on_collision(position, flight.direction, throughput);
    incoming = flight.direction;
    q = step.channel_probabilities(throughput);
    update_back_shares(position, q);
    flight = step.propose_scatter(flight.direction, axes, q, rng);
  }
  return false;
}

template <class Random, class Tracer>
bool random_walk(const MixtureWalkStep<3>& step, const WalkSettings& settings, const WalkGuide& guide, Vec3 start_p,
                 Vec3 dir_in, Random& rng, Tracer&& tracer, WalkResult& out, RGB initial = RGB(1.0f)) {
  return random_walk(step, settings, guide, start_p, dir_in, rng, std::forward<Tracer>(tracer), out, initial,
                     NoCollisionHook{});
}

// A walk from the entry point: makes its guide (make_walk_guide) first.
template <class Random, class Tracer>
bool random_walk(const MixtureWalkStep<3>& step, const WalkSettings& settings, Vec3 entry_p, Vec3 entry_n, Vec3 dir_in,
                 Random& rng, Tracer&& tracer, WalkResult& out, RGB initial = RGB(1.0f)) {
  const WalkGuide guide = make_walk_guide(settings, entry_p, entry_n, tracer);
  return random_walk(step, settings, guide, entry_p, dir_in, rng, std::forward<Tracer>(tracer), out, initial);
}

template <class Random, class Tracer>
bool random_walk(const WalkMedium& medium, const WalkSettings& settings, Vec3 entry_p, Vec3 entry_n, Vec3 dir_in,
                 Random& rng, Tracer&& tracer, WalkResult& out) {
  return random_walk(make_walk_step(medium, settings), settings, entry_p, entry_n, dir_in, rng,
                     std::forward<Tracer>(tracer), out);
}

}  // namespace dermis::sss
