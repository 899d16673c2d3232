// The wavelengths a spectral path carries (hero-wavelength sampling, Wilkie et al. 2014,
// "Hero Wavelength Spectral Sampling"): kPathWavelengths of them at equal steps of one sample
// u through the visible-importance density's CDF, each with its own density; and the colour a
// film records from the path's values at them (CIE 1931 observer, to linear sRGB). Three, so
// that a path's per-wavelength values fit the RGB triple the transport code already carries.
//
// Wavelength i is at CDF (u + i) / n, in the i-th n-quantile slice, rather than at u + i / n
// (mod 1) as in Wilkie et al. and pbrt-v4. For a uniform u the two are the same set of
// wavelengths, so the estimate is the same; but the set, and so the estimate, depends on u
// mod 1/n only, and a pixel's N samples of u stratified in N strata folded onto that period
// cover it unevenly. Stretched over the whole period, they stratify each wavelength in its
// slice: under a sky seen directly, 16 samples gave 1.8 % blue noise instead of 13.6 %
// (docs/rendering.md, "Spectral transport").
#pragma once

#include <array>

#include "dermis/core/rgb.h"

namespace dermis {

inline constexpr int kPathWavelengths = 3;

struct SampledWavelengths {
  std::array<float, kPathWavelengths> lambda{};  // nm
  std::array<float, kPathWavelengths> pdf{};     // per nm; 0 for a wavelength dropped

  // From one uniform number u in [0, 1): lambda_i at CDF (u + i) / kPathWavelengths.
  static SampledWavelengths sample_visible(float u);
  // The visible-importance density over 360-830 nm, proportional to
  // 1 / cosh^2(0.0072 (lambda - 538)) (Radziszowski's fit to the luminous efficiency, the
  // density pbrt-v4 samples; inverted in closed form).
  static float visible_pdf(float lambda_nm);

  // A dispersive event (an index that depends on the wavelength) keeps one wavelength alone,
  // chosen uniformly by u (each lies in its own slice: no one of them follows the density).
  void terminate_secondary(float u);
  bool secondary_terminated() const;
  // The wavelength kept by terminate_secondary (the first with a density, before).
  int kept() const;

  // The colour of a path's values at these wavelengths, as linear sRGB: the Monte Carlo
  // estimate of integral L(lambda) {x, y, z}(lambda) dlambda / integral y, averaged over the
  // wavelengths kept, then CIE XYZ to linear sRGB. A flat L = c gives, in expectation, the
  // colour of the equal-energy white at luminance c.
  RGB to_linear_srgb(RGB values) const;
};

}  // namespace dermis
