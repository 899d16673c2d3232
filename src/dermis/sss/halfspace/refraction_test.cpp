#include "dermis/sss/halfspace/refraction.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dermis/core/fresnel.h"

namespace dermis::sss {
namespace {

// Reciprocity: the same interface seen from either side, F(theta_i, eta) = F(theta_t, 1/eta),
// with theta_t from refract_through_plane.
TEST(HalfspaceRefraction, SnellAndFresnelReciprocity) {
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

}  // namespace
}  // namespace dermis::sss
