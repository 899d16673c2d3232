// The half-space simulator's rough boundary (HalfspaceConfig::alpha_x, alpha_y): below
// the smoothness threshold it is the smooth boundary, number for number; just above it
// (the rough code path, another random stream) it agrees with the smooth boundary within
// 4 standard errors; and it conserves energy, counting what the microfacet model loses.
// Its agreement with the renderer's medium inside a rough dielectric is tested in
// render/rough_albedo_table_test.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "dermis/core/fresnel.h"
#include "dermis/core/microfacet.h"
#include "dermis/sss/halfspace/halfspace.h"
#include "dermis/sss/walk/albedo_inversion.h"

namespace dermis::sss {
namespace {

HalfspaceConfig dielectric_halfspace(bool exit_matched) {
  HalfspaceConfig c;
  c.albedo = 0.9;
  c.g = 0.3;
  c.eta = 1.4;
  c.exit_matched = exit_matched;
  c.incidence = Incidence::Diffuse;
  c.sampling = WalkSampling::Dwivedi;
  c.paths = 100000;
  c.seed = 11;
  return c;
}

TEST(HalfspaceRoughBoundary, BelowTheSmoothThresholdIsTheSmoothBoundaryExactly) {
  for (bool exit_matched : {false, true}) {
    const HalfspaceConfig smooth = dielectric_halfspace(exit_matched);
    const HalfspaceResult s = simulate_halfspace(smooth);
    for (double ax : {0.0, 0.5 * double(kSmoothAlpha)}) {
      HalfspaceConfig c = smooth;
      c.alpha_x = ax;
      c.alpha_y = 0.9 * double(kSmoothAlpha);
      const HalfspaceResult r = simulate_halfspace(c);
      EXPECT_EQ(r.albedo, s.albedo);
      EXPECT_EQ(r.albedo_stderr, s.albedo_stderr);
      EXPECT_EQ(r.specular, s.specular);
      EXPECT_EQ(r.absorbed, s.absorbed);
      EXPECT_EQ(r.albedo_per_entering(), s.albedo_per_entering());
      EXPECT_EQ(r.albedo_per_entering_stderr(), s.albedo_per_entering_stderr());
      EXPECT_EQ(r.lost, 0.0);
    }
  }
  // And so is a table node.
  AlbedoTableConfig t;
  t.eta = 1.4;
  t.size = 8;
  t.paths_per_node = 5000;
  t.use_cache = false;
  const AlbedoNode smooth_node = simulate_albedo_node(t, 3);
  t.alpha_x = t.alpha_y = 0.5 * double(kSmoothAlpha);
  const AlbedoNode node = simulate_albedo_node(t, 3);
  EXPECT_EQ(node.albedo, smooth_node.albedo);
  EXPECT_EQ(node.error, smooth_node.error);
}

// alpha = 2 kSmoothAlpha takes the rough code path (microfacet sampling, a per-path
// entered weight) with an interface all but smooth: the same A, specular and entered
// power as the smooth boundary (exact Fresnel), within 4 standard errors.
TEST(HalfspaceRoughBoundary, NearlySmoothAgreesWithTheSmoothBoundary) {
  for (bool exit_matched : {false, true}) {
    SCOPED_TRACE(exit_matched);
    const HalfspaceConfig smooth = dielectric_halfspace(exit_matched);
    const HalfspaceResult s = simulate_halfspace(smooth);
    HalfspaceConfig c = smooth;
    c.alpha_x = c.alpha_y = 2 * double(kSmoothAlpha);
    c.seed = 12;
    const HalfspaceResult r = simulate_halfspace(c);
    EXPECT_GT(r.entered_stderr, 0.0);  // the rough code path was taken
    EXPECT_NEAR(r.albedo_per_entering(), s.albedo_per_entering(),
                4 * std::hypot(r.albedo_per_entering_stderr(), s.albedo_per_entering_stderr()));
    EXPECT_NEAR(r.specular, fresnel_diffuse_reflectance(1.4), 4 * r.specular_stderr);
    EXPECT_NEAR(r.entered, 1 - fresnel_diffuse_reflectance(1.4), 4 * r.entered_stderr);
    EXPECT_LT(r.lost, 1e-3);
  }
}

// Implicit capture, Russian roulette and the rough boundary conserve energy in
// expectation: specular + albedo + absorbed + lost = 1 (nothing truncated). The
// microfacet model does lose energy, at the entry and at the exits.
TEST(HalfspaceRoughBoundary, EnergyBalanceCountsTheMicrofacetLoss) {
  for (bool exit_matched : {false, true}) {
    SCOPED_TRACE(exit_matched);
    HalfspaceConfig c = dielectric_halfspace(exit_matched);
    c.alpha_x = 0.6;
    c.alpha_y = 0.3;
    c.paths = 40000;
    const HalfspaceResult r = simulate_halfspace(c);
    EXPECT_EQ(r.truncated, 0u);
    EXPECT_NEAR(r.specular + r.albedo + r.absorbed + r.lost, 1.0,
                4 * (r.specular_stderr + r.albedo_stderr + r.absorbed_stderr + r.lost_stderr));
    EXPECT_GT(r.lost, 10 * r.lost_stderr);
  }
}

TEST(HalfspaceRoughBoundary, RejectsBadAlphas) {
  HalfspaceConfig c;
  c.alpha_x = -0.1;
  EXPECT_THROW(simulate_halfspace(c), std::invalid_argument);
  c.alpha_x = 0.1, c.alpha_y = std::nan("");
  EXPECT_THROW(simulate_halfspace(c), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
