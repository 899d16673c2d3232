#include "dermis/scene/spectra.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <vector>

#include "dermis/scene/scene_parser.h"
#include "dermis/scene/spectrum_file.h"
#include "dermis/spectral/blackbody.h"
#include "dermis/spectral/cie_observer.h"
#include "dermis/spectral/named_spectra_data.h"
#include "dermis/spectral/piecewise_linear.h"

namespace dermis {

namespace {

// Spectra are integrated at 1 nm over the range of the CIE 1931 observer table.
constexpr int kLambdaMin = CieTables::kLambdaMin;
constexpr int kSamples = CieTables::kSamples;

struct Pairs {
  std::vector<double> lambda, value;
};
Pairs split(std::span<const double> interleaved) {
  Pairs p;
  for (size_t i = 0; i + 1 < interleaved.size(); i += 2) {
    p.lambda.push_back(interleaved[i]);
    p.value.push_back(interleaved[i + 1]);
  }
  return p;
}

const NamedSpectrumTable* find_table(const std::string& name) {
  for (const NamedSpectrumTable& t : named_spectrum_tables())
    if (name == t.name) return &t;
  return nullptr;
}

// CIE XYZ to linear sRGB, out-of-gamut components clamped to zero.
RGB xyz_to_srgb(double X, double Y, double Z) {
  const auto rgb = xyz_to_linear_srgb(X, Y, Z);
  return RGB(float(std::max(0.0, rgb[0])), float(std::max(0.0, rgb[1])), float(std::max(0.0, rgb[2])));
}

// Sum over 1 nm steps of s(lambda) * y-bar(lambda) / sum of y-bar: a spectrum's luminance
// relative to the equal-energy spectrum, the normalization pbrt-v4 gives named illuminants.
double relative_luminance(std::span<const double> lambda, std::span<const double> value, SpectrumEnds ends) {
  const CieTables& o = cie_tables();
  PiecewiseLinear f(lambda, value, ends);
  double sy = 0, y = 0;
  for (int i = 0; i < kSamples; ++i) {
    sy += f.at(kLambdaMin + i) * o.y[i];
    y += o.y[i];
  }
  return sy / y;
}

// Mean of a piecewise-linear function over [a, b] nm (midpoint rule at 0.1 nm: exact to ~1e-6
// relative for piecewise-linear data).
double mean_over(std::span<const double> lambda, std::span<const double> value, SpectrumEnds ends, double a, double b) {
  PiecewiseLinear f(lambda, value, ends);
  const int n = int((b - a) * 10);
  double sum = 0;
  for (int i = 0; i < n; ++i) sum += f.at(a + (i + 0.5) * (b - a) / n);
  return sum / n;
}

}  // namespace

RGB spectrum_rgb(std::span<const double> lambda, std::span<const double> value, SpectrumType type, SpectrumEnds ends) {
  const CieTables& o = cie_tables();
  PiecewiseLinear f(lambda, value, ends);
  double X = 0, Y = 0, Z = 0;
  for (int i = 0; i < kSamples; ++i) {
    // Object colours: X = k * sum S R x-bar, k = 1 / sum S y-bar, with S = D65 (CIE 015:2004,
    // eqs. 7.1-7.3); light sources: X = sum Le x-bar, then divided by Y (pbrt-v4's lights).
    const double s = f.at(kLambdaMin + i) * (type == SpectrumType::Unbounded ? o.d65[i] : 1.0);
    X += s * o.x[i];
    Y += s * o.y[i];
    Z += s * o.z[i];
  }
  const double k = type == SpectrumType::Unbounded ? 1 / o.d65_y : (Y > 0 ? 1 / Y : 0);
  return xyz_to_srgb(X * k, Y * k, Z * k);
}

std::optional<RGB> named_spectrum_rgb(const std::string& name, SpectrumType type) {
  const NamedSpectrumTable* t = find_table(name);
  if (!t) return std::nullopt;
  Pairs p = split(t->pairs);
  if (t->kind == NamedSpectrumKind::Illuminant) {
    // pbrt-v4 scales its named illuminants to luminance 1 (PiecewiseLinearSpectrum::FromInterleaved).
    const double lum = relative_luminance(p.lambda, p.value, SpectrumEnds::Extend);
    for (double& v : p.value) v /= lum;
  }
  return spectrum_rgb(p.lambda, p.value, type, SpectrumEnds::Extend);
}

std::optional<float> named_glass_ior(const std::string& name) {
  const NamedSpectrumTable* t = find_table(name);
  if (!t || t->kind != NamedSpectrumKind::GlassIndex) return std::nullopt;
  const Pairs p = split(t->pairs);
  return float(mean_over(p.lambda, p.value, SpectrumEnds::Extend, 400, 700));
}

bool is_camera_sensor_spectrum(const std::string& name) {
  for (const char* camera : camera_sensor_names())
    for (const char* channel : {"_r", "_g", "_b"})
      if (name == std::string(camera) + channel) return true;
  return false;
}

std::string named_spectrum_list() {
  std::string s;
  for (const NamedSpectrumTable& t : named_spectrum_tables()) s += (s.empty() ? "" : ", ") + std::string(t.name);
  s += "; camera sensor curves (Film \"sensor\" only):";
  for (const char* camera : camera_sensor_names()) s += fmt::format(" {}_{{r,g,b}}", camera);
  return s;
}

RGB blackbody_rgb(double kelvin) {
  std::array<double, kSamples> lambda, value;
  for (int i = 0; i < kSamples; ++i) {
    lambda[i] = kLambdaMin + i;
    value[i] = planck(lambda[i], kelvin);
  }
  return spectrum_rgb(lambda, value, SpectrumType::Illuminant);
}

namespace {

void check_pairs(const ParsedParam& p) {
  const std::vector<double> v = p.param.numbers_as_doubles();
  if (v.size() < 2 || v.size() % 2 != 0)
    throw SceneError(p.value_loc, fmt::format("spectrum '{}' needs [wavelength value ...] pairs, got {} numbers",
                                              p.param.name, v.size()));
  for (size_t i = 2; i < v.size(); i += 2)
    if (v[i] <= v[i - 2])
      throw SceneError(p.value_at(i), fmt::format("spectrum '{}': wavelengths must increase ({} after {})",
                                                  p.param.name, v[i], v[i - 2]));
}

// A spectrum given by name: pbrt-v4 looks the name up among its named spectra first, then
// reads it as a spectrum file (relative to the scene's directory).
std::string unknown_spectrum_message(const std::string& name, const std::string& path) {
  std::string hint;
  std::size_t best = 4;  // the nearest name at most 3 edits away
  for (const NamedSpectrumTable& t : named_spectrum_tables())
    if (const std::size_t d = edit_distance(name, t.name); d < best) {
      best = d;
      hint = fmt::format(" (did you mean '{}'?)", t.name);
    }
  return fmt::format("unknown named spectrum '{}'{} and no spectrum file '{}'; named spectra: {}", name, hint, path,
                     named_spectrum_list());
}

Pairs spectrum_file_pairs(const ParsedParam& p) {
  const std::string& name = p.param.strings[0];
  if (is_camera_sensor_spectrum(name))
    throw SceneError(p.value_loc, fmt::format("'{}' is a camera sensor curve, which pbrt-v4 uses only through Film "
                                              "\"string sensor\"; Dermis's film records linear sRGB",
                                              name));
  const std::string path = resolve_path(name, p.base_dir);
  if (p.file_access) p.file_access->check_read(path, name, p.value_loc, "spectrum file");
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw SceneError(p.value_loc, unknown_spectrum_message(name, path));
  SampledSpectrum f = read_spectrum_file(path, p.value_loc);
  return {std::move(f.lambda), std::move(f.value)};
}

}  // namespace

RGB spectrum_param_rgb(const ParsedParam& p, Diagnostics& diag, SpectrumType type) {
  p.used = true;
  if (p.type == "rgb") {
    if (p.param.number_count() != 3)
      throw SceneError(p.value_loc, fmt::format("parameter \"{} {}\" expects 3 values, got {}", p.param.type,
                                                p.param.name, p.param.number_count()));
    return RGB(float(p.param.numbers[0]), float(p.param.numbers[1]), float(p.param.numbers[2]));
  }
  if (p.type == "blackbody") {
    const auto& v = p.param.numbers;
    if (p.param.number_count() != 1 && p.param.number_count() != 2)
      throw SceneError(p.value_loc, fmt::format("parameter \"blackbody {}\" expects a temperature in kelvin, got "
                                                "{} values",
                                                p.param.name, p.param.number_count()));
    if (v[0] <= 0) throw SceneError(p.value_at(0), fmt::format("blackbody temperature must be positive, got {}", v[0]));
    RGB rgb = blackbody_rgb(v[0]);
    if (v.size() == 2) rgb *= float(v[1]);  // pbrt-v3's [T scale]
    return rgb;
  }
  const char* how = type == SpectrumType::Illuminant
                        ? "its chromaticity at luminance 1, as pbrt-v4 normalizes light spectra; \"scale\" sets the "
                          "brightness"
                        : "its colour under D65, CIE 1931 observer";
  if (p.type == "spectrum") {
    if (!p.param.strings.empty()) {
      if (auto rgb = named_spectrum_rgb(p.param.strings[0], type)) return *rgb;
      const Pairs f = spectrum_file_pairs(p);
      diag.warn(p.param.loc,
                fmt::format("spectrum file '{}' for '{}' reduced to RGB ({})", p.param.strings[0], p.param.name, how));
      return spectrum_rgb(f.lambda, f.value, type);
    }
    check_pairs(p);
    const Pairs s = split(p.param.numbers_as_doubles());
    diag.warn(p.param.loc, fmt::format("sampled spectrum '{}' reduced to RGB ({})", p.param.name, how));
    return spectrum_rgb(s.lambda, s.value, type);
  }
  throw SceneError(p.param.loc, fmt::format("parameter '{}' has type '{}', expected rgb, spectrum or blackbody",
                                            p.param.name, p.param.type));
}

namespace {

// At every nanometre, scaled as `type` asks (spectrum_param_samples).
std::vector<float> samples_of(std::span<const double> value, SpectrumType type, double extra_scale) {
  if (type == SpectrumType::Illuminant) {
    // Luminance 1: sum s y / sum y = 1, as the film's colour of it (spectral/sampled_wavelengths.h).
    const CieTables& o = cie_tables();
    double sy = 0;
    for (int i = 0; i < kSamples; ++i) sy += value[std::size_t(i)] * o.y[std::size_t(i)];
    if (sy > 0) extra_scale *= o.y_sum / sy;
  }
  std::vector<float> out(kSamples);
  for (int i = 0; i < kSamples; ++i) out[std::size_t(i)] = float(value[std::size_t(i)] * extra_scale);
  return out;
}

std::vector<double> at_every_nanometre(const Pairs& pairs, SpectrumEnds ends) {
  PiecewiseLinear f(pairs.lambda, pairs.value, ends);
  std::vector<double> value(kSamples);
  for (int i = 0; i < kSamples; ++i) value[std::size_t(i)] = f.at(kLambdaMin + i);
  return value;
}

}  // namespace

std::optional<std::vector<float>> named_spectrum_samples(const std::string& name, SpectrumType type) {
  const NamedSpectrumTable* t = find_table(name);
  if (!t) return std::nullopt;
  return samples_of(at_every_nanometre(split(t->pairs), SpectrumEnds::Extend), type, 1);
}

std::optional<std::vector<float>> spectrum_param_samples(const ParsedParam& p, SpectrumType type) {
  if (p.type != "blackbody" && p.type != "spectrum") return std::nullopt;
  if (p.type == "spectrum" && !p.param.strings.empty())
    if (auto named = named_spectrum_samples(p.param.strings[0], type)) return named;
  if (p.type == "blackbody") {
    const auto& v = p.param.numbers;  // checked by spectrum_param_rgb
    std::vector<double> value(kSamples);
    for (int i = 0; i < kSamples; ++i) value[std::size_t(i)] = planck(kLambdaMin + i, v[0]);
    return samples_of(value, type, v.size() == 2 ? v[1] : 1);  // pbrt-v3's [T scale]
  }
  if (!p.param.strings.empty())
    return samples_of(at_every_nanometre(spectrum_file_pairs(p), SpectrumEnds::Zero), type, 1);
  check_pairs(p);
  return samples_of(at_every_nanometre(split(p.param.numbers_as_doubles()), SpectrumEnds::Zero), type, 1);
}

float ior_param(const ParsedParam& p, Diagnostics& diag) {
  p.used = true;
  if (p.type == "float") {
    if (p.param.numbers.size() != 1)
      throw SceneError(p.value_loc, fmt::format("parameter \"float {}\" expects exactly one value", p.param.name));
    return float(p.param.numbers[0]);
  }
  if (p.type == "spectrum") {
    Pairs s;
    if (!p.param.strings.empty()) {
      if (auto ior = named_glass_ior(p.param.strings[0])) return *ior;
      if (find_table(p.param.strings[0]))
        throw SceneError(p.value_loc, fmt::format("named spectrum '{}' is not an index of refraction; valid names: "
                                                  "glass-BK7, glass-BAF10, glass-FK51A, glass-LASF9, glass-F5, "
                                                  "glass-F10, glass-F11, or a spectrum file",
                                                  p.param.strings[0]));
      s = spectrum_file_pairs(p);
      diag.warn(p.param.loc, fmt::format("spectrum file '{}' for '{}' reduced to its mean over 400-700 nm",
                                         p.param.strings[0], p.param.name));
    } else {
      check_pairs(p);
      s = split(p.param.numbers_as_doubles());
      diag.warn(p.param.loc, fmt::format("sampled spectrum '{}' reduced to its mean over 400-700 nm", p.param.name));
    }
    return float(mean_over(s.lambda, s.value, SpectrumEnds::Zero, 400, 700));
  }
  throw SceneError(p.param.loc,
                   fmt::format("parameter '{}' has type '{}', expected float or spectrum", p.param.name, p.param.type));
}

}  // namespace dermis
