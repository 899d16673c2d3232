// RGB stand-ins for the spectral quantities of pbrt-v4 scenes (Dermis renders in linear
// Rec.709 / sRGB): named spectra, sampled [lambda value ...] spectra, spectrum files (.spd)
// and blackbodies, turned into the RGB that pbrt-v4's RGB film would record for them.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/scene/diagnostics.h"
#include "dermis/scene/params.h"
#include "dermis/spectral/piecewise_linear.h"

namespace dermis {

// What a spectrum parameter describes (pbrt-v4's SpectrumType; its Albedo and Unbounded
// types convert alike).
enum class SpectrumType {
  // Reflectance, eta, k, sigma_a ...: the sRGB colour of the spectrum seen under D65, the
  // white of sRGB (a constant spectrum c gives (c, c, c)).
  Unbounded,
  // A light's emission: its chromaticity at luminance Y = 1, as pbrt-v4 divides every light
  // spectrum by its photometric power (the light's "scale" then sets its brightness).
  Illuminant,
};

// Linear sRGB of the piecewise-linear spectrum through (lambda[i], value[i]) (nm,
// increasing), integrated against the CIE 1931 observer over 360-830 nm. Negative components
// (outside the sRGB gamut) are clamped to zero.
RGB spectrum_rgb(std::span<const double> lambda, std::span<const double> value, SpectrumType type,
                 SpectrumEnds ends = SpectrumEnds::Zero);

// pbrt-v4's named spectra with data ("metal-Au-eta", "stdillum-F4", "glass-BK7", ... : see
// named_spectra_data.h) as RGB; nullopt for other names. Illuminant tables are normalized
// to luminance 1 first, as pbrt-v4 does.
std::optional<RGB> named_spectrum_rgb(const std::string& name, SpectrumType type = SpectrumType::Unbounded);
// Named glasses "glass-{BK7,BAF10,FK51A,LASF9,F5,F10,F11}": mean index over 400-700 nm.
std::optional<float> named_glass_ior(const std::string& name);
// True for pbrt-v4's camera sensor curves ("canon_eos_5d_r", ...), which Dermis knows by name only.
bool is_camera_sensor_spectrum(const std::string& name);
// All the names pbrt-v4 gives to spectra, for error messages.
std::string named_spectrum_list();

// Linear Rec.709 RGB of a blackbody at `kelvin`, normalized to luminance Y = 1 (pbrt-v4
// divides light spectra by their photometric power, so a blackbody light's scale is its
// luminance). Negative components (outside the gamut) are clamped to zero.
RGB blackbody_rgb(double kelvin);

// The RGB value of a parameter of type rgb, spectrum (pairs, a name or a file name) or
// blackbody. A file name resolves against the parameter's base directory. Warns (at the
// parameter) when a sampled spectrum or a spectrum file is reduced to RGB.
RGB spectrum_param_rgb(const ParsedParam& p, Diagnostics& diag, SpectrumType type = SpectrumType::Unbounded);

// The spectrum behind a parameter of type spectrum (pairs, a name or a file name) or
// blackbody, at every nanometre of 360-830 nm, for spectral rendering (render/renderer.h
// RenderOptions::spectral) to use as data: a light's (Illuminant) scaled so that its
// luminance is 1, the scale spectrum_param_rgb's colour has, a coefficient's (Unbounded) as
// given. nullopt for an rgb parameter (spectral rendering reads RGB as pbrt-v4 does).
std::optional<std::vector<float>> spectrum_param_samples(const ParsedParam& p, SpectrumType type);
// The same for one of pbrt-v4's named spectra (nullopt for other names).
std::optional<std::vector<float>> named_spectrum_samples(const std::string& name, SpectrumType type);

// A scalar from a float parameter, a named glass, or a sampled spectrum or spectrum file
// (mean over 400-700 nm, with a warning).
float ior_param(const ParsedParam& p, Diagnostics& diag);

}  // namespace dermis
