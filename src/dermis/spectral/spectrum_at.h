// An RGB input's values at a path's wavelengths, as pbrt-v4 reads RGB in its spectral
// renderer (Jakob & Hanika 2019's spectra, rgb_to_spectrum.h): a reflectance (albedo,
// transmittance) as the spectrum of its colour; an unbounded quantity (a conductor's eta and
// k, a medium's coefficients) as scale x that of its colour over the scale; an emission
// likewise, times sRGB's illuminant D65 at luminance 1, so that an emission (1, 1, 1) is
// D65's white and a film records it as (1, 1, 1).
#pragma once

#include <span>

#include "dermis/core/rgb.h"
#include "dermis/spectral/sampled_wavelengths.h"

namespace dermis {

// Each channel of the result is the spectrum's value at that wavelength.
RGB reflectance_at(RGB rgb, const SampledWavelengths& w);  // rgb clamped to [0, 1]
RGB unbounded_at(RGB rgb, const SampledWavelengths& w);    // negative components as 0
RGB illuminant_at(RGB rgb, const SampledWavelengths& w);   // negative components as 0

// A spectrum given as data at every nanometre of 360-830 nm (scene/spectra.h
// spectrum_param_samples), read at the wavelengths (linear between nanometres).
RGB tabulated_at(std::span<const float> every_nanometre, const SampledWavelengths& w);

// D65's relative spectral power at a wavelength, scaled to luminance Y = 1 (linear between
// the nanometres of cie_observer.h).
float d65_at(float lambda_nm);

}  // namespace dermis
