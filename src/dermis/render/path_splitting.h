// Splitting of heavy paths: the upper bound of a weight window (Booth 1982, "A Sample
// Problem for Variance Reduction in MCNP"; in rendering, Vorba & Krivanek 2016, "Adjoint-
// Driven Russian Roulette and Splitting in Light Transport Simulation", sec. 4, with a
// constant importance). Russian roulette keeps a path's throughput from falling far below
// one; a path whose throughput rises above `threshold` goes on as n = ceil(max / threshold)
// independent copies, each weighted 1/n: the mean of n unbiased estimates is unbiased
// whatever n is, as long as n is fixed before they are drawn.
//
// Where it pays: subsurface exits multiply a path's channels by weights well above one
// (a disk probe's red weight reaches about A / (q_red P_axis), 3 to 6 on skin; a walk's
// spectral MIS weights likewise), and a path that meets the object again compounds them:
// on a bust, the paths past the first exit carried a small share of the light and much of
// the variance (docs/results/results-rendering.md, "Heavy paths are split").
#pragma once

#include <algorithm>
#include <cmath>

#include "dermis/core/rgb.h"

namespace dermis {

// The copies of one split at most, and the copies split off one camera sample in all
// (with its nested paths): a closed room of a bright subsurface material must not branch
// without end.
inline constexpr int kMaxSplit = 8;
inline constexpr int kSplitBudgetPerSample = 16;

// How many copies a path of throughput `beta` goes on as (1: no split); takes the copies
// beyond the first from `budget`. threshold <= 0: never.
inline int split_count(const RGB& beta, float threshold, int& budget) {
  if (!(threshold > 0) || budget <= 0) return 1;
  const float m = beta.max();
  if (!(m > threshold) || !std::isfinite(m)) return 1;
  const int n = std::min({int(std::ceil(m / threshold)), kMaxSplit, budget + 1});
  budget -= n - 1;
  return n;
}

}  // namespace dermis
