// Tests of the Trowbridge-Reitz distribution: normalisation over projected area, the
// visible-normal density (which integrates to one only if Lambda matches D) and its
// sampler (chi-square), Smith's masking, and the half-vector Jacobians.
#include "dermis/core/microfacet.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dermis/core/rng.h"
#include "support/direction_grid.h"

namespace dermis {
namespace {

using testing::direction_at;
using testing::DirectionHistogram;
using testing::integrate_with_error;
using testing::kChiSquareAlpha;

// Isotropic and anisotropic roughnesses, from nearly smooth to very rough.
const std::vector<std::pair<float, float>> kAlphas = {{0.05f, 0.05f}, {0.2f, 0.2f}, {0.6f, 0.6f},
                                                      {1.0f, 1.0f},   {0.1f, 0.4f}, {0.5f, 0.05f}};

// The grid resolves the narrowest peak (alpha = 0.05 rad) with ~60 theta steps; float
// evaluation leaves ~1e-6 on top of the grid's own error estimate.
constexpr int kThetaSteps = 2048, kPhiSteps = 256;
constexpr double kFloatSlack = 1e-5;

TEST(TrowbridgeReitz, IntegratesToOneOverProjectedArea) {
  for (auto [ax, ay] : kAlphas) {
    const TrowbridgeReitz d(ax, ay);
    auto projected = [&](Vec3 m) { return double(d.D(m)) * m.z; };
    const auto I = integrate_with_error(projected, kPiD / 2, kThetaSteps, kPhiSteps);
    EXPECT_NEAR(I.value, 1.0, I.error + kFloatSlack) << ax << " " << ay;
    EXPECT_EQ(d.D({0.6f, 0, -0.8f}), 0.0f);  // no normals below the surface
  }
}

// int D_w(m) dm = 1 holds for every w exactly when Lambda is Smith's for this D
// (Heitz 2014, eq. 20: cos theta_w = int G1(w) <w, m> D(m) dm).
TEST(TrowbridgeReitz, VisibleNormalPdfIntegratesToOne) {
  for (auto [ax, ay] : kAlphas) {
    const TrowbridgeReitz d(ax, ay);
    for (double theta_w : {0.0, 0.5, 1.1, 1.45, 2.3}) {  // 2.3: from below the surface
      const Vec3 w = direction_at(theta_w, 0.7);
      auto pdf = [&](Vec3 m) { return double(d.visible_pdf(w, m)); };
      const auto I = integrate_with_error(pdf, kPiD / 2, kThetaSteps, kPhiSteps);
      EXPECT_NEAR(I.value, 1.0, I.error + kFloatSlack) << ax << " " << ay << " theta_w " << theta_w;
    }
  }
}

TEST(TrowbridgeReitz, VisibleNormalSamplerMatchesPdf) {
  constexpr int kSamples = 200'000;
  uint64_t seed = 1;
  for (auto [ax, ay] : {std::pair{0.2f, 0.2f}, std::pair{0.6f, 0.6f}, std::pair{0.1f, 0.4f}})
    for (double theta_w : {0.0, 0.8, 1.4, 2.6}) {
      SCOPED_TRACE(::testing::Message() << ax << " " << ay << " theta_w " << theta_w);
      const TrowbridgeReitz d(ax, ay);
      const Vec3 w = direction_at(theta_w, 2.0);
      const Vec3 w_up = w.z < 0 ? -w : w;
      DirectionHistogram h(kPiD / 2, 20, 40);
      Rng rng(seed++, 0);
      for (int i = 0; i < kSamples; ++i) {
        const Vec3 m = d.sample_visible(w, {rng.uniform(), rng.uniform()});
        ASSERT_NEAR(length(m), 1.0f, 1e-5f);
        ASSERT_GE(m.z, 0.0f);
        ASSERT_GE(dot(w_up, m), -1e-6f);  // only visible normals
        h.add(m);
      }
      const auto r = h.test([&](Vec3 m) { return double(d.visible_pdf(w, m)); });
      EXPECT_GT(r.p_value, kChiSquareAlpha) << "chi2 " << r.statistic << " dof " << r.dof;
    }
}

TEST(TrowbridgeReitz, SmithMasking) {
  // Isotropic: G1 = 2 / (1 + sqrt(1 + alpha^2 tan^2 theta)) (Walter et al. 2007, eq. 34).
  for (float a : {0.05f, 0.3f, 1.0f})
    for (double theta : {0.1, 0.7, 1.3, 1.55}) {
      const TrowbridgeReitz d(a, a);
      const double t = std::tan(theta);
      const double walter = 2 / (1 + std::sqrt(1 + a * a * t * t));
      EXPECT_NEAR(d.G1(direction_at(theta, 0.3)), walter, 2e-6) << a << " " << theta;
      EXPECT_NEAR(d.G1(direction_at(kPiD - theta, 0.3)), walter, 2e-6);  // even in w
    }
  const TrowbridgeReitz d(0.1f, 0.6f);
  EXPECT_EQ(d.G1({0, 0, 1}), 1.0f);  // nothing masks at normal incidence
  EXPECT_EQ(d.G1({1, 0, 0}), 0.0f);  // everything at grazing incidence
  // Anisotropy: a direction along the rougher axis is masked more.
  EXPECT_LT(d.G1(direction_at(1.0, kPiD / 2)), d.G1(direction_at(1.0, 0)));
  // Height-correlated G: symmetric, between the separable product and either G1.
  const Vec3 wo = direction_at(0.9, 0.4), wi = direction_at(1.2, 2.5);
  EXPECT_EQ(d.G(wo, wi), d.G(wi, wo));
  EXPECT_LE(d.G(wo, wi), std::min(d.G1(wo), d.G1(wi)));
  EXPECT_GE(d.G(wo, wi), d.G1(wo) * d.G1(wi));
}

TEST(TrowbridgeReitz, RoughnessRemapAndSmoothness) {
  EXPECT_FLOAT_EQ(roughness_to_alpha(0.25f, true), 0.5f);  // pbrt-v4: alpha = sqrt(roughness)
  EXPECT_FLOAT_EQ(roughness_to_alpha(0.25f, false), 0.25f);
  EXPECT_EQ(roughness_to_alpha(0, true), 0.0f);
  EXPECT_TRUE(TrowbridgeReitz(0, 0).effectively_smooth());
  EXPECT_TRUE(TrowbridgeReitz(9e-4f, 5e-4f).effectively_smooth());
  EXPECT_FALSE(TrowbridgeReitz(9e-4f, 1e-3f).effectively_smooth());
}

// |d omega_m / d omega_i| by central differences of the half-vector functions: the
// ratio of the areas spanned by the derivatives of m and of wi in (theta, phi). The
// step h = 1e-2 leaves an O(h^2) ~ 1e-4 relative error, float rounding ~1e-5 / h.
template <class HalfVector>
double numeric_jacobian(const HalfVector& half, double theta, double phi) {
  const double h = 1e-2;
  auto m_at = [&](double t, double p) { return Vec3d(half(direction_at(t, p))); };
  auto w_at = [&](double t, double p) { return Vec3d(direction_at(t, p)); };
  const Vec3d dm_t = (m_at(theta + h, phi) - m_at(theta - h, phi)) / (2 * h);
  const Vec3d dm_p = (m_at(theta, phi + h) - m_at(theta, phi - h)) / (2 * h);
  const Vec3d dw_t = (w_at(theta + h, phi) - w_at(theta - h, phi)) / (2 * h);
  const Vec3d dw_p = (w_at(theta, phi + h) - w_at(theta, phi - h)) / (2 * h);
  return length(cross(dm_t, dm_p)) / length(cross(dw_t, dw_p));
}

TEST(MicrofacetJacobians, MatchFiniteDifferences) {
  const Vec3 wo = direction_at(0.6, 0.2);
  for (double theta_i : {0.3, 0.9, 1.3})
    for (double phi_i : {0.5, 2.9}) {
      auto reflected = [&](Vec3 wi) { return *reflection_half_vector(wo, wi); };
      const Vec3 wi = direction_at(theta_i, phi_i);
      const double expected = reflection_jacobian(wi, reflected(wi));
      EXPECT_NEAR(numeric_jacobian(reflected, theta_i, phi_i) / expected, 1.0, 1e-3) << theta_i << " " << phi_i;
    }
  // Refraction from outside (etap = 1.5) into directions below, and from inside out.
  int checked = 0;
  for (float etap : {1.5f, 1 / 1.5f}) {
    const Vec3 wo_side = etap > 1 ? wo : Vec3(wo.x, wo.y, -wo.z);
    for (double theta_i : {0.3, 0.7})
      for (double phi_i : {2.5, 3.5}) {
        const double t = etap > 1 ? kPiD - theta_i : theta_i;  // wi on the other side
        auto refracted = [&](Vec3 wi) { return *refraction_half_vector(wo_side, wi, etap); };
        const Vec3 wi = direction_at(t, phi_i);
        const Vec3 m = refracted(wi);
        if (dot(wo_side, m) * wo_side.z <= 0 || dot(wi, m) * wi.z <= 0) continue;  // no microfacet connects them
        const double expected = refraction_jacobian(wo_side, wi, m, etap);
        EXPECT_NEAR(numeric_jacobian(refracted, t, phi_i) / expected, 1.0, 1e-3) << etap << " " << t << " " << phi_i;
        ++checked;
      }
  }
  EXPECT_GE(checked, 6);
}

}  // namespace
}  // namespace dermis
