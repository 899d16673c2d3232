// RGB to spectrum (Jakob & Hanika 2019, "A Low-Dimensional Function Space for Efficient
// Spectral Upsampling"): an RGB reflectance becomes a smooth spectrum whose colour under D65
// (sRGB's white, CIE 1931 observer) is that RGB. The paper's grid of sigmoid-polynomial fits
// over the RGB cube (rgb_to_spectrum_fit.h), fitted at build time
// (tools/make_rgb_to_spectrum.cpp) and built into the library, is read at the rgb's cell:
// where the paper interpolates the eight neighbouring fits' coefficients, Dermis blends
// their spectra with the same trilinear weights. A colour is linear in its spectrum and the
// weights are linear in the rgb, so the blend's colour is the rgb itself (to the fits'
// 1e-7), where interpolated coefficients missed it by 1e-3 near the gamut's edges and white.
#pragma once

#include <array>
#include <span>

#include "dermis/core/rgb.h"
#include "dermis/spectral/sigmoid_polynomial.h"

namespace dermis {

// The spectrum of a reflectance rgb: a blend of up to eight sigmoid polynomials, in [0, 1].
struct RgbSpectrum {
  std::array<SigmoidPolynomial, 8> polynomial{};
  std::array<float, 8> weight{};
  int count = 0;
  float operator()(float lambda_nm) const {
    float s = 0;
    for (int i = 0; i < count; ++i) s += weight[std::size_t(i)] * polynomial[std::size_t(i)](lambda_nm);
    return s;
  }
};

class RgbToSpectrumTable {
 public:
  // sRGB's table, the one built into the library.
  static const RgbToSpectrumTable& srgb();
  // A table over a grid of RgbToSpectrumGrid::kCells fits (its layout), kept by the caller.
  explicit RgbToSpectrumTable(std::span<const SigmoidPolynomial> grid);

  // The spectrum of a reflectance rgb (each channel clamped to [0, 1]).
  RgbSpectrum operator()(RGB rgb) const;

 private:
  std::span<const SigmoidPolynomial> grid_;
};

// pbrt-v4's RGBUnboundedSpectrum and RGBIlluminantSpectrum: an rgb with components above 1
// (a coefficient, an emission) as scale x a reflectance spectrum of rgb / scale, the scale
// twice the largest component (the reflectance's largest is then 1/2).
struct UnboundedSpectrum {
  float scale = 0;
  RgbSpectrum reflectance;
  float operator()(float lambda_nm) const { return scale * reflectance(lambda_nm); }
};
UnboundedSpectrum unbounded_spectrum(const RgbToSpectrumTable& table, RGB rgb);

}  // namespace dermis
