// Calibrates the region-means comparison of the tests (tests/support/pixel_statistics.h) on
// SubsurfaceRandomWalk.ThePilotsStrategiesEqualAMediumInsideADielectric's scenes: renders the
// test's pair of pictures with many seeds and reports, per strategy,
//  - the false-failure rate: the share of seeds at which the test's verdict (every region and
//    channel within K standard errors) fails, though both pictures have the same mean;
//  - sigma against the spread: per region and channel, the standard deviation over the seeds
//    of the difference of region means, over the root mean square of the sigma each seed
//    estimated from its own images (1: the test's sigma is right; above 1: it underestimates);
//  - the tails of z = difference / sigma against a normal's.
// Not run by the tests (it takes minutes): docs/testing.md gives its command and results.
//   dermis_region_calibration [seeds (50)] [spp (512)] [first seed (1000)] [k (4)]
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "support/pilot_strategy_scenes.h"
#include "support/pixel_statistics.h"

namespace {

using dermis::testing::RegionComparison;

std::vector<RegionComparison> compare_once(const dermis::RenderScene& a, const dermis::RenderScene& b, int spp,
                                           uint64_t seed) {
  // As testing::expect_same_picture: seeds `seed` and seed + 1, 4 x 4 regions.
  return dermis::testing::region_comparisons(dermis::testing::pixel_statistics(a, spp, seed),
                                             dermis::testing::pixel_statistics(b, spp, seed + 1), 4, 4);
}

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 50;
  const int spp = argc > 2 ? std::atoi(argv[2]) : 512;
  const uint64_t first = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 1000;
  const double k = argc > 4 ? std::atof(argv[4]) : 4.0;
  dermis::Diagnostics diag;
  auto volume =
      dermis::build_render_scene(dermis::parse_scene_string(dermis::testing::pilot_strategy_volume_scene()), diag);
  std::printf("%d seeds (%llu, %llu, ...), %d spp, verdict at %g sigma\n", seeds, (unsigned long long)first,
              (unsigned long long)first + 2, spp, k);
  int any_fail = 0;
  std::vector<int> seed_failed(std::size_t(seeds), 0);
  for (const char* strategy : dermis::testing::kPilotStrategies) {
    auto walk = dermis::build_render_scene(
        dermis::parse_scene_string(dermis::testing::pilot_strategy_walk_scene(strategy)), diag);
    std::vector<std::vector<RegionComparison>> runs{std::size_t(seeds)};
    tbb::parallel_for(0, seeds,
                      [&](int i) { runs[std::size_t(i)] = compare_once(*walk, *volume, spp, first + 2 * i); });
    const std::size_t m = runs[0].size();
    int fails = 0;
    std::size_t beyond3 = 0, beyond4 = 0, beyond_k = 0, count = 0;
    double max_abs_z = 0;
    for (int i = 0; i < seeds; ++i) {
      bool failed = false;
      for (const RegionComparison& r : runs[std::size_t(i)]) {
        if (r.sigma == 0 && r.mean_a == r.mean_b) continue;  // a region of sky alone: no noise, no comparison
        const double z = std::abs(r.z());
        ++count;
        beyond3 += z > 3, beyond4 += z > 4, beyond_k += z > k;
        max_abs_z = std::max(max_abs_z, z);
        failed |= z > k;
      }
      fails += failed;
      seed_failed[std::size_t(i)] |= failed;
    }
    // Sigma against the spread over the seeds, per region and channel.
    std::vector<double> ratios;
    for (std::size_t j = 0; j < m; ++j) {
      double s = 0, s2 = 0, sig2 = 0;
      for (int i = 0; i < seeds; ++i) {
        const RegionComparison& r = runs[std::size_t(i)][j];
        const double d = r.mean_a - r.mean_b;
        s += d, s2 += d * d, sig2 += r.sigma * r.sigma;
      }
      const double mean = s / seeds, spread = std::sqrt(std::max(0.0, (s2 - seeds * mean * mean) / (seeds - 1)));
      // A region of sky alone has no noise (its sigma, if any, is the rounding of a constant).
      if (sig2 > 0 && s2 > 0) ratios.push_back(spread / std::sqrt(sig2 / seeds));
    }
    std::sort(ratios.begin(), ratios.end());
    auto quantile = [&](double q) { return ratios.empty() ? NAN : ratios[std::size_t(q * (ratios.size() - 1))]; };
    std::printf("\n%s\n", strategy);
    std::printf("  false failures: %d of %d seeds (%.1f %%)\n", fails, seeds, 100.0 * fails / seeds);
    std::printf(
        "  spread over seeds / rms sigma, over %zu region-channels: min %.3f, median %.3f, 90%% %.3f, max %.3f\n",
        ratios.size(), quantile(0), quantile(0.5), quantile(0.9), quantile(1));
    std::printf(
        "  |z| > 3: %.2e (normal 2.70e-03), |z| > 4: %.2e (normal 6.33e-05), |z| > %g: %zu of %zu; max |z| %.2f\n",
        double(beyond3) / count, double(beyond4) / count, k, beyond_k, count, max_abs_z);
  }
  for (int f : seed_failed) any_fail += f;
  std::printf("\nthe test as a whole (all strategies): %d of %d seeds fail (%.1f %%)\n", any_fail, seeds,
              100.0 * any_fail / seeds);
  return 0;
}
