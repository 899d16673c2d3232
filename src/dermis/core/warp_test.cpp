// Tests of the sampling warps: every pdf integrates to one over its domain
// (midpoint quadrature), and every sampler matches its pdf (Pearson chi-square).
#include "dermis/core/warp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "dermis/core/rng.h"
#include "support/chi_square.h"

namespace dermis {
namespace {

using testing::chi_square;
using testing::kChiSquareAlpha;

constexpr double kTwoPi = 2 * kPiD;

Vec3 direction(double theta, double phi) {
  return {float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta))};
}

// Midpoint rule for the integral of f(direction) dω over theta in [theta0, theta1],
// phi in [phi0, phi1] (dω = sin(theta) dtheta dphi).
double integrate_directions(const std::function<double(Vec3)>& f, double theta0, double theta1, int n_theta,
                            double phi0, double phi1, int n_phi) {
  const double dt = (theta1 - theta0) / n_theta, dp = (phi1 - phi0) / n_phi;
  double sum = 0;
  for (int i = 0; i < n_theta; ++i) {
    const double theta = theta0 + (i + 0.5) * dt;
    for (int j = 0; j < n_phi; ++j) sum += f(direction(theta, phi0 + (j + 0.5) * dp)) * std::sin(theta);
  }
  return sum * dt * dp;
}

// The midpoint rule's error is O(h^2): with 2048 theta steps it is far below 1e-5 for
// these smooth integrands (the sharper HG lobe is tested in henyey_greenstein_test.cpp).
// The integrands do not depend on phi, so the phi rule is exact. 1e-3 therefore only
// leaves room for float evaluation of the pdfs.
constexpr int kThetaSteps = 2048, kPhiSteps = 8;
constexpr double kIntegralTolerance = 1e-3;

double integrate_over_cap(const std::function<double(Vec3)>& f, double theta_max) {
  return integrate_directions(f, 0, theta_max, kThetaSteps, 0, kTwoPi, kPhiSteps);
}

const float kConeCosines[] = {-0.5f, 0.0f, 0.5f, 0.9f, 0.999f};

TEST(WarpPdf, CosineHemisphereIntegratesToOne) {
  auto pdf = [](Vec3 w) { return double(cosine_hemisphere_pdf(w.z)); };
  EXPECT_NEAR(integrate_over_cap(pdf, kPiD / 2), 1.0, kIntegralTolerance);
  EXPECT_EQ(integrate_directions(pdf, kPiD / 2, kPiD, 64, 0, kTwoPi, 8), 0.0);  // nothing below
}

TEST(WarpPdf, UniformSphereIntegratesToOne) {
  EXPECT_NEAR(integrate_over_cap([](Vec3) { return double(uniform_sphere_pdf()); }, kPiD), 1.0, kIntegralTolerance);
}

TEST(WarpPdf, UniformConeIntegratesToOne) {
  for (float cos_max : kConeCosines) {
    const double pdf = uniform_cone_pdf(cos_max);
    EXPECT_NEAR(integrate_over_cap([pdf](Vec3) { return pdf; }, std::acos(double(cos_max))), 1.0, kIntegralTolerance)
        << "cos_max " << cos_max;
  }
}

// ---- chi-square tests of the samplers ----

constexpr int kSamples = 200'000;
constexpr int kThetaBins = 20, kPhiBins = 40;

double phi_of(Vec3 w) {
  double phi = std::atan2(double(w.y), double(w.x));
  return phi < 0 ? phi + kTwoPi : phi;
}

// Samples a direction sampler into a theta x phi grid over theta in [0, theta_max] and
// compares against expected counts from integrating pdf over each cell (midpoint rule,
// 16 x 4 points per cell; the pdfs are smooth within a cell). Directions must be unit
// length and lie within theta_max.
void expect_direction_sampler_matches_pdf(const std::function<Vec3(Vec2)>& sample,
                                          const std::function<double(Vec3)>& pdf, double theta_max, uint64_t seed) {
  std::vector<double> observed(kThetaBins * kPhiBins, 0.0), expected(kThetaBins * kPhiBins, 0.0);
  const double dt = theta_max / kThetaBins, dp = kTwoPi / kPhiBins;
  Rng rng(seed, 0);
  int outside = 0;
  for (int s = 0; s < kSamples; ++s) {
    Vec2 u{rng.uniform(), rng.uniform()};
    Vec3 w = sample(u);
    ASSERT_NEAR(length(w), 1.0f, 1e-5f) << "u = " << u.x << ", " << u.y;
    const double theta = std::acos(std::clamp(double(w.z), -1.0, 1.0));
    if (theta > theta_max + 1e-3) {
      ++outside;
      continue;
    }
    const int i = std::min(kThetaBins - 1, int(theta / dt)), j = std::min(kPhiBins - 1, int(phi_of(w) / dp));
    observed[i * kPhiBins + j] += 1;
  }
  EXPECT_EQ(outside, 0);
  double total = 0;
  for (int i = 0; i < kThetaBins; ++i)
    for (int j = 0; j < kPhiBins; ++j) {
      double p = integrate_directions(pdf, i * dt, (i + 1) * dt, 16, j * dp, (j + 1) * dp, 4);
      expected[i * kPhiBins + j] = p * kSamples;
      total += p;
    }
  ASSERT_NEAR(total, 1.0, kIntegralTolerance);  // the grid covers the whole domain
  auto r = chi_square(observed, expected);
  EXPECT_GT(r.p_value, kChiSquareAlpha) << "chi2 = " << r.statistic << " dof " << r.dof;
}

TEST(WarpSampler, CosineHemisphereMatchesPdf) {
  expect_direction_sampler_matches_pdf(
      sample_cosine_hemisphere, [](Vec3 w) { return double(cosine_hemisphere_pdf(w.z)); }, kPiD / 2, 1);
}

TEST(WarpSampler, UniformSphereMatchesPdf) {
  expect_direction_sampler_matches_pdf(
      sample_uniform_sphere, [](Vec3) { return double(uniform_sphere_pdf()); }, kPiD, 2);
}

TEST(WarpSampler, UniformConeMatchesPdf) {
  uint64_t seed = 3;
  for (float cos_max : kConeCosines) {
    SCOPED_TRACE(cos_max);
    const double pdf = uniform_cone_pdf(cos_max);
    expect_direction_sampler_matches_pdf([cos_max](Vec2 u) { return sample_uniform_cone(u, cos_max); },
                                         [pdf](Vec3) { return pdf; }, std::acos(double(cos_max)), seed++);
  }
}

TEST(WarpSampler, ConcentricDiskIsUniformInArea) {
  // Polar cells [r0, r1] x [phi0, phi1] have exact area fractions (r1^2 - r0^2) / kPhiBins.
  constexpr int kRadialBins = 20;
  std::vector<double> observed(kRadialBins * kPhiBins, 0.0), expected(kRadialBins * kPhiBins, 0.0);
  Rng rng(10, 0);
  for (int s = 0; s < kSamples; ++s) {
    Vec2 p = sample_uniform_disk_concentric({rng.uniform(), rng.uniform()});
    const double r = std::hypot(double(p.x), double(p.y));
    ASSERT_LE(r, 1 + 1e-6);
    double phi = std::atan2(double(p.y), double(p.x));
    if (phi < 0) phi += kTwoPi;
    const int i = std::min(kRadialBins - 1, int(r * kRadialBins)),
              j = std::min(kPhiBins - 1, int(phi / kTwoPi * kPhiBins));
    observed[i * kPhiBins + j] += 1;
  }
  for (int i = 0; i < kRadialBins; ++i)
    for (int j = 0; j < kPhiBins; ++j)
      expected[i * kPhiBins + j] = kSamples * (sqr(i + 1.0) - sqr(double(i))) / sqr(double(kRadialBins)) / kPhiBins;
  auto r = chi_square(observed, expected);
  EXPECT_GT(r.p_value, kChiSquareAlpha) << "chi2 = " << r.statistic << " dof " << r.dof;
  EXPECT_EQ(sample_uniform_disk_concentric({0.5f, 0.5f}).x, 0.0f);  // centre maps to centre
}

TEST(WarpSampler, TriangleIsUniformInBarycentricArea) {
  // Cells of an n x n grid over (b0, b1): below the diagonal b0 + b1 = 1 a cell has area
  // 1/n^2, on it (i + j = n - 1) half that, above it zero; the density is 2 (area 1/2).
  constexpr int n = 20;
  std::vector<double> observed(n * n, 0.0), expected(n * n, 0.0);
  Rng rng(11, 0);
  for (int s = 0; s < kSamples; ++s) {
    Vec2 b = sample_uniform_triangle({rng.uniform(), rng.uniform()});
    ASSERT_GE(b.x, 0.0f);
    ASSERT_GE(b.y, 0.0f);
    ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
    observed[std::min(n - 1, int(b.x * n)) * n + std::min(n - 1, int(b.y * n))] += 1;
  }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      expected[i * n + j] = i + j < n - 1 ? 2.0 * kSamples / (n * n) : i + j == n - 1 ? 1.0 * kSamples / (n * n) : 0;
  for (int i = 0; i < n; ++i)
    for (int j = n - i; j < n; ++j) EXPECT_EQ(observed[i * n + j], 0) << "cell " << i << ", " << j;
  auto r = chi_square(observed, expected);
  EXPECT_GT(r.p_value, kChiSquareAlpha) << "chi2 = " << r.statistic << " dof " << r.dof;
}

}  // namespace
}  // namespace dermis
