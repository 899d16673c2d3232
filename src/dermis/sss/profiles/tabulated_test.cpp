#include "dermis/sss/profiles/tabulated.h"

#include <gtest/gtest.h>

#include <map>

#include "dermis/sss/profiles/profile_test_support.h"

namespace dermis::sss {
namespace {

const std::shared_ptr<const ProfileTable>& dipole_table(double eta) {
  static std::map<double, std::shared_ptr<const ProfileTable>> tables;
  auto& t = tables[eta];
  if (!t) t = std::make_shared<const ProfileTable>(dipole_family(eta));
  return t;
}

const std::shared_ptr<const ProfileTable>& burley_table() {
  static const auto t = std::make_shared<const ProfileTable>(burley_family());
  return t;
}

// Largest relative difference between the table and the analytic profile over the
// radii carrying the middle 99% of the energy [r(0.005), r(0.995)], 400 log-spaced radii.
double max_relative_error(const RadialProfile& table, const RadialProfile& analytic) {
  const double lo = analytic.r_max(0.005), hi = analytic.r_max(0.995);
  double worst = 0;
  for (int i = 0; i <= 400; ++i) {
    const double r = lo * std::pow(hi / lo, i / 400.0);
    worst = std::max(worst, std::abs(table.eval(r) / analytic.eval(r) - 1));
  }
  return worst;
}

// Albedos half-way between nodes of the default grid (node indices 3, 40, 80, 120, 150, 158).
std::vector<double> between_nodes(const ProfileTable& table) {
  std::vector<double> a;
  for (int j : {3, 40, 80, 120, 150, 158}) a.push_back(0.5 * (table.albedos()[j] + table.albedos()[j + 1]));
  return a;
}

TEST(ProfileTabulated, MatchesTheDipoleItWasBuiltFrom) {
  for (double eta : {1.0, 1.3, 1.6})
    for (double a : between_nodes(*dipole_table(eta))) {
      const TabulatedProfile t(dipole_table(eta), a, 0.6);
      const DipoleProfile d = DipoleProfile::from_albedo(a, 0.6, eta);
      EXPECT_LT(max_relative_error(t, d), 1e-3) << "eta " << eta << " A " << a;
      // Sampling is truncated where 99.9% of the table's energy is kept (TabulatedProfile's
      // default): the dipole's energy inside that radius is 0.999 of the table's.
      EXPECT_NEAR(0.999 * t.albedo() / d.energy_within(t.r_max()), 1.0, 1e-3) << "eta " << eta << " A " << a;
    }
  // eta matters: the dipoles at eta 1.0 and 1.6 differ by far more than the tolerance, so
  // matching each table to its own eta above is discriminating.
  const DipoleProfile a = DipoleProfile::from_albedo(0.5, 1.0, 1.0), b = DipoleProfile::from_albedo(0.5, 1.0, 1.6);
  EXPECT_GT(std::abs(a.eval(0.01) / b.eval(0.01) - 1), 10e-3);
}

TEST(ProfileTabulated, MatchesTheBurleyProfileItWasBuiltFrom) {
  for (double a : between_nodes(*burley_table())) {
    const TabulatedProfile t(burley_table(), a, 2.5);
    const BurleyProfile b(a, 2.5);
    EXPECT_LT(max_relative_error(t, b), 1e-3) << "A " << a;
    EXPECT_NEAR(t.albedo(), a, 1e-3 * a);
  }
}

TEST(ProfileTabulated, IntegratesToAlbedoAndSamplesItsPdf) {
  uint64_t seed = 500;
  for (double a : {0.1, 0.5, 0.9}) {
    testing::expect_consistent_profile(TabulatedProfile(dipole_table(1.3), a, 0.4),
                                       "tabulated dipole A=" + std::to_string(a), seed++);
    testing::expect_consistent_profile(TabulatedProfile(burley_table(), a, 3.0),
                                       "tabulated burley A=" + std::to_string(a), seed++);
  }
}

TEST(ProfileTabulated, AnyProfileFromATwoArgumentFunction) {
  // A Gaussian family A G(0.25, r) and a cubic family, on a coarse custom grid.
  ProfileTableOptions options;
  options.albedos = {0.1, 0.4, 0.7, 1.0};
  const auto gaussian = std::make_shared<const ProfileTable>(
      std::function<double(double, double)>([](double a, double r) { return a * gaussian_2d(0.25, r); }), options);
  const TabulatedProfile t(gaussian, 0.55, 2.0);
  const GaussianProfile g(0.25 * 4, 0.55);  // l = 2 scales the variance by 4
  EXPECT_LT(max_relative_error(t, g), 1e-3);
  testing::expect_consistent_profile(t, "tabulated gaussian", 600);
  const auto cubic = std::make_shared<const ProfileTable>(
      std::function<double(double, double)>([](double a, double r) { return CubicProfile(1.0, a).eval(r); }), options);
  testing::expect_consistent_profile(TabulatedProfile(cubic, 0.3, 1.0), "tabulated cubic", 601);
}

TEST(ProfileTabulated, RejectsBadParameters) {
  EXPECT_THROW(TabulatedProfile(burley_table(), 0.001, 1.0), std::invalid_argument);
  EXPECT_THROW(TabulatedProfile(burley_table(), 0.5, 0.0), std::invalid_argument);
  ProfileTableOptions bad;
  bad.albedos = {0.5, 0.2};
  EXPECT_THROW(ProfileTable(burley_family(), bad), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
