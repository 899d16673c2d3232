#include "dermis/spectral/rgb_to_spectrum.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "dermis/core/rng.h"
#include "dermis/spectral/cie_observer.h"
#include "dermis/spectral/rgb_to_spectrum_fit.h"

namespace dermis {
namespace {

// The colour of a reflectance spectrum under D65, summed here at every nanometre (CIE 015:2004,
// eqs. 7.1-7.3), apart from the fit's own sums.
template <class Spectrum>
RGB colour_under_d65(const Spectrum& s) {
  const CieTables& c = cie_tables();
  double X = 0, Y = 0, Z = 0;
  for (int i = 0; i < CieTables::kSamples; ++i) {
    const double v = s(float(CieTables::kLambdaMin + i)) * c.d65[i] / c.d65_y;
    X += v * c.x[i], Y += v * c.y[i], Z += v * c.z[i];
  }
  const auto rgb = xyz_to_linear_srgb(X, Y, Z);
  return RGB(float(rgb[0]), float(rgb[1]), float(rgb[2]));
}

// A grey is a constant spectrum, exactly: S^-1 of the value.
TEST(RgbToSpectrum, GreyIsAConstantSpectrum) {
  for (float v : {0.0f, 0.18f, 0.5f, 0.9f, 1.0f}) {
    const RgbSpectrum s = RgbToSpectrumTable::srgb()(RGB(v));
    for (float lambda : {360.0f, 500.0f, 700.0f, 830.0f}) EXPECT_NEAR(s(lambda), v, 1e-6f);
  }
}

// The fit alone: Newton's method finds a spectrum of each colour, checked by the colour
// integrated at every nanometre (the fit sums at 5 nm).
TEST(RgbToSpectrum, FitFindsASpectrumOfTheColour) {
  for (RGB rgb : {RGB(0.8f, 0.2f, 0.1f), RGB(0.05f, 0.6f, 0.3f), RGB(0.2f, 0.3f, 0.9f), RGB(0.9f, 0.85f, 0.6f)}) {
    const SigmoidFit fit = fit_sigmoid(rgb);
    const RGB back = colour_under_d65(fit.polynomial);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], rgb[c], 1e-4f) << c;
    EXPECT_LT(fit.residual, 1e-6);
  }
}

// The table's round trip over the sRGB gamut: rgb -> spectrum (interpolated coefficients)
// -> rgb (the spectrum's colour under D65 at every nanometre) within 0.001 in each channel,
// a tenth of a percent of the reflectance range, on a 21^3 grid of the cube (corners, the
// pure primaries and the edges included) and at 20000 random colours.
TEST(RgbToSpectrum, RoundTripOverTheGamutWithinATenthOfAPercent) {
  const RgbToSpectrumTable& table = RgbToSpectrumTable::srgb();
  constexpr int n = 21;
  double worst = 0;
  RGB worst_rgb;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const RGB rgb(float(i) / (n - 1), float(j) / (n - 1), float(k) / (n - 1));
        const RGB back = colour_under_d65(table(rgb));
        for (int c = 0; c < 3; ++c)
          if (std::abs(back[c] - rgb[c]) > worst) worst = std::abs(back[c] - rgb[c]), worst_rgb = rgb;
      }
  Rng rng(7, 1);  // and random colours, a quarter with a channel near 0 (the gamut's edge), a quarter near white
  for (int i = 0; i < 20000; ++i) {
    RGB rgb(rng.uniform(), rng.uniform(), rng.uniform());
    if (i % 4 == 1) rgb[i % 3] *= 0.02f;
    if (i % 4 == 3) rgb = RGB(1) - rgb * 0.05f;  // near white
    const RGB back = colour_under_d65(table(rgb));
    for (int c = 0; c < 3; ++c)
      if (std::abs(back[c] - rgb[c]) > worst) worst = std::abs(back[c] - rgb[c]), worst_rgb = rgb;
  }
  std::printf("round trip: largest difference %.2e at (%g, %g, %g)\n", worst, worst_rgb[0], worst_rgb[1], worst_rgb[2]);
  EXPECT_LE(worst, 1e-3);
}

// A spectrum is a reflectance: within [0, 1] at every wavelength.
TEST(RgbToSpectrum, SpectraStayWithinZeroAndOne) {
  const RgbToSpectrumTable& table = RgbToSpectrumTable::srgb();
  for (RGB rgb : {RGB(1, 0, 0), RGB(0, 1, 0), RGB(0, 0, 1), RGB(0.3f, 0.01f, 0.7f)}) {
    const RgbSpectrum s = table(rgb);
    for (float lambda = 360; lambda <= 830; lambda += 1) {
      EXPECT_GE(s(lambda), 0.0f);
      EXPECT_LE(s(lambda), 1.0f);
    }
  }
}

// An unbounded colour (a coefficient, an emission) as scale x a reflectance at half height.
TEST(RgbToSpectrum, UnboundedIsScaledReflectance) {
  const RGB rgb(3.0f, 1.2f, 0.6f);
  const UnboundedSpectrum s = unbounded_spectrum(RgbToSpectrumTable::srgb(), rgb);
  EXPECT_FLOAT_EQ(s.scale, 6.0f);
  const RGB back = colour_under_d65(s);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], rgb[c], 1e-3f * s.scale) << c;
  EXPECT_EQ(unbounded_spectrum(RgbToSpectrumTable::srgb(), RGB(0))(550), 0.0f);
}

// The built-in table is the grid fitted now (the build's tool and this code agree), at a
// few cells.
TEST(RgbToSpectrum, BuiltInTableIsTheFit) {
  const RgbToSpectrumTable& table = RgbToSpectrumTable::srgb();
  for (RGB rgb : {RGB(0.7f, 0.2f, 0.4f), RGB(0.01f, 0.02f, 0.9f), RGB(0.3f, 0.8f, 0.5f)}) {
    const RGB back = colour_under_d65(table(rgb)), fit = colour_under_d65(fit_sigmoid(rgb).polynomial);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], fit[c], 1e-3f) << c;
  }
}

}  // namespace
}  // namespace dermis
