// Free flights and transmittance in a heterogeneous medium by null collisions: the medium
// is filled up to its majorant with a fictitious "null" medium that scatters straight on, so
// that tentative collisions come from a piecewise-homogeneous exponential (the majorant's,
// cell by cell: grid_medium.h MajorantTraversal) and each is an absorption, a real scattering
// or a null collision (delta tracking, Woodcock et al. 1965; the null-scattering path
// integral, Miller et al. 2019).
//
// Chromatic media: the collisions follow one channel's majorant and event probabilities,
// the channel chosen per flight in proportion to the throughput times a preference, and the
// weight is the one-sample balance heuristic over the channels, each channel's density of
// the sampled sequence of tentative collisions and events being computable in the
// null-scattering path space (Miller et al. 2019 sec. 5, the spectral MIS of pbrt-v4's
// volpath): every channel stays unbiased whatever channel drew the flight.
#pragma once

#include "dermis/core/rgb.h"
#include "dermis/core/rng.h"
#include "dermis/materials/grid_medium.h"

namespace dermis {

struct NullScatteringFlight {
  bool valid = false;      // false: the path ends here (absorbed, or nothing carries on)
  bool scattered = false;  // a real scattering event at distance t, before t_max
  float t = 0;
  RGB weight;  // multiplies the throughput
  // The medium's emission met on the way (pbrt-v4's, at every tentative collision, weighed
  // like the flight): multiplied by the throughput before the flight, it adds to the radiance.
  RGB emitted;
  int null_collisions = 0;
  // Stopped without an outcome at kMaxTentativeCollisions (a majorant so large that steps
  // vanish against the distance: float t stops advancing); valid is false. The caller counts
  // it (PathCounters::truncated).
  bool stalled = false;
};

// The most tentative collisions one flight or one transmittance estimate takes.
inline constexpr int kMaxTentativeCollisions = 1 << 24;

// What a real collision does: Analog, an absorption (the path ends) with probability
// sigma_a / sigma_t and a scattering otherwise, as pbrt-v4's volpath; Weighted, always a
// scattering, its weight carrying sigma_s / sigma_t (survival biasing: channel k's density of
// the collision is then sigma_t,k T_k, its integrand sigma_s,k T_k), which a random walk
// takes: a walk ended by an absorption in one channel carries nothing in the others.
enum class Absorption { Analog, Weighted };

// beta: the path throughput and `preference` a per-channel factor (both choose the channel);
// u_channel uniform in [0, 1); rng draws the distances and events.
NullScatteringFlight sample_null_scattering_flight(const GridMediumView& m, const Ray& ray, float t_max,
                                                   const RGB& beta, const RGB& preference, float u_channel, Rng& rng,
                                                   Absorption absorption = Absorption::Analog);

// An unbiased estimate of the transmittance along [0, t_max) in every channel by ratio
// tracking (Cramer 1978; Novak et al. 2014 sec. 4.2) against the largest channel's majorant,
// with Russian roulette once it falls below 5 % (as pbrt-v4's TraceTransmittance). Across a
// uniform cell (MajorantSegment::exact) the stretch's exact transmittance multiplies in: the
// estimate stays an unbiased product of independent factors, with less variance and cost.
// `stalled` (when given) is set where the tracking stopped at kMaxTentativeCollisions (the
// estimate is then 0).
RGB ratio_tracking_transmittance(const GridMediumView& m, const Ray& ray, float t_max, Rng& rng,
                                 bool* stalled = nullptr);

// The random numbers of a medium's tracking: a stream from one sample number and the ray
// (pbrt-v4 seeds its tracking alike), so that an image does not depend on the thread count.
Rng tracking_rng(float u, const Ray& ray);

}  // namespace dermis
