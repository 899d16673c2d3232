#include "dermis/sss/study/albedo_inversion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "dermis/sss/halfspace/halfspace.h"

namespace dermis::sss {
namespace {

// A -> alpha -> A through Chandrasekhar's exact relation, 1e-9 (the brief's tolerance).
TEST(AlbedoInversion, SurfaceAlbedoRoundTrips) {
  for (double a : {1e-4, 0.01, 0.05, 0.1, 0.2, 0.5, 0.8, 0.9, 0.95, 0.99, 0.999, 0.99999}) {
    const double alpha = single_scattering_albedo_index_matched(a);
    EXPECT_GE(alpha, 0.0);
    EXPECT_LE(alpha, 1.0);
    EXPECT_NEAR(surface_albedo_index_matched(alpha), a, 1e-9) << a;
  }
  EXPECT_EQ(single_scattering_albedo_index_matched(0.0), 0.0);
  EXPECT_EQ(single_scattering_albedo_index_matched(1.0), 1.0);
}

// The table against the exact relation, between its nodes and at them, over the whole range
// of alpha (half of the points where A changes fastest, near alpha = 1).
TEST(AlbedoInversion, TabulatedSurfaceAlbedoIsTheExactOne) {
  double worst = 0;
  for (int i = 0; i <= 200; ++i) {
    const double u = (i + 0.37) / 201.0, alpha = i < 100 ? 1 - u * u : double(i - 100) / 100;
    const double err = std::abs(surface_albedo_index_matched_tabulated(alpha) - surface_albedo_index_matched(alpha));
    worst = std::max(worst, err);
    EXPECT_LT(err, 2e-7) << alpha;
  }
  std::printf("largest difference: %.3g\n", worst);
  EXPECT_EQ(surface_albedo_index_matched_tabulated(1.0), 1.0);
  EXPECT_NEAR(surface_albedo_index_matched_tabulated(0.0), 0.0, 1e-12);
}

// alpha -> A -> alpha, compared in u = sqrt(1 - alpha) (A is linear in u near alpha = 1,
// so u is what A determines to 1e-9).
TEST(AlbedoInversion, SingleScatteringAlbedoRoundTrips) {
  for (double alpha : {0.01, 0.3, 0.7, 0.9, 0.99, 0.9999, 1 - 1e-8}) {
    const double back = single_scattering_albedo_index_matched(surface_albedo_index_matched(alpha));
    EXPECT_NEAR(std::sqrt(1 - back), std::sqrt(1 - alpha), 1e-9) << alpha;
  }
}

// Small alpha: single scattering dominates, A = (alpha/2)(1 - ln 2) + O(alpha^2) for normal
// incidence (the single-scattering albedo of a half-space: int_0^1 mu/(1+mu) dmu = 1 - ln 2).
TEST(AlbedoInversion, SingleScatteringLimit) {
  const double alpha = 1e-4;
  EXPECT_NEAR(surface_albedo_index_matched(alpha) / (alpha / 2 * (1 - std::log(2.0))), 1.0, 1e-3);
}

TEST(AlbedoInversion, RejectsBadInput) {
  EXPECT_THROW(single_scattering_albedo_index_matched(-0.1), std::invalid_argument);
  EXPECT_THROW(single_scattering_albedo_index_matched(1.5), std::invalid_argument);
  EXPECT_THROW(single_scattering_albedo_index_matched(std::nan("")), std::invalid_argument);
  EXPECT_THROW(surface_albedo_index_matched(1.01), std::invalid_argument);
  EXPECT_THROW(single_scattering_albedo_simulated(0.5, 0.0, 1000, 1), std::invalid_argument);
  EXPECT_THROW(single_scattering_albedo_simulated(0.5, 1.3, 0, 1), std::invalid_argument);
}

TEST(AlbedoInversion, SimulatedIsExactWhenIndexMatched) {
  const SimulatedInversion s = single_scattering_albedo_simulated(0.4, 1.0, 1000, 1);
  EXPECT_EQ(s.simulations, 0);
  EXPECT_EQ(s.single_scattering_albedo, single_scattering_albedo_index_matched(0.4));
}

// A dielectric boundary: the alpha found reproduces A in an independent simulation (other
// seed) within 4 standard errors of the two estimates, and exceeds the index-matched alpha
// (internal reflection lengthens paths, so less absorption is needed for the same A).
TEST(AlbedoInversion, SimulatedReproducesTheTargetWithADielectric) {
  const double target = 0.5;
  const SimulatedInversion s = single_scattering_albedo_simulated(target, 1.4, 40000, 7);
  EXPECT_GT(s.simulations, 0);
  EXPECT_GT(s.single_scattering_albedo, single_scattering_albedo_index_matched(target));
  HalfspaceConfig c;
  c.albedo = s.single_scattering_albedo;
  c.eta = 1.4;
  c.paths = 200000;
  c.seed = 99;
  const HalfspaceResult r = simulate_halfspace(c);
  const double sigma = std::hypot(r.albedo_per_entering_stderr(), s.surface_albedo_stderr);
  EXPECT_NEAR(r.albedo_per_entering(), target, 4 * sigma + std::abs(s.surface_albedo - target));
  EXPECT_LE(std::abs(s.surface_albedo - target), s.surface_albedo_stderr * 1.000001);
}

}  // namespace
}  // namespace dermis::sss
