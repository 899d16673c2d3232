// Russian roulette: the lower bound of a weight window (Booth 1982; Vorba & Krivanek 2016,
// "Adjoint-Driven Russian Roulette and Splitting in Light Transport Simulation", sec. 4,
// with a constant importance; path_splitting.h is the upper bound). A path whose throughput
// measure rr (max over channels x eta scale, pbrt-v4 sec. 14.1.3) has fallen below the
// threshold goes on with probability rr / threshold, its throughput divided by that
// probability: unbiased for any threshold in (0, 1].
//
// The threshold at surfaces is 1 (pbrt-v4's rule). At a collision in a medium that sees
// lights it is 1/2: a path there gathers direct light on every segment, and the collision's
// albedo is a weight (implicit capture: sigma_s / sigma_t in the free flight's weight), so
// roulette on that weight from 1 down kills a bright medium's paths as analog absorption
// would, with probability about 1 - albedo per collision, while they still gather light:
// the variance implicit capture removes, for little time, as such a path mostly leaves the
// medium first. Lower thresholds gave no less variance and cost time in a denser medium. In
// a medium enclosed by glass (no light seen: the path gathers only once it leaves) 1/2
// added time for no variance, and the rule stays 1 there. Measured: docs/results/results-rendering.md,
// "Russian roulette in media".
#pragma once

namespace dermis {

inline constexpr float kSurfaceRouletteThreshold = 1.0f;
inline constexpr float kMediumRouletteThreshold = 0.5f;

// The probability that a path of throughput measure rr goes on: 1 at or above the
// threshold, rr / threshold below it (0 for rr <= 0 or NaN).
inline float roulette_survival(float rr, float threshold) {
  if (rr >= threshold) return 1;
  if (!(rr > 0)) return 0;
  return rr / threshold;
}

}  // namespace dermis
