// The fit behind RGB to spectrum (Jakob & Hanika 2019, "A Low-Dimensional Function Space
// for Efficient Spectral Upsampling"): the sigmoid polynomial whose colour under D65 is a
// given RGB, found by Newton's method, and the grid of such fits over the RGB cube that
// rgb_to_spectrum.h interpolates. Run at build time by tools/make_rgb_to_spectrum.cpp.
#pragma once

#include <cstddef>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/spectral/sigmoid_polynomial.h"

namespace dermis {

// The linear sRGB colour of a reflectance spectrum under D65 (CIE 015:2004, eqs. 7.1-7.3, at
// 1 nm over 360-830 nm): what pbrt-v4's RGB film records for a white-lit diffuse surface.
RGB reflectance_rgb(const SigmoidPolynomial& s);

struct SigmoidFit {
  SigmoidPolynomial polynomial;
  double residual = 0;  // the largest |colour - rgb| over the channels
  int iterations = 0;
};
// The sigmoid polynomial whose reflectance_rgb is `rgb` (each in [0, 1]), by damped Newton
// iterations on the colour's three equations from `start`; at the gamut's edge (a pure
// primary) the coefficients grow without bound and the fit stops at its iteration limit.
SigmoidFit fit_sigmoid(RGB rgb, SigmoidPolynomial start = {});

// The grid: for each of the three channels that can be the largest, kResolution^3 fits at
// (its value z, the next channel over it, the one after over it), z spaced densely near 0
// and 1 (the paper's sec. 4), the ratios evenly.
struct RgbToSpectrumGrid {
  static constexpr int kResolution = 64;
  static constexpr std::size_t kCells = 3 * std::size_t(kResolution) * kResolution * kResolution;
  static double z_node(int i);  // smoothstep(smoothstep(i / (res - 1)))
  static std::size_t index(int channel, int z, int y, int x) {
    return ((std::size_t(channel) * kResolution + std::size_t(z)) * kResolution + std::size_t(y)) * kResolution +
           std::size_t(x);
  }
};
// Every cell of the grid fitted (seconds on a few cores).
std::vector<SigmoidPolynomial> fit_rgb_to_spectrum_grid();

}  // namespace dermis
