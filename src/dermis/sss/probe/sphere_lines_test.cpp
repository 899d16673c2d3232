// Tests of the sphere-line probe sampler (the Cycles page after Walter et al. 2012,
// App. B; METHODS 2.2): the radius table, q(d) ∝ R(d) - R(rho_max), the exact expected
// number of crossings per line on planes, chi-square of hit positions against q(d), the
// unbiased flat-plane and curved-surface estimators, and the retry variant's bias.
#include "dermis/sss/probe/sphere_lines.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "dermis/sss/probe/probe_test_support.h"
#include "support/chi_square.h"

namespace dermis::sss {
namespace {

using testing::integrate_pieces;
using testing::MeanAndError;
using testing::TestPlane;

struct NamedProfile {
  std::string name;
  ProfileRGB profile;
  RGB weights;
};

std::vector<NamedProfile> test_profiles() {
  return {
      {"gaussian", make_gaussian_rgb(RGB(0.8f, 0.6f, 0.4f), RGB(0.04f, 0.09f, 0.25f)), RGB(0.8f, 0.6f, 0.4f)},
      {"skin", make_skin_rgb(1.0), RGB(1.0f, 0.7f, 0.5f)},
      {"burley", make_burley_rgb(RGB(0.8f, 0.5f, 0.3f), RGB(0.5f, 0.3f, 0.2f)), RGB(1.0f)},
      {"dipole", make_dipole_rgb(RGB(0.8f, 0.5f, 0.3f), RGB(0.3f, 0.2f, 0.1f), 1.3), RGB(0.8f, 0.5f, 0.3f)},
  };
}

const Vec3d kP(0.2, -0.4, 0.1);

// Energy of R within rho: int_0^rho R(r) 2 pi r dr by adaptive quadrature, split
// geometrically towards 0 (where Burley's 1/r lives).
double energy_within(const RadialProfile& p, double rho) {
  std::vector<double> breaks;
  for (double x = rho; x > 1e-9 * rho; x *= 0.25) breaks.push_back(x);
  return integrate_pieces([&](double r) { return 2 * kPiD * r * p.eval(r); }, 0, rho, breaks, 1e-13);
}

TEST(SphereLines, RadiusTableIsNormalisedAndSampled) {
  uint64_t seed = 10;
  for (const auto& [name, profile, weights] : test_profiles()) {
    const SphereLineTablesRGB tables(profile, 256);
    for (int c = 0; c < 3; ++c) {
      const SphereLineTable& t = tables.channel[c];
      const double rho_max = t.rho_max();
      auto edge = [&](int k) { return rho_max * double(k) / t.bins() * double(k) / t.bins(); };
      // Midpoint rule on the table's own bins is exact for a piecewise-constant density.
      double total = 0;
      constexpr int kCoarse = 32;
      std::vector<double> expected(kCoarse, 0.0), observed(kCoarse, 0.0);
      for (int k = 0; k < t.bins(); ++k) {
        const double mass = t.pdf_radius(0.5 * (edge(k) + edge(k + 1))) * (edge(k + 1) - edge(k));
        total += mass;
        expected[k * kCoarse / t.bins()] += mass;
      }
      EXPECT_NEAR(total, 1.0, 1e-12) << name << " channel " << c;
      EXPECT_EQ(t.pdf_radius(rho_max * 1.001), 0.0);
      constexpr int kSamples = 100000;
      for (double& e : expected) e *= kSamples / total;
      Rng rng(++seed, 4);
      for (int s = 0; s < kSamples; ++s) {
        const double rho = t.sample_radius(rng.uniform_double());
        ASSERT_TRUE(rho >= 0 && rho <= rho_max);
        observed[std::min(int(std::sqrt(rho / rho_max) * kCoarse), kCoarse - 1)] += 1;
      }
      const auto result = dermis::testing::chi_square(observed, expected);
      EXPECT_GT(result.p_value, dermis::testing::kChiSquareAlpha)
          << name << " channel " << c << ": chi-square " << result.statistic << " dof " << result.dof;
    }
  }
}

// With p ∝ -rho^2 R', q(d) = (R(d) - R(rho_max)) / (2 (E - pi rho_max^2 R(rho_max))), E the
// energy within rho_max (integration by parts; docs/probe-sampling.md). The table (1024
// bins) must agree to 1e-3 of q(1e-3 rho_max) (measured: <= 2.5e-4) wherever d >= 1e-3 rho_max.
TEST(SphereLines, HitDensityIsProportionalToTheProfileDrop) {
  const ProfileRGB cubic = make_cubic_rgb(RGB(0.8f), RGB(1.5f, 1.0f, 0.5f));
  auto profiles = test_profiles();
  profiles.push_back({"cubic", cubic, RGB(1.0f)});
  for (const auto& [name, profile, weights] : profiles) {
    const SphereLineTablesRGB tables(profile);
    for (int c = 0; c < 3; ++c) {
      const SphereLineTable& t = tables.channel[c];
      const RadialProfile& p = profile[c];
      const double rho_max = t.rho_max(), r_end = p.eval(rho_max);
      const double e = energy_within(p, rho_max);
      EXPECT_NEAR(t.energy_within(), e, 1e-7 * e) << name;  // 16-point Gauss-Legendre per bin
      const double norm = 2 * (e - kPiD * rho_max * rho_max * r_end);
      const double scale = (p.eval(1e-3 * rho_max) - r_end) / norm;
      double worst = 0;
      for (int i = 0; i <= 400; ++i) {
        const double d = rho_max * std::pow(10.0, -3.0 + 3.0 * i / 400) * 0.9999;
        const double analytic = (p.eval(d) - r_end) / norm;
        worst = std::max(worst, std::abs(t.hit_density(d) - analytic) / scale);
      }
      EXPECT_LT(worst, 1e-3) << name << " channel " << c;
      EXPECT_EQ(t.hit_density(rho_max), 0.0);
    }
  }
}

// Crossings per line of the plane at distance h from P: for a fixed rho the plane cuts a
// disk of area pi (rho^2 - h^2) out of the sphere, crossed 1/(2 pi rho^2) times per unit
// area, so E = int_h^rho_max p(rho) (1 - h^2 / rho^2) / 2 d rho; for h = 0 exactly 1/2 for
// every p. Checked three ways: that formula (quadrature of the table's p), the quadrature
// of q over the plane, and a Monte Carlo count of crossings (4 sigma).
TEST(SphereLines, ExpectedCrossingsPerLineOnPlanes) {
  uint64_t seed = 20;
  for (const auto& [name, profile, weights] : test_profiles()) {
    const SphereLineTablesRGB tables(profile);
    const SphereLineSampler sampler(tables, weights);
    const double rho_max = sampler.max_radius();
    for (double h_frac : {0.0, 0.1, 0.3}) {
      const double h = h_frac * rho_max;
      double formula = 0;
      for (int c = 0; c < 3; ++c) {
        const SphereLineTable& t = tables.channel[c];
        std::vector<double> edges;
        for (int k = 0; k <= t.bins(); ++k) edges.push_back(t.rho_max() * k * k / (double(t.bins()) * t.bins()));
        if (h < t.rho_max())
          formula += sampler.channel_probability(c) *
                     integrate_pieces([&](double rho) { return t.pdf_radius(rho) * (1 - h * h / (rho * rho)) / 2; }, h,
                                      t.rho_max(), edges, 1e-13);
      }
      if (h == 0) {
        EXPECT_NEAR(formula, 0.5, 1e-10) << name;
      }
      const Vec3d n = normalize(Vec3d(0.3, -0.5, 0.8));
      const TestPlane plane(kP + n * h, n);
      const double s_max = std::sqrt(rho_max * rho_max - h * h);
      std::vector<double> breaks;
      for (double x = s_max; x > 1e-9 * s_max; x *= 0.5) breaks.push_back(x);
      const double over_plane = integrate_pieces(
          [&](double s) { return sampler.pdf_area(kP, plane.point(s, 0.4)) * 2 * kPiD * s; }, 0, s_max, breaks, 1e-12);
      EXPECT_NEAR(over_plane, formula, 1e-6) << name << " h " << h;
      MeanAndError crossings;
      Rng rng(++seed, 5);
      for (int k = 0; k < 40000; ++k) {
        const auto smp = sampler.sample(kP, rng.uniform_double(), rng.uniform_double(),
                                        Vec2d(rng.uniform_double(), rng.uniform_double()),
                                        Vec2d(rng.uniform_double(), rng.uniform_double()));
        Vec3d x;
        crossings.add(testing::intersect(smp.segment, plane, &x) ? 1.0 : 0.0);
      }
      EXPECT_NEAR(crossings.mean(), formula, 4 * crossings.error()) << name << " h " << h;
    }
  }
}

// Chi-square of crossing positions against q(d) (channel MIS), bins in polar coordinates
// about the foot of P on the plane, plus a bin for lines that miss (a line crosses a
// plane at most once, so the counts are multinomial).
TEST(SphereLines, HitsOnPlanesMatchTheHitDensity) {
  uint64_t seed = 30;
  const auto profiles = test_profiles();
  for (int k : {1, 2}) {  // skin (channels of very different widths), burley
    const auto& [name, profile, weights] = profiles[k];
    const SphereLineTablesRGB tables(profile);
    const SphereLineSampler sampler(tables, weights);
    const double rho_max = sampler.max_radius();
    for (double h_frac : {0.0, 0.2}) {
      const Vec3d n = normalize(Vec3d(-0.4, 0.2, 0.9));
      const double h = h_frac * rho_max;
      const TestPlane plane(kP + n * h, n);
      const double s_max = std::sqrt(rho_max * rho_max - h * h);
      constexpr int kRadial = 12, kAngular = 6, kLines = 200000;
      std::vector<double> s_edges(kRadial + 1);
      // Edges at fractions of the energy of the widest channel (well-filled bins).
      for (int i = 0; i <= kRadial; ++i) s_edges[i] = s_max * std::pow(double(i) / kRadial, 3.0);
      std::vector<double> expected(kRadial * kAngular + 1), observed(kRadial * kAngular + 1, 0.0);
      double hit_total = 0;
      for (int i = 0; i < kRadial; ++i) {
        std::vector<double> breaks;
        for (double x = s_edges[i + 1]; x > std::max(s_edges[i], 1e-9 * s_max); x *= 0.5) breaks.push_back(x);
        const double radial = integrate_pieces([&](double s) { return sampler.pdf_area(kP, plane.point(s, 0.0)) * s; },
                                               s_edges[i], s_edges[i + 1], breaks, 1e-12);
        for (int j = 0; j < kAngular; ++j) {
          expected[i * kAngular + j] = radial * 2 * kPiD / kAngular * kLines;
          hit_total += radial * 2 * kPiD / kAngular;
        }
      }
      expected.back() = (1 - hit_total) * kLines;
      Rng rng(++seed, 6);
      for (int l = 0; l < kLines; ++l) {
        const auto smp = sampler.sample(kP, rng.uniform_double(), rng.uniform_double(),
                                        Vec2d(rng.uniform_double(), rng.uniform_double()),
                                        Vec2d(rng.uniform_double(), rng.uniform_double()));
        Vec3d x;
        if (!testing::intersect(smp.segment, plane, &x)) {
          observed.back() += 1;
          continue;
        }
        double s, psi;
        plane.polar(x, &s, &psi);
        const int i =
            std::min(int(std::upper_bound(s_edges.begin(), s_edges.end(), s) - s_edges.begin()) - 1, kRadial - 1);
        const int j = std::min(int(psi / (2 * kPiD) * kAngular), kAngular - 1);
        observed[i * kAngular + j] += 1;
      }
      const auto result = dermis::testing::chi_square(observed, expected);
      EXPECT_GT(result.p_value, dermis::testing::kChiSquareAlpha)
          << name << " h " << h << ": chi-square " << result.statistic << " dof " << result.dof;
    }
  }
}

// sum_hits R(d) / q(d) on a plane through P averages to the energy within rho_max
// (quadrature), within 4 sigma, per channel.
TEST(SphereLines, FlatPlaneEstimatorRecoversTheKeptEnergy) {
  uint64_t seed = 40;
  for (const auto& [name, profile, weights] : test_profiles()) {
    const SphereLineTablesRGB tables(profile);
    const SphereLineSampler sampler(tables, weights);
    const Vec3d n = normalize(Vec3d(0.2, 0.1, -1.0));
    const TestPlane plane(kP, n);
    for (bool folded : {false, true}) {  // the four-number form, and one number for channel and radius
      MeanAndError estimate[3];
      Rng rng(++seed, 7);
      for (int k = 0; k < 40000; ++k) {
        const double u0 = rng.uniform_double();
        const auto smp =
            folded ? sampler.sample(kP, u0, Vec2d(rng.uniform_double(), rng.uniform_double()),
                                    Vec2d(rng.uniform_double(), rng.uniform_double()))
                   : sampler.sample(kP, u0, rng.uniform_double(), Vec2d(rng.uniform_double(), rng.uniform_double()),
                                    Vec2d(rng.uniform_double(), rng.uniform_double()));
        Vec3d x;
        const bool hit = testing::intersect(smp.segment, plane, &x);
        for (int c = 0; c < 3; ++c)
          estimate[c].add(hit ? profile[c].eval(length(x - kP)) / sampler.pdf_area(kP, x) : 0.0);
      }
      for (int c = 0; c < 3; ++c) {
        const double kept = energy_within(profile[c], sampler.max_radius());
        EXPECT_NEAR(estimate[c].mean(), kept, 4 * estimate[c].error())
            << name << (folded ? " folded" : "") << " channel " << c << " kept/A " << kept / profile[c].albedo();
      }
    }
    // Folded, evenly spaced numbers give each channel its share (within one) and radii that
    // grow with the number: every channel's radii are stratified.
    constexpr int kNumbers = 3000;
    std::vector<double> radii[3];
    for (int j = 0; j < kNumbers; ++j) {
      const auto smp = sampler.sample(kP, (j + 0.5) / kNumbers, Vec2d(0.3, 0.6), Vec2d(0.7, 0.2));
      radii[smp.channel].push_back(smp.sphere_radius);
    }
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(double(radii[c].size()), sampler.channel_probability(c) * kNumbers, 1.0) << name << " channel " << c;
      EXPECT_TRUE(std::is_sorted(radii[c].begin(), radii[c].end())) << name << " channel " << c;
    }
  }
}

// Radius scales (textured parameters): a sampler over the tables of one profile,
// stretched by s_c, (a) has the hit density of the tables of the stretched profile
// R(r / s) / s^2 (Burley: the same profile family, so the tables must agree to
// rounding), and (b) estimates any other profile's energy on a plane without bias:
// here a dipole of other albedos and lengths, weighted by its own R(d) / q(d), within
// 4 sigma of the quadrature of that dipole within the scaled sampler's reach.
TEST(SphereLines, RadiusScalesStretchTheTablesExactly) {
  const RGB A(0.8f, 0.5f, 0.3f), l(0.5f, 0.3f, 0.2f);
  const std::array<double, 3> s{2.0, 0.5, 4.0};  // powers of 2: the stretched lengths exact in float
  const ProfileRGB unit = make_burley_rgb(A, l);
  const ProfileRGB stretched = make_burley_rgb(A, RGB(float(l[0] * s[0]), float(l[1] * s[1]), float(l[2] * s[2])));
  const SphereLineTablesRGB unit_tables(unit);
  const SphereLineSampler scaled(unit_tables, RGB(1.0f), s);
  for (int c = 0; c < 3; ++c) {
    // The stretched channel's own table on the scaled reach (the same edges, stretched).
    const SphereLineTable own(stretched[c], s[c] * unit_tables.channel[c].rho_max());
    const SphereLineTable& base = unit_tables.channel[c];
    for (double f : {1e-3, 0.01, 0.1, 0.3, 0.7, 0.99}) {
      const double d = f * own.rho_max();
      const double expected = own.hit_density(d);
      EXPECT_NEAR(base.hit_density(d / s[c]) / (s[c] * s[c]), expected, 1e-9 * expected)
          << "channel " << c << " d " << d;
    }
  }
  // (b) Another profile, estimated with the scaled sampler.
  const ProfileRGB other = make_dipole_rgb(RGB(0.6f, 0.7f, 0.2f), RGB(0.7f, 0.2f, 0.5f), 1.3);
  const Vec3d n = normalize(Vec3d(0.2, 0.1, -1.0));
  const TestPlane plane(kP, n);
  MeanAndError estimate[3];
  Rng rng(77, 7);
  for (int k = 0; k < 40000; ++k) {
    const auto smp =
        scaled.sample(kP, rng.uniform_double(), rng.uniform_double(), Vec2d(rng.uniform_double(), rng.uniform_double()),
                      Vec2d(rng.uniform_double(), rng.uniform_double()));
    Vec3d x;
    const bool hit = testing::intersect(smp.segment, plane, &x);
    for (int c = 0; c < 3; ++c) estimate[c].add(hit ? other[c].eval(length(x - kP)) / scaled.pdf_area(kP, x) : 0.0);
  }
  for (int c = 0; c < 3; ++c) {
    const double kept = energy_within(other[c], scaled.max_radius());
    EXPECT_NEAR(estimate[c].mean(), kept, 4 * estimate[c].error()) << "channel " << c;
  }
  EXPECT_THROW(SphereLineSampler(unit_tables, RGB(1.0f), {1, 0, 1}), std::invalid_argument);
}

// On a sphere of radius 0.3 rho_max through P (a small, curved object; lines can cross
// it twice) the unbiased estimator (every crossing counts) averages to int_S R(|x - P|) dA
// (quadrature), and the retry variant to its predicted biased value
//   (1 - (1 - pi_h)^8) I / (2 pi_h) + (1 - pi_h)^8 F,
// pi_h the probability that a line hits (measured), F the fallback weight; the retry is
// exact on the plane through P.
TEST(SphereLines, UnbiasedOnCurvedSurfacesRetryBiasedAsPredicted) {
  const ProfileRGB profile = make_burley_rgb(RGB(0.8f), RGB(0.5f));
  const SphereLineTablesRGB tables(profile);
  const SphereLineSampler sampler(tables);
  const double rho_max = sampler.max_radius();
  const double radius = 0.3 * rho_max;
  const Vec3d n(0, 0, 1);
  const Vec3d centre = kP - n * radius;
  const RadialProfile& p = profile[0];
  // I = int_S R(|x - P|) dA: |x - P| = 2 a sin(theta / 2) about the axis through P.
  std::vector<double> breaks;
  for (double x = kPiD; x > 1e-8; x *= 0.5) breaks.push_back(x);
  const double reference = integrate_pieces(
      [&](double theta) {
        const double d = 2 * radius * std::sin(theta / 2);
        return d < rho_max ? p.eval(d) * 2 * kPiD * radius * radius * std::sin(theta) : 0.0;
      },
      0, kPiD, breaks, 1e-13);
  constexpr int kLines = 100000;
  MeanAndError unbiased, any_hit;
  Rng rng(50, 8);
  for (int k = 0; k < kLines; ++k) {
    const auto smp = sampler.sample(kP, rng.uniform_double(), rng.uniform_double(),
                                    Vec2d(rng.uniform_double(), rng.uniform_double()),
                                    Vec2d(rng.uniform_double(), rng.uniform_double()));
    Vec3d x[2];
    const int hits = testing::intersect_sphere(smp.segment, centre, radius, x);
    double sum = 0;
    for (int h = 0; h < hits; ++h) sum += p.eval(length(x[h] - kP)) / sampler.pdf_area(kP, x[h]);
    unbiased.add(sum);
    any_hit.add(hits > 0);
  }
  EXPECT_NEAR(unbiased.mean(), reference, 4 * unbiased.error());

  MeanAndError retry;
  Rng retry_rng(51, 9);
  for (int k = 0; k < kLines; ++k) {
    Vec3d x[2];
    int found = 0;
    const auto r = sampler.sample_retry(kP, retry_rng, [&](const ProbeSegment& seg) {
      found = testing::intersect_sphere(seg, centre, radius, x);
      return found;
    });
    if (r.hits == 0) {
      retry.add(sampler.fallback_weight(0));
      continue;
    }
    const Vec3d hit = x[r.chosen];
    retry.add(SphereLineSampler::retry_weight(p.eval(length(hit - kP)), r.hits, sampler.pdf_area(kP, hit)));
  }
  auto predicted = [&](double pi_h) {
    const double miss = std::pow(1 - pi_h, SphereLineSampler::kRetryMaxLines);
    return (1 - miss) * reference / (2 * pi_h) + miss * sampler.fallback_weight(0);
  };
  const double pi_h = any_hit.mean();
  const double slope = (predicted(pi_h + 1e-4) - predicted(pi_h - 1e-4)) / 2e-4;
  const double sigma = std::hypot(retry.error(), slope * any_hit.error());
  EXPECT_NEAR(retry.mean(), predicted(pi_h), 4 * sigma) << "pi_h " << pi_h;
  EXPECT_GT(std::abs(retry.mean() - reference), 4 * retry.error()) << "the retry should be biased here";

  // On the plane through P the retry variant is exact: E = the energy within rho_max.
  const TestPlane plane(kP, n);
  MeanAndError on_plane;
  Rng plane_rng(52, 10);
  for (int k = 0; k < 40000; ++k) {
    Vec3d x;
    const auto r = sampler.sample_retry(
        kP, plane_rng, [&](const ProbeSegment& seg) { return testing::intersect(seg, plane, &x) ? 1 : 0; });
    on_plane.add(r.hits == 0 ? sampler.fallback_weight(0)
                             : SphereLineSampler::retry_weight(p.eval(length(x - kP)), 1, sampler.pdf_area(kP, x)));
  }
  EXPECT_NEAR(on_plane.mean(), energy_within(p, rho_max), 4 * on_plane.error());
}

TEST(SphereLines, RejectsBadInput) {
  const ProfileRGB p = make_gaussian_rgb(RGB(0.5f, 0.0f, 0.5f), RGB(1.0f));
  const SphereLineTablesRGB tables(p, 64);
  EXPECT_TRUE(tables.channel[1].is_empty());
  EXPECT_THROW(SphereLineSampler(tables, RGB(0.0f, 1.0f, 0.0f)), std::invalid_argument);  // only an empty channel
  EXPECT_THROW(SphereLineSampler(tables, RGB(1.0f, -1.0f, 1.0f)), std::invalid_argument);
  EXPECT_THROW(SphereLineTable(p[0], 0, 1), std::invalid_argument);
  const SphereLineSampler ok(tables, RGB(1.0f));
  EXPECT_EQ(ok.channel_probability(1), 0.0);
}

}  // namespace
}  // namespace dermis::sss
