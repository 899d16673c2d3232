#include "dermis/spectral/blackbody.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dermis/spectral/cie_observer.h"

namespace dermis {
namespace {

// pbrt-v4's BlackbodySpectrum peaks at 1, at Wien's wavelength.
TEST(Blackbody, NormalisedToOneAtItsPeak) {
  for (float kelvin : {1500.0f, 2856.0f, 5500.0f, 9000.0f}) {
    const float peak = 2.8977721e-3f / kelvin * 1e9f;
    EXPECT_NEAR(normalized_blackbody(peak, kelvin), 1, 1e-5f);
    EXPECT_LT(normalized_blackbody(peak * 1.1f, kelvin), 1);
    EXPECT_LT(normalized_blackbody(peak * 0.9f, kelvin), 1);
  }
  EXPECT_EQ(normalized_blackbody(500, 0), 0);
}

// The table's colours against the observer's sum at every nanometre, between its entries too,
// within 1e-3 of the largest channel; nothing at or below 100 K.
TEST(Blackbody, ColourTableIsTheObserversSum) {
  const CieTables& cie = cie_tables();
  for (float kelvin : {600.0f, 800.0f, 1234.5f, 2000.0f, 3300.3f, 6504.0f, 12000.0f, 40000.0f}) {
    double X = 0, Y = 0, Z = 0;
    for (int i = 0; i < CieTables::kSamples; ++i) {
      const double v = normalized_blackbody(float(CieTables::kLambdaMin + i), kelvin) / cie.y_sum;
      X += v * cie.x[std::size_t(i)], Y += v * cie.y[std::size_t(i)], Z += v * cie.z[std::size_t(i)];
    }
    const auto expected = xyz_to_linear_srgb(X, Y, Z);
    const RGB got = normalized_blackbody_rgb(kelvin);
    const double scale = std::max({std::abs(expected[0]), std::abs(expected[1]), std::abs(expected[2])});
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[std::size_t(c)], 1e-3 * scale) << kelvin << " K, " << c;
  }
  EXPECT_EQ(normalized_blackbody_rgb(100), RGB(0));
}

}  // namespace
}  // namespace dermis
