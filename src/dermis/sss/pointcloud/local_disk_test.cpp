#include "dermis/sss/pointcloud/local_disk.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dermis/core/rng.h"
#include "dermis/sss/pointcloud/local_disk_weight.h"

namespace dermis::sss::pointcloud {
namespace {

TEST(LocalDisk, WeightsAreSmoothAndSumToOne) {
  EXPECT_EQ(local_weight(0, 2), 1.0);
  EXPECT_EQ(local_weight(2, 2), 0.0);
  EXPECT_EQ(local_weight(3, 2), 0.0);
  for (double r = 0; r < 3; r += 0.1) EXPECT_DOUBLE_EQ(local_weight(r, 2) + global_weight(r, 2), 1.0);
  EXPECT_EQ(global_weight(0.5, 0.0), 1.0);
}

// For a Gaussian of variance v, with c = alpha^2 / (2v) and u = r^2,
// 2 pi int_0^alpha (1 - r^2/alpha^2)^2 G r dr = c int_0^1 (1-s)^2 e^{-cs} ds
//   = 1 - 2/c + 2/c^2 - 2 e^{-c}/c^2 = c sum_n (-c)^n / n! 2 / ((n+1)(n+2)(n+3)).
double gaussian_local_albedo(double c) {
  if (c > 2) return 1 - 2 / c + 2 / (c * c) - 2 * std::exp(-c) / (c * c);
  double sum = 0, term = 1;  // (-c)^n / n!
  for (int n = 0; n < 60; ++n, term *= -c / n) sum += term * 2 / ((n + 1.0) * (n + 2) * (n + 3));
  return c * sum;
}
TEST(LocalDisk, TableMatchesTheClosedFormForAGaussian) {
  const double v = 0.3;
  const LocalDiskTable table(GaussianProfile(v, 1.0));
  Rng rng(5, 5);
  for (int i = 0; i < 200; ++i) {
    const double alpha = table.alpha_min() * std::pow(table.alpha_max() / table.alpha_min(), rng.uniform_double());
    const double c = alpha * alpha / (2 * v);
    const double exact = gaussian_local_albedo(c);
    EXPECT_NEAR(table.integrate_directly(alpha), exact, 1e-9 * exact + 1e-15) << alpha;
    EXPECT_NEAR(table.local_albedo(alpha), exact, 2e-4 * exact) << alpha;
  }
}

// The table interpolates the direct quadrature (dipole and Burley, singular-ish at 0) and
// tends to the albedo for a disk much larger than the profile.
TEST(LocalDisk, TableMatchesQuadratureAndTendsToTheAlbedo) {
  for (const RadialProfile& p :
       {RadialProfile(DipoleProfile::from_albedo(0.8, 0.1, 1.3)), RadialProfile(BurleyProfile(0.6, 0.1))}) {
    const LocalDiskTable table(p);
    Rng rng(6, 6);
    for (int i = 0; i < 100; ++i) {
      const double alpha = table.alpha_min() * std::pow(table.alpha_max() / table.alpha_min(), rng.uniform_double());
      const double direct = table.integrate_directly(alpha);
      EXPECT_NEAR(table.local_albedo(alpha), direct, 2e-4 * direct) << alpha;
    }
    EXPECT_NEAR(table.local_albedo(table.alpha_max()), p.albedo(), 1e-4 * p.albedo());
    EXPECT_LT(table.local_albedo(0.5 * p.r_max(0.5)), 0.5 * p.albedo());
  }
}

}  // namespace
}  // namespace dermis::sss::pointcloud
