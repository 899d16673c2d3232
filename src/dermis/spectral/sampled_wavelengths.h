// The wavelengths a spectral path carries (hero-wavelength sampling, Wilkie et al. 2014,
// "Hero Wavelength Spectral Sampling"): kPathWavelengths of them, the first (the hero) drawn
// from the visible-importance density, the others at equal steps of its sample through the
// range, each with its own density; and the colour a film records from the path's values at
// them (CIE 1931 observer, to linear sRGB). Three, so that a path's per-wavelength values
// fit the RGB triple the transport code already carries.
#pragma once

#include <array>

#include "dermis/core/rgb.h"

namespace dermis {

inline constexpr int kPathWavelengths = 3;

struct SampledWavelengths {
  std::array<float, kPathWavelengths> lambda{};  // nm
  std::array<float, kPathWavelengths> pdf{};     // per nm; 0 for a wavelength dropped

  // From one uniform number u in [0, 1): lambda_i at u + i / kPathWavelengths (mod 1).
  static SampledWavelengths sample_visible(float u);
  // The visible-importance density over 360-830 nm, proportional to
  // 1 / cosh^2(0.0072 (lambda - 538)) (Radziszowski's fit to the luminous efficiency, the
  // density pbrt-v4 samples; inverted in closed form).
  static float visible_pdf(float lambda_nm);

  // A dispersive event (an index that depends on the wavelength) keeps the hero alone.
  void terminate_secondary();
  bool secondary_terminated() const { return pdf[1] == 0; }

  // The colour of a path's values at these wavelengths, as linear sRGB: the Monte Carlo
  // estimate of integral L(lambda) {x, y, z}(lambda) dlambda / integral y, averaged over the
  // wavelengths kept, then CIE XYZ to linear sRGB. A flat L = c gives, in expectation, the
  // colour of the equal-energy white at luminance c.
  RGB to_linear_srgb(RGB values) const;
};

}  // namespace dermis
