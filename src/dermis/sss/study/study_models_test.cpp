#include "dermis/sss/study/study_models.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dermis/sss/profiles/burley.h"
#include "dermis/sss/profiles/dipole.h"

namespace dermis::sss {
namespace {

// Burley's unfitted profile has the C-B radial CDF with d = 1: the annulus mean times the
// annulus area is A (F(hi) - F(lo)), F(r) = 1 - e^{-r}/4 - 3 e^{-r/3}/4 (Christensen &
// Burley 2015, sec. 3). Checks annulus_mean's quadrature, including the first bin [0, r).
TEST(StudyModels, AnnulusMeanOfBurleyMatchesItsCdf) {
  const double a = 0.37;
  // F(hi) - F(lo), written without the cancellation of 1 - ... far out.
  auto energy = [](double lo, double hi) {
    return 0.25 * (std::exp(-lo) - std::exp(-hi)) + 0.75 * (std::exp(-lo / 3) - std::exp(-hi / 3));
  };
  auto R = [a](double r) { return burley_unfitted(a, r); };
  const double edges[][2] = {{0, 0.005}, {0.005, 0.0057}, {0.3, 0.4}, {1, 1.3}, {10, 14}, {100, 130}};
  for (const auto& e : edges) {
    const double area = kPiD * (e[1] * e[1] - e[0] * e[0]);
    const double expected = a * energy(e[0], e[1]);
    EXPECT_NEAR(annulus_mean(R, e[0], e[1]) * area / expected, 1.0, 1e-10) << e[0] << " " << e[1];
  }
}

// The dipole's closed-form energy_within checks the same for a different shape.
TEST(StudyModels, AnnulusMeanOfDipoleMatchesItsEnergy) {
  const DipoleProfile d = DipoleProfile::from_albedo(0.6, 1.0, 1.0);
  auto R = [&](double r) { return d.eval(r); };
  for (double lo : {0.0, 0.01, 0.5, 3.0}) {
    const double hi = lo == 0 ? 0.01 : lo * 1.15;
    const double area = kPiD * (hi * hi - lo * lo);
    EXPECT_NEAR(annulus_mean(R, lo, hi) * area / (d.energy_within(hi) - d.energy_within(lo)), 1.0, 1e-9) << lo;
  }
}

// Each model at A = 0.5, l = 1: the C-B fits are the BurleyProfile with their scales, the
// two C-B forms agree for A <= 0.8 and differ above it, and the tabulated dipole follows
// the analytic dipole (its table's own accuracy, tabulated_test.cpp, is 1e-3-ish).
TEST(StudyModels, ModelsAreWhatTheyClaim) {
  const auto table = study_profile_table(1.0);
  const auto models = study_models(0.5, 1.0, table);
  ASSERT_EQ(models.size(), 5u);
  EXPECT_EQ(models[0].key, "burley_s1");
  const BurleyProfile cb(0.5, 1.0, BurleyParameterisation::VolumeMeanFreePath);
  const DipoleProfile dip = DipoleProfile::from_albedo(0.5, 1.0, 1.0);
  for (double r : {0.01, 0.3, 2.0, 9.0}) {
    EXPECT_DOUBLE_EQ(models[0].eval(r), 0.5 * (std::exp(-r) + std::exp(-r / 3)) / (8 * kPiD * r));
    EXPECT_DOUBLE_EQ(models[1].eval(r), cb.eval(r));
    EXPECT_DOUBLE_EQ(models[2].eval(r), cb.eval(r));  // same s below A = 0.8
    EXPECT_DOUBLE_EQ(models[3].eval(r), dip.eval(r));
    EXPECT_NEAR(models[4].eval(r) / dip.eval(r), 1.0, 5e-3) << r;
  }
  const auto high = study_models(0.95, 1.0, table);
  EXPECT_NE(high[1].eval(1.0), high[2].eval(1.0));
}

}  // namespace
}  // namespace dermis::sss
