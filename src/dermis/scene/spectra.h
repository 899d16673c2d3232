// RGB stand-ins for the spectral quantities of pbrt-v4 scenes (Dermis renders in
// linear Rec.709 RGB): named spectra, sampled [lambda value ...] spectra and blackbodies.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/scene/diagnostics.h"
#include "dermis/scene/params.h"

namespace dermis {

// The wavelength bands an RGB channel stands for when a spectrum is averaged:
// B = [400, 500) nm, G = [500, 600) nm, R = [600, 700] nm.
inline constexpr double kBandEdgesNm[4] = {400, 500, 600, 700};

// Average of the piecewise-linear spectrum through (lambda[i], value[i]) over each band
// (zero outside the tabulated range, as pbrt-v4's PiecewiseLinearSpectrum).
RGB band_average_rgb(const std::vector<double>& lambda, const std::vector<double>& value);

// Named spectra: "metal-{Cu,Au,Ag,Al,CuZn}-{eta,k}" and "stdillum-D65" (white).
// nullopt for other names.
std::optional<RGB> named_spectrum_rgb(const std::string& name);
// Named glasses "glass-{BK7,BAF10,FK51A,LASF9,F5,F10,F11}": mean index over 400-700 nm.
std::optional<float> named_glass_ior(const std::string& name);
// All names the two functions above accept, for error messages.
std::string named_spectrum_list();

// Linear Rec.709 RGB of a blackbody at `kelvin`, normalized to luminance Y = 1 (pbrt-v4
// divides light spectra by their photometric power, so a blackbody light's scale is its
// luminance). Negative components (outside the gamut) are clamped to zero.
RGB blackbody_rgb(double kelvin);

// The RGB value of a parameter of type rgb, spectrum (pairs or a name) or blackbody.
// Warns (at the parameter) when a sampled spectrum is reduced to band averages.
RGB spectrum_param_rgb(const ParsedParam& p, Diagnostics& diag);

// A scalar from a float parameter, a named glass, or a sampled spectrum (mean over
// 400-700 nm, with a warning).
float ior_param(const ParsedParam& p, Diagnostics& diag);

}  // namespace dermis
