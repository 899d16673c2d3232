// Tests of the piecewise-constant tables: densities integrate to one, samplers
// match the tabulated function (Pearson chi-square), zero bins are never sampled,
// and the density a sample reports is the density pdf() gives at that point.
#include "dermis/core/distribution.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "dermis/core/rng.h"
#include "support/chi_square.h"

namespace dermis {
namespace {

using testing::chi_square;
using testing::kChiSquareAlpha;

constexpr int kSamples = 200'000;

// A function with zeros at both ends and in the middle, and a wide dynamic range.
const std::vector<float> kFunction = {0, 1, 3, 0.5f, 0, 0, 2, 7, 0.01f, 4, 0};

double sum_of(const std::vector<float>& f) { return std::accumulate(f.begin(), f.end(), 0.0); }

void expect_chi_square_passes(const std::vector<double>& observed, const std::vector<double>& expected) {
  auto r = chi_square(observed, expected);
  EXPECT_GT(r.p_value, kChiSquareAlpha) << "chi2 = " << r.statistic << " dof " << r.dof;
}

TEST(Distribution1D, PdfIntegratesToOneAndPmfSumsToOne) {
  Distribution1D d(kFunction);
  const std::size_t n = kFunction.size();
  EXPECT_NEAR(d.integral(), sum_of(kFunction) / double(n), 1e-6);
  // The density is constant on each bin: a midpoint rule with whole sub-steps per bin is exact.
  constexpr int kSub = 16;
  double integral = 0, pmf_sum = 0;
  for (std::size_t i = 0; i < n * kSub; ++i) integral += d.pdf_continuous((i + 0.5f) / float(n * kSub));
  integral /= double(n * kSub);
  for (std::size_t i = 0; i < n; ++i) {
    pmf_sum += d.pmf_discrete(i);
    EXPECT_NEAR(d.pmf_discrete(i), kFunction[i] / sum_of(kFunction), 1e-7);
  }
  EXPECT_NEAR(integral, 1.0, 1e-6);
  EXPECT_NEAR(pmf_sum, 1.0, 1e-6);
  EXPECT_EQ(d.pdf_continuous(-0.1f), 0);
  EXPECT_EQ(d.pdf_continuous(1.0f), 0);
}

TEST(Distribution1D, ContinuousSamplingMatchesTheFunction) {
  // Histogram into 4 sub-bins per table bin: also checks uniformity within each bin.
  Distribution1D d(kFunction);
  const std::size_t n = kFunction.size(), m = 4 * n;
  std::vector<double> observed(m, 0.0), expected(m, 0.0);
  Rng rng(1, 0);
  for (int s = 0; s < kSamples; ++s) {
    float pdf;
    std::size_t bin;
    const float x = d.sample_continuous(rng.uniform(), &pdf, &bin);
    ASSERT_GE(x, 0.0f);
    ASSERT_LT(x, 1.0f);
    ASSERT_EQ(bin, std::size_t(double(x) * double(n))) << "x = " << x;
    ASSERT_EQ(pdf, d.pdf_continuous(x)) << "x = " << x;
    observed[std::min(m - 1, std::size_t(double(x) * double(m)))] += 1;
  }
  for (std::size_t i = 0; i < m; ++i) expected[i] = kSamples * kFunction[i / 4] / sum_of(kFunction) / 4;
  expect_chi_square_passes(observed, expected);
}

TEST(Distribution1D, DiscreteSamplingMatchesTheFunction) {
  Distribution1D d(kFunction);
  const std::size_t n = kFunction.size();
  constexpr int kRemapBins = 20;
  std::vector<double> observed(n, 0.0), expected(n, 0.0), remapped(kRemapBins, 0.0),
      remapped_expected(kRemapBins, kSamples / double(kRemapBins));
  Rng rng(2, 0);
  for (int s = 0; s < kSamples; ++s) {
    float pmf, u_remapped;
    const std::size_t i = d.sample_discrete(rng.uniform(), &pmf, &u_remapped);
    ASSERT_LT(i, n);
    ASSERT_NEAR(pmf, kFunction[i] / sum_of(kFunction), 1e-7);
    ASSERT_GE(u_remapped, 0.0f);
    ASSERT_LT(u_remapped, 1.0f);
    observed[i] += 1;
    remapped[std::min(kRemapBins - 1, int(u_remapped * kRemapBins))] += 1;
  }
  for (std::size_t i = 0; i < n; ++i) expected[i] = kSamples * kFunction[i] / sum_of(kFunction);
  expect_chi_square_passes(observed, expected);
  // The remapped number is again uniform on [0, 1), so it can be reused.
  expect_chi_square_passes(remapped, remapped_expected);
}

// Floats at and on both sides of every bin boundary of the table's CDF, plus a fine grid.
std::vector<float> probing_numbers(const std::vector<float>& f) {
  std::vector<float> u;
  const double total = sum_of(f);
  double cdf = 0;
  for (float v : f) {
    cdf += v / total;
    const float b = float(cdf);
    for (float x : {std::nextafter(std::nextafter(b, 0.0f), 0.0f), std::nextafter(b, 0.0f), b, std::nextafter(b, 1.0f)})
      if (x >= 0 && x < 1) u.push_back(x);
  }
  u.push_back(0);
  u.push_back(std::nextafter(1.0f, 0.0f));
  for (int i = 0; i < 100'000; ++i) u.push_back(i / 100'000.0f);
  return u;
}

TEST(Distribution1D, ZeroBinsAreNeverSampled) {
  const std::vector<float> f = {0, 0, 1, 0, 0, 2, 0, 0.3f, 0};
  Distribution1D d(f);
  for (float u : probing_numbers(f)) {
    float pdf, pmf;
    std::size_t bin;
    const float x = d.sample_continuous(u, &pdf, &bin);
    ASSERT_GT(f[bin], 0) << "u = " << u;
    ASSERT_GT(pdf, 0) << "u = " << u;
    ASSERT_GT(d.pdf_continuous(x), 0) << "u = " << u << ", x = " << x;
    const std::size_t i = d.sample_discrete(u, &pmf);
    ASSERT_GT(f[i], 0) << "u = " << u;
    ASSERT_GT(pmf, 0) << "u = " << u;
  }
}

// The cutpoint search finds the bin a binary search over the same CDF finds (the CDF built
// here as the constructor builds it), for every u probed: at the bins' edges, at the
// cutpoints j/n and between them, for functions with zero bins, spikes and a long tail.
TEST(Distribution1D, GuidedSearchFindsTheBinABinarySearchFinds) {
  Rng rng(11, 0);
  for (std::size_t n : {1u, 2u, 5u, 64u, 1000u, 1024u}) {
    std::vector<float> f(n);
    for (float& v : f) {
      const float r = rng.uniform();
      v = r < 0.3f ? 0.0f : r < 0.35f ? 1e4f * rng.uniform() : 1e-6f + rng.uniform();
    }
    std::vector<double> cdf(n + 1, 0.0);
    for (std::size_t i = 0; i < n; ++i) cdf[i + 1] = cdf[i] + double(f[i]) / double(n);
    for (std::size_t i = 1; i <= n; ++i) cdf[i] /= cdf[n];
    std::vector<float> us = probing_numbers(f);
    for (std::size_t j = 0; j <= n; ++j)
      for (float du : {-1e-7f, 0.0f, 1e-7f}) us.push_back(float(double(j) / double(n)) + du);
    for (int k = 0; k < 2000; ++k) us.push_back(rng.uniform());
    Distribution1D d(f);
    for (float u : us) {
      if (!(u >= 0 && u < 1)) continue;
      std::size_t expected = std::size_t(std::upper_bound(cdf.begin(), cdf.end(), double(u)) - cdf.begin()) - 1;
      expected = std::min(expected, n - 1);
      while (cdf[expected + 1] - cdf[expected] <= 0 && expected + 1 < n) ++expected;  // as sample_discrete skips
      ASSERT_EQ(d.sample_discrete(u), expected) << "n = " << n << ", u = " << u;
    }
  }
}

TEST(Distribution1D, SampledPointLiesInTheReportedBin) {
  // Bin counts that are not powers of two, so bin edges i/n are inexact in float.
  Rng rng(3, 0);
  for (std::size_t n : {3u, 7u, 13u, 100u, 999u}) {
    std::vector<float> f(n);
    for (float& v : f) v = rng.uniform() < 0.2f ? 0.0f : 0.1f + rng.uniform();
    Distribution1D d(f);
    for (float u : probing_numbers(f)) {
      float pdf;
      std::size_t bin;
      const float x = d.sample_continuous(u, &pdf, &bin);
      ASSERT_LT(x, 1.0f);
      ASSERT_EQ(pdf, d.pdf_continuous(x)) << "n = " << n << ", u = " << u << ", x = " << x << ", bin " << bin;
    }
  }
}

TEST(Distribution1D, AllZeroFunctionFallsBackToUniform) {
  const std::vector<float> f(5, 0.0f);
  Distribution1D d(f);
  EXPECT_EQ(d.integral(), 0);
  for (float u : {0.0f, 0.1f, 0.5f, 0.73f, 0.999f}) {
    float pdf, pmf;
    EXPECT_NEAR(d.sample_continuous(u, &pdf), u, 1e-6);
    EXPECT_EQ(pdf, 1.0f);
    EXPECT_EQ(d.pdf_continuous(u), 1.0f);
    EXPECT_EQ(d.sample_discrete(u, &pmf), std::size_t(u * 5));
    EXPECT_NEAR(pmf, 0.2f, 1e-7);
  }
}

TEST(Distribution1D, RejectsEmptyAndNonFiniteInput) {
  EXPECT_THROW(Distribution1D(std::span<const float>()), std::invalid_argument);
  const std::vector<float> nan = {1, std::numeric_limits<float>::quiet_NaN()};
  EXPECT_THROW(Distribution1D{nan}, std::invalid_argument);
  const std::vector<float> inf = {std::numeric_limits<float>::infinity(), 1};
  EXPECT_THROW(Distribution1D{inf}, std::invalid_argument);
  const std::vector<float> f(6, 1.0f);
  EXPECT_THROW(Distribution2D(f, 4, 2), std::invalid_argument);
}

// A bright spot on a dim background, with an all-zero row and a zero cell.
constexpr std::size_t kNu = 32, kNv = 16;
std::vector<float> spot_function() {
  std::vector<float> f(kNu * kNv);
  for (std::size_t v = 0; v < kNv; ++v)
    for (std::size_t u = 0; u < kNu; ++u) {
      const double x = (u + 0.5) / kNu - 0.7, y = (v + 0.5) / kNv - 0.3;
      f[v * kNu + u] = float(0.05 + 20 * std::exp(-(x * x + y * y) / (2 * 0.05 * 0.05)));
    }
  for (std::size_t u = 0; u < kNu; ++u) f[12 * kNu + u] = 0;
  f[3 * kNu + 5] = 0;
  return f;
}

TEST(Distribution2D, PdfIntegratesToOne) {
  const std::vector<float> f = spot_function();
  Distribution2D d(f, kNu, kNv);
  EXPECT_NEAR(d.integral(), sum_of(f) / double(kNu * kNv), 1e-5 * d.integral());
  constexpr int kSub = 4;  // whole sub-steps per cell: exact for a piecewise-constant density
  double integral = 0;
  for (std::size_t j = 0; j < kNv * kSub; ++j)
    for (std::size_t i = 0; i < kNu * kSub; ++i)
      integral += d.pdf({(i + 0.5f) / float(kNu * kSub), (j + 0.5f) / float(kNv * kSub)});
  EXPECT_NEAR(integral / double(kNu * kNv * kSub * kSub), 1.0, 1e-5);
}

TEST(Distribution2D, SamplingMatchesTheFunctionAndPdf) {
  const std::vector<float> f = spot_function();
  Distribution2D d(f, kNu, kNv);
  const double mean = sum_of(f) / double(kNu * kNv);  // the density is f / mean
  std::vector<double> observed(kNu * kNv, 0.0), expected(kNu * kNv, 0.0);
  Rng rng(4, 0);
  for (int s = 0; s < kSamples; ++s) {
    float pdf;
    const Vec2 p = d.sample({rng.uniform(), rng.uniform()}, &pdf);
    ASSERT_GE(p.x, 0.0f);
    ASSERT_LT(p.x, 1.0f);
    ASSERT_GE(p.y, 0.0f);
    ASSERT_LT(p.y, 1.0f);
    const std::size_t cell = std::size_t(double(p.y) * kNv) * kNu + std::size_t(double(p.x) * kNu);
    ASSERT_GT(f[cell], 0) << "sampled a zero cell at " << p.x << ", " << p.y;
    ASSERT_NEAR(pdf, f[cell] / mean, 1e-5 * pdf);
    ASSERT_NEAR(d.pdf(p), pdf, 1e-5 * pdf) << p.x << ", " << p.y;
    observed[cell] += 1;
  }
  for (std::size_t i = 0; i < f.size(); ++i) expected[i] = kSamples * f[i] / sum_of(f);
  expect_chi_square_passes(observed, expected);
}

TEST(Distribution2D, SampleAndPdfAgreeAtCellBoundaries) {
  const std::vector<float> f = spot_function();
  Distribution2D d(f, kNu, kNv);
  const std::vector<float> probes = {0.0f,
                                     0.25f,
                                     0.5f,
                                     std::nextafter(0.5f, 0.0f),
                                     std::nextafter(1.0f, 0.0f),
                                     1.0f / 3,
                                     std::nextafter(1.0f / 3, 0.0f)};
  for (float a : probes)
    for (float b : probes) {
      float pdf;
      const Vec2 p = d.sample({a, b}, &pdf);
      EXPECT_GT(pdf, 0);
      EXPECT_NEAR(d.pdf(p), pdf, 1e-5 * pdf) << "u = " << a << ", " << b;
    }
}

}  // namespace
}  // namespace dermis
