// Tests of the Fresnel reflectance (both precisions of the one template), its first
// moment, the conductor Fresnel term, and refraction.
#include "dermis/core/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>

namespace dermis {
namespace {

template <class T>
class FresnelDielectric : public ::testing::Test {
 protected:
  // Closed forms below are evaluated in double; float evaluation leaves ~1e-7.
  static constexpr double kTol = std::is_same_v<T, float> ? 1e-6 : 1e-15;
};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(FresnelDielectric, Precisions);

TYPED_TEST(FresnelDielectric, NormalIncidenceMatchesClosedForm) {
  using T = TypeParam;
  for (double eta : {1.0, 1.33, 1.4, 1.5, 2.4, 0.7}) {
    const double r0 = std::pow((T(eta) - 1.0) / (T(eta) + 1.0), 2);  // Born & Wolf 1.5.2
    EXPECT_NEAR(fresnel_dielectric<T>(1, T(eta)), r0, this->kTol) << eta;
    EXPECT_NEAR(fresnel_dielectric<T>(-1, T(eta)), r0, this->kTol) << eta;  // same from the other side
  }
}

TYPED_TEST(FresnelDielectric, GrazingIncidenceReflectsEverything) {
  using T = TypeParam;
  EXPECT_NEAR(fresnel_dielectric<T>(T(1e-6), T(1.5)), 1, 1e-4);
  for (double eta : {1.0, 1.33, 1.4, 0.7}) EXPECT_NEAR(fresnel_dielectric<T>(0, T(eta)), 1.0, this->kTol) << eta;
  // Index-matched: no reflection (in float, cos_t = sqrt(1 - sin^2) rounds away from cos_i).
  EXPECT_NEAR(fresnel_dielectric<T>(T(0.3), 1), 0.0, (std::is_same_v<T, float> ? 1e-12 : 1e-30));
}

// Total internal reflection beyond the critical angle, seen from inside (signed cosine)
// and as a relative index below one (the half-space simulator's way of asking).
TYPED_TEST(FresnelDielectric, TotalInternalReflectionBeyondCriticalAngle) {
  using T = TypeParam;
  const T eta = T(1.5);
  const T cos_critical = std::sqrt(1 - 1 / (eta * eta));
  EXPECT_EQ(fresnel_dielectric<T>(-(cos_critical - T(0.01)), eta), T(1));
  EXPECT_LT(fresnel_dielectric<T>(-(cos_critical + T(0.01)), eta), T(1));
  const double cos_c = std::sqrt(1 - 0.7 * 0.7);
  const double below = std::is_same_v<T, float> ? 1e-5 : 1e-9;
  EXPECT_EQ(fresnel_dielectric<T>(T(cos_c - below), T(0.7)), T(1));
  EXPECT_LT(fresnel_dielectric<T>(T(cos_c + 1e-3), T(0.7)), T(1));
}

// The signed cosine: arriving from the side n points away from is the inverse index.
TYPED_TEST(FresnelDielectric, NegativeCosineMeansInverseIndex) {
  using T = TypeParam;
  for (double eta : {0.7, 1.33, 2.0})
    for (double c : {0.05, 0.4, 0.9})
      EXPECT_EQ(fresnel_dielectric<T>(T(-c), T(eta)), fresnel_dielectric<T>(T(c), T(1 / T(eta))));
}

TYPED_TEST(FresnelDielectric, TransmittanceIsReciprocalAcrossTheInterface) {
  // T(theta_i, eta) from outside equals T(theta_t, 1/eta) from inside (Stokes relations).
  using T = TypeParam;
  const double tol = std::is_same_v<T, float> ? 1e-5 : 1e-13;
  for (double eta : {1.4, 2.0, 0.8})
    for (double cos_i : {0.05, 0.2, 0.5, 0.9}) {
      const double sin_t = std::sqrt(1 - cos_i * cos_i) / eta;
      if (sin_t >= 1) continue;
      const double cos_t = std::sqrt(1 - sin_t * sin_t);
      EXPECT_NEAR(fresnel_dielectric<T>(T(cos_i), T(eta)), fresnel_dielectric<T>(T(-cos_t), T(eta)), tol);
    }
}

TEST(FresnelDielectricFloat, RendererSignatureIsTheFloatTemplate) {
  for (float eta : {1.0f, 1.33f, 1.5f})
    for (float c : {-0.8f, -0.1f, 0.0f, 0.3f, 1.0f})
      EXPECT_EQ(fresnel_dielectric(c, eta), fresnel_dielectric<float>(c, eta));
  EXPECT_EQ(fresnel_dielectric(1, 1.5f), fresnel_dielectric<float>(1.0f, 1.5f));  // mixed int / float arguments
}

TEST(FresnelDielectricPrecision, FloatAgreesWithDouble) {
  for (double eta : {0.7, 1.0, 1.33, 2.4})
    for (double c = -1; c <= 1; c += 1.0 / 64) {
      // Near the critical cosine F has a square-root branch: compare away from it.
      const double cos_c = eta < 1 ? std::sqrt(1 - eta * eta) : (eta > 1 ? -std::sqrt(1 - 1 / (eta * eta)) : 2.0);
      if (std::abs(c - cos_c) < 1e-2) continue;
      EXPECT_NEAR(fresnel_dielectric(float(c), float(eta)), fresnel_dielectric<double>(c, eta), 2e-6)
          << eta << " " << c;
    }
}

// ---- the first moment and the diffuse reflectance ----

// Diffuse reflectance from inside (eta < 1, with total internal reflection) and from
// outside satisfy 1 - r_inside = (1 - r_outside) / eta^2 (radiance invariance n^2 L);
// the two integrals are computed independently (one is split at the critical angle).
TEST(FresnelMoment, DiffuseReflectanceStokesRelation) {
  for (double eta : {1.2, 1.4, 1.6}) {
    const double outside = fresnel_diffuse_reflectance(eta), inside = fresnel_diffuse_reflectance(1 / eta);
    EXPECT_NEAR(1 - inside, (1 - outside) / (eta * eta), 1e-9) << eta;
    // Against a plain midpoint rule with many points (smooth integrand for eta > 1).
    const int n = 200000;
    double midpoint = 0;
    for (int i = 0; i < n; ++i) {
      const double mu = (i + 0.5) / n;
      midpoint += 2 * fresnel_dielectric(mu, eta) * mu / n;
    }
    EXPECT_NEAR(outside, midpoint, 1e-8) << eta;
  }
  EXPECT_NEAR(fresnel_diffuse_reflectance(1.0), 0.0, 1e-15);
}

TEST(FresnelMoment, DiffuseReflectanceIsTwiceTheFirstMoment) {
  for (double eta : {0.6, 1.0, 1.33, 2.0}) EXPECT_EQ(fresnel_diffuse_reflectance(eta), 2 * fresnel_moment1(eta));
  // eta < 1: at least the totally reflected part mu_c^2 / 2 of the moment, at most 1/2.
  for (double eta : {0.5, 0.75, 0.9}) {
    EXPECT_GT(fresnel_moment1(eta), (1 - eta * eta) / 2);
    EXPECT_LT(fresnel_moment1(eta), 0.5);
  }
}

// The second moment against a fine midpoint sum of its definition, on both sides of the
// interface (with total internal reflection for eta < 1), and the zeroth moment at
// eta = 1 (no reflection) and its totally reflected share mu_c for eta < 1.
TEST(FresnelMoment, SecondMomentMatchesItsDefinition) {
  for (double eta : {0.6, 1 / 1.33, 1.33, 1.5}) {
    const int n = 2000000;
    double midpoint = 0;
    for (int k = 0; k < n; ++k) {
      const double mu = (k + 0.5) / n;
      midpoint += fresnel_dielectric(mu, eta) * mu * mu / n;
    }
    EXPECT_NEAR(fresnel_moment(2, eta), midpoint, 1e-7) << eta;
  }
  EXPECT_EQ(fresnel_moment(1, 1.4), fresnel_moment1(1.4));
  EXPECT_NEAR(fresnel_moment(0, 1.0), 0.0, 1e-12);  // F(mu, 1) is rounding
  EXPECT_GT(fresnel_moment(0, 0.75), std::sqrt(1 - 0.75 * 0.75));
}

// ---- conductors ----

TEST(FresnelConductor, WithoutAbsorptionIsADielectric) {
  for (float c : {0.1f, 0.5f, 1.0f}) EXPECT_NEAR(fresnel_conductor(c, 1.5f, 0.0f), fresnel_dielectric(c, 1.5f), 1e-5);
}

TEST(FresnelConductor, NormalIncidenceMatchesClosedForm) {
  float n = 0.2f, k = 3.9f;  // ((n-1)^2 + k^2) / ((n+1)^2 + k^2)
  EXPECT_NEAR(fresnel_conductor(1, n, k), (sqr(n - 1) + k * k) / (sqr(n + 1) + k * k), 1e-5);
}

// ---- directions ----

TEST(Refract, ObeysSnellsLaw) {
  Vec3 n{0, 0, 1};
  Vec3 wo = normalize(Vec3(0.6f, 0, 0.8f));
  auto wt = refract(wo, n, 1.5f);
  ASSERT_TRUE(wt);
  EXPECT_NEAR(length(*wt), 1, 1e-5);
  float sin_i = 0.6f, sin_t = std::sqrt(1 - sqr(wt->z));
  EXPECT_NEAR(sin_i, 1.5f * sin_t, 1e-5);
  EXPECT_LT(wt->z, 0);
  EXPECT_LT(wt->x, 0);  // continues to the other side of the normal
  // From inside beyond the critical angle: nothing.
  EXPECT_FALSE(refract(normalize(Vec3(0.9f, 0, -0.436f)), n, 1.5f));
}

TEST(Reflect, MirrorsAboutTheNormal) {
  const Vec3 n = normalize(Vec3(0.2f, -0.3f, 0.9f)), wo = normalize(Vec3(0.5f, 0.1f, 0.4f));
  const Vec3 wi = reflect(wo, n);
  EXPECT_NEAR(dot(wi, n), dot(wo, n), 1e-6);
  EXPECT_NEAR(length(wi + wo - n * (2 * dot(wo, n))), 0, 1e-6);
}

}  // namespace
}  // namespace dermis
