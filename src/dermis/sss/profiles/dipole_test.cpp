#include "dermis/sss/profiles/dipole.h"

#include <gtest/gtest.h>

#include "dermis/sss/profiles/profile_test_support.h"

namespace dermis::sss {
namespace {

TEST(ProfileDipole, IntegratesToAlbedoAndSamplesItsPdf) {
  uint64_t seed = 300;
  for (double a : {0.1, 0.5, 0.9, 0.99})
    testing::expect_consistent_profile(DipoleProfile::from_albedo(a, 0.5, 1.3), "dipole A=" + std::to_string(a),
                                       seed++);
  testing::expect_consistent_profile(DipoleProfile::from_coefficients(0.02, 2.0, 0.3, 1.5), "dipole coefficients",
                                     seed++);
}

TEST(ProfileDipole, PlaneIntegralEqualsClosedFormTotalReflectance) {
  // The integral of Jensen's eq. 4 over the plane equals the closed form R_d (Jensen &
  // Buehler 2002, eq. 3) exactly: int 2 pi r z (1 + s d) e^{-s d} / d^3 dr = 2 pi e^{-s z}.
  for (double eta : {1.0, 1.3, 1.8})
    for (double alpha : {0.05, 0.5, 0.9, 0.999}) {
      const DipoleProfile p = DipoleProfile::from_coefficients(1 - alpha, alpha, 0.0, eta);
      const double quadrature = testing::plane_integral(p);
      EXPECT_NEAR(quadrature / dipole_total_reflectance(alpha, eta), 1.0, 1e-7) << "alpha' " << alpha;
      EXPECT_NEAR(p.albedo() / dipole_total_reflectance(alpha, eta), 1.0, 1e-12);
      // The closed-form energy inside r matches quadrature too.
      for (double r : {0.3, 2.0, 10.0})
        EXPECT_NEAR(p.energy_within(r), integrate([&](double x) { return 2 * kPiD * x * p.eval(x); }, 0, r, 1e-13),
                    1e-10);
    }
}

TEST(ProfileDipole, AlbedoAndMeanFreePathRoundTrip) {
  // (A, l) -> (sigma_a, sigma_s') -> (A, l).
  for (double eta : {1.0, 1.3, 1.6})
    for (double a : {0.01, 0.1, 0.5, 0.9, 0.99}) {
      const DipoleProfile p = DipoleProfile::from_albedo(a, 0.7, eta);
      const DipoleCoefficients c = p.coefficients();
      const DipoleProfile q = DipoleProfile::from_coefficients(c.sigma_a, c.sigma_s_reduced, 0.0, eta);
      EXPECT_NEAR(q.albedo(), a, 1e-6 * a);
      EXPECT_NEAR(q.mean_free_path(), 0.7, 1e-6 * 0.7);
    }
  // (sigma_a, sigma_s, g) -> (A, l) -> (sigma_a, sigma_s (1 - g)).
  for (double sa : {0.001, 0.1, 2.0})
    for (double ss : {0.5, 10.0}) {
      const double g = 0.4;
      const DipoleProfile p = DipoleProfile::from_coefficients(sa, ss, g, 1.4);
      const DipoleCoefficients c = DipoleProfile::from_albedo(p.albedo(), p.mean_free_path(), 1.4).coefficients();
      EXPECT_NEAR(c.sigma_a, sa, 1e-6 * sa);
      EXPECT_NEAR(c.sigma_s_reduced, ss * (1 - g), 1e-6 * ss);
    }
}

TEST(ProfileDipole, TotalReflectanceIsMonotoneAndInverted) {
  double previous = 0;
  for (int i = 1; i <= 100; ++i) {
    const double alpha = i / 100.0;
    const double r = dipole_total_reflectance(alpha, 1.3);
    EXPECT_GT(r, previous);
    previous = r;
    EXPECT_NEAR(dipole_reduced_albedo_from_reflectance(r, 1.3), alpha, 1e-12);
  }
  EXPECT_NEAR(dipole_total_reflectance(1.0, 1.3), 1.0, 1e-15);
  // F_dr(1) of the Egan & Hilgeman fit is close to zero (index-matched boundary).
  EXPECT_NEAR(dipole_fresnel_diffuse_reflectance(1.0), 0.0016, 1e-12);
}

TEST(ProfileDipole, TruncationKeepsTheStatedFraction) {
  const DipoleProfile p = DipoleProfile::from_albedo(0.8, 2.0, 1.3, 0.995);
  EXPECT_NEAR(testing::truncated_integral(p) / p.albedo(), 0.995, 1e-9);
}

TEST(ProfileDipole, RejectsBadParameters) {
  EXPECT_THROW(DipoleProfile::from_albedo(0.0, 1.0, 1.3), std::invalid_argument);
  EXPECT_THROW(DipoleProfile::from_albedo(0.5, -1.0, 1.3), std::invalid_argument);
  EXPECT_THROW(DipoleProfile::from_albedo(0.5, 1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(DipoleProfile::from_coefficients(0.0, 0.0, 0.0, 1.3), std::invalid_argument);
  EXPECT_THROW(DipoleProfile::from_coefficients(0.1, 1.0, 1.0, 1.3), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
