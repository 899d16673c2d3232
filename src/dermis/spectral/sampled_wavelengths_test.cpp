#include "dermis/spectral/sampled_wavelengths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "dermis/core/rng.h"
#include "dermis/spectral/cie_observer.h"
#include "support/running_mean.h"

namespace dermis {
namespace {

using testing::Mean;

TEST(SampledWavelengths, VisiblePdfIntegratesToOne) {
  double sum = 0;
  for (double l = 360.05; l < 830; l += 0.1) sum += SampledWavelengths::visible_pdf(float(l)) * 0.1;
  EXPECT_NEAR(sum, 1.0, 1e-4);
  EXPECT_EQ(SampledWavelengths::visible_pdf(359), 0.0f);
  EXPECT_EQ(SampledWavelengths::visible_pdf(831), 0.0f);
}

// Wavelength i of a set lies in the i-th n-quantile slice of the density, and one of the set
// chosen uniformly (in turn) follows the density: the share in each of 47 bins of 10 nm against
// the density's integral there, within 4 sigma (binomial).
TEST(SampledWavelengths, EachInItsSliceAndOneChosenFollowsTheVisibleDensity) {
  constexpr int kBins = 47, kSets = 100000;
  std::array<float, kPathWavelengths + 1> quantile{};  // the slices' ends, by the density's integral
  quantile[0] = 360, quantile[kPathWavelengths] = 830;
  double cdf = 0;
  int next = 1;
  for (double l = 360.005; l < 830 && next < kPathWavelengths; l += 0.01) {
    cdf += SampledWavelengths::visible_pdf(float(l)) * 0.01;
    if (cdf >= double(next) / kPathWavelengths) quantile[std::size_t(next++)] = float(l);
  }
  std::array<int, kBins> counts{};
  Rng rng(3, 1);
  for (int s = 0; s < kSets; ++s) {
    const SampledWavelengths w = SampledWavelengths::sample_visible(rng.uniform());
    for (int i = 0; i < kPathWavelengths; ++i) {
      const float l = w.lambda[std::size_t(i)];
      ASSERT_NEAR(w.pdf[std::size_t(i)], SampledWavelengths::visible_pdf(l), 1e-6f);
      ASSERT_GE(l, quantile[std::size_t(i)] - 0.05f) << i;
      ASSERT_LE(l, quantile[std::size_t(i) + 1] + 0.05f) << i;
    }
    const float chosen = w.lambda[std::size_t(s % kPathWavelengths)];
    ++counts[std::size_t(std::min(int((chosen - 360) / 10), kBins - 1))];
  }
  for (int b = 0; b < kBins; ++b) {
    double p = 0;
    for (int k = 0; k < 100; ++k) p += SampledWavelengths::visible_pdf(float(360 + 10 * b + (k + 0.5) * 0.1)) * 0.1;
    const double sigma = std::sqrt(kSets * p * (1 - p));
    EXPECT_NEAR(counts[std::size_t(b)], kSets * p, 4 * sigma) << "bin " << b;
  }
}

// The film's colour of a spectrum, estimated from sampled wavelengths, against the exact sum
// at every nanometre (CIE 1931, to linear sRGB), within 4 sigma per channel: a smooth
// spectrum, and again with the secondary wavelengths dropped.
TEST(SampledWavelengths, ColourEstimateIsUnbiased) {
  auto spectrum = [](double l) { return 0.3 + 0.6 * std::exp(-(l - 610) * (l - 610) / (2 * 40.0 * 40.0)); };
  const CieTables& cie = cie_tables();
  double X = 0, Y = 0, Z = 0;
  for (int i = 0; i < CieTables::kSamples; ++i) {
    const double v = spectrum(CieTables::kLambdaMin + i) / cie.y_sum;
    X += v * cie.x[i], Y += v * cie.y[i], Z += v * cie.z[i];
  }
  const auto exact = xyz_to_linear_srgb(X, Y, Z);
  for (bool terminated : {false, true}) {
    Mean m[3];
    Rng rng(5, terminated ? 2 : 1);
    for (int s = 0; s < 200000; ++s) {
      SampledWavelengths w = SampledWavelengths::sample_visible(rng.uniform());
      if (terminated) w.terminate_secondary(rng.uniform());
      RGB values;
      for (int i = 0; i < kPathWavelengths; ++i) values[i] = float(spectrum(w.lambda[std::size_t(i)]));
      const RGB c = w.to_linear_srgb(values);
      for (int k = 0; k < 3; ++k) m[k].add(c[k]);
    }
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(m[k].mean(), exact[std::size_t(k)], 4 * m[k].stderr_())
          << "channel " << k << (terminated ? ", hero alone" : "");
  }
}

}  // namespace
}  // namespace dermis
