#include "dermis/sss/halfspace/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>

namespace dermis::sss {
namespace {

TEST(HalfspaceFresnel, NormalIncidenceAndLimits) {
  for (double eta : {1.0, 1.33, 1.4, 0.7}) {
    EXPECT_NEAR(fresnel_dielectric(1.0, eta), std::pow((eta - 1) / (eta + 1), 2), 1e-15);  // Born & Wolf 1.5.2
    EXPECT_NEAR(fresnel_dielectric(0.0, eta), 1.0, 1e-15);  // grazing
  }
  EXPECT_NEAR(fresnel_dielectric(0.3, 1.0), 0.0, 1e-30);  // index-matched: no reflection
  // Total internal reflection beyond the critical angle, sin(theta_c) = eta < 1.
  const double cos_c = std::sqrt(1 - 0.7 * 0.7);
  EXPECT_EQ(fresnel_dielectric(cos_c - 1e-9, 0.7), 1.0);
  EXPECT_LT(fresnel_dielectric(cos_c + 1e-3, 0.7), 1.0);
}

// Reciprocity: the same interface seen from either side, F(theta_i, eta) = F(theta_t, 1/eta).
TEST(HalfspaceFresnel, Reciprocity) {
  for (double eta : {1.4, 2.0, 0.8}) {
    for (double cos_i : {0.05, 0.3, 0.6, 0.95}) {
      const double sin_i = std::sqrt(1 - cos_i * cos_i);
      Vec3d d{sin_i, 0, -cos_i}, t;
      if (!refract_through_plane(d, eta, t)) continue;
      EXPECT_NEAR(std::sqrt(t.x * t.x + t.y * t.y) * eta, sin_i, 1e-15);  // Snell
      EXPECT_NEAR(length(t), 1.0, 1e-15);
      EXPECT_LT(t.z, 0);
      EXPECT_NEAR(fresnel_dielectric(cos_i, eta), fresnel_dielectric(-t.z, 1 / eta), 1e-13);
    }
  }
}

// Diffuse reflectance from inside (eta < 1, with total internal reflection) and from
// outside satisfy 1 - r_inside = (1 - r_outside) / eta^2 (radiance invariance n^2 L);
// the two integrals are computed independently (one is split at the critical angle).
TEST(HalfspaceFresnel, DiffuseReflectanceStokesRelation) {
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

}  // namespace
}  // namespace dermis::sss
