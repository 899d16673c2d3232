// The random walk through a heterogeneous interior: a grid medium filling a subsurface
// object (SubsurfaceParams::interior), walked by null collisions. Each flight runs along
// its line up to the boundary the tracer finds there; its tentative collisions follow the
// majorant grid, and each is a real scattering or a null one (delta tracking with the
// one-sample balance heuristic over the channels: materials/null_scattering.h; Woodcock et
// al. 1965, Miller et al. 2019), every real collision a scattering weighted by the albedo
// (Absorption::Weighted: no walk ends by absorption but by roulette, as the homogeneous
// walk's). A flight that passes the boundary leaves the medium, and the
// caller applies the boundary's rules as for the homogeneous walk (walk_method.cpp): the
// result is the homogeneous walk's (sss/walk/random_walk.h WalkResult). Flights sample the
// phase function (Henyey & Greenstein 1941); the guided flights of the homogeneous walk
// follow a half-space of one medium (Dwivedi's), which a varying one is not.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "dermis/core/henyey_greenstein.h"
#include "dermis/core/rgb.h"
#include "dermis/core/rng.h"
#include "dermis/materials/grid_medium.h"
#include "dermis/materials/null_scattering.h"
#include "dermis/sss/walk/boundary_hit.h"
#include "dermis/sss/walk/random_walk.h"

namespace dermis {

// One walk from start_p along dir_in (into the medium) until a flight passes the boundary:
// true with `out` filled (out.weight includes `initial`), false where it was absorbed (by
// the null collisions' weights or Russian roulette), truncated (settings.max_steps real
// scatterings, or a flight's kMaxTentativeCollisions: out.truncated) or lost (no boundary
// ahead). tracer(origin, unit direction, max_t) -> sss::BoundaryHit as for
// sss::random_walk, asked here for the nearest boundary along a whole line (max_t
// infinite): the tracking needs the segment's end before it starts. `rng`: a random stream
// or a pixel sampler (uniform()). The medium's emission met on the way, times the
// throughput, is added to `emitted`. on_collision(position, incoming propagation direction,
// throughput per channel) is called at every scattering event (after its weight, which
// holds the medium's sigma_s there, and the roulette; before the next direction is drawn),
// as sss::random_walk's.
template <class Random, class Tracer, class OnCollision = sss::NoCollisionHook>
bool heterogeneous_walk(const GridMediumView& medium, const sss::WalkSettings& settings, Vec3 start_p, Vec3 dir_in,
                        Random& rng, Tracer&& tracer, sss::WalkResult& out, RGB initial, RGB& emitted,
                        OnCollision&& on_collision = {}) {
  out = sss::WalkResult{};
  RGB throughput = initial;
  if (!(throughput.max() > 0)) return false;
  Vec3 position = start_p, direction = normalize(dir_in);
  Vec3 incoming;  // the direction of the flight that ended at `position` (after a scattering)
  // Each flight's channel follows the throughput times the medium's preference (as the
  // volumetric path tracer's: path/grid_volume_vertex.cpp).
  const RGB preference = medium.channel_preference();
  for (int steps = 0;;) {
    const sss::BoundaryHit hit = tracer(position, direction, std::numeric_limits<double>::infinity());
    if (!hit.hit) return false;  // no boundary ahead: lost
    const Ray ray{position, direction};
    const float u_channel = rng.uniform();
    Rng tracking = tracking_rng(rng.uniform(), ray);
    const NullScatteringFlight flight = sample_null_scattering_flight(medium, ray, hit.t, throughput, preference,
                                                                      u_channel, tracking, Absorption::Weighted);
    emitted += throughput * flight.emitted;
    if (!flight.valid) {
      out.truncated = flight.stalled;
      return false;
    }
    throughput *= flight.weight;
    if (!flight.scattered) {
      out.weight = throughput;
      out.exit_p = hit.p, out.exit_n = hit.n, out.exit_dir_in_medium = direction;
      out.steps = steps;
      out.from_collision = steps > 0;
      if (out.from_collision) out.last_collision = position, out.last_incoming = incoming;
      return true;
    }
    position = position + direction * flight.t;
    out.steps = steps;
    if (steps == settings.max_steps) {
      out.truncated = true;
      return false;
    }
    ++steps;
    // Russian roulette on the largest channel: survive with probability m / threshold (unbiased).
    const float m = throughput.max();
    if (!(m > 0)) return false;
    if (m < settings.roulette_threshold) {
      if (rng.uniform() * settings.roulette_threshold >= m) return false;
      throughput *= settings.roulette_threshold / m;
    }
    on_collision(Vec3d(position), Vec3d(direction), std::array<double, 3>{throughput[0], throughput[1], throughput[2]});
    incoming = direction;
    const float cos_theta = sample_henyey_greenstein_cos(rng.uniform(), medium.g);
    const double phi = 2 * std::numbers::pi * double(rng.uniform());
    direction = normalize(Vec3(sss::direction_about(Vec3d(direction), double(cos_theta), phi)));
  }
}

}  // namespace dermis
