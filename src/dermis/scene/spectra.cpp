#include "dermis/scene/spectra.h"

#include <cmath>
#include <map>

#include <fmt/format.h>

namespace dermis {

namespace {

// Band averages (B 400-500, G 500-600, R 600-700 nm, stored here as R, G, B) of the
// tabulated refractive indices that pbrt-v4 ships as named spectra (src/pbrt/util/
// spectrum.cpp, arrays Cu_eta, Cu_k, Au_*, Ag_*, Al_*; measured data after Palik), computed
// by integrating their piecewise-linear interpolants over each band.
struct MetalRGB {
  const char* name;
  RGB rgb;
};
constexpr MetalRGB kMetals[] = {
    {"metal-Cu-eta", {0.2427f, 0.8757f, 1.1624f}}, {"metal-Cu-k", {3.6046f, 2.6447f, 2.3807f}},
    {"metal-Au-eta", {0.1761f, 0.4118f, 1.4180f}}, {"metal-Au-k", {3.3020f, 2.5955f, 1.8807f}},
    {"metal-Ag-eta", {0.1363f, 0.1251f, 0.1501f}}, {"metal-Ag-k", {4.1272f, 3.3368f, 2.4620f}},
    {"metal-Al-eta", {1.4869f, 0.9672f, 0.6217f}}, {"metal-Al-k", {7.7954f, 6.6799f, 5.4706f}},
};

// Mean over 400-700 nm of pbrt-v4's glass tables (from refractiveindex.info, Schott
// Sellmeier fits; pbrt's "glass-F5/F10/F11" are the SF5/SF10/SF11 tables).
struct GlassIor {
  const char* name;
  float ior;
};
constexpr GlassIor kGlasses[] = {
    {"glass-BK7", 1.5196f}, {"glass-BAF10", 1.6752f}, {"glass-FK51A", 1.4886f}, {"glass-LASF9", 1.8601f},
    {"glass-F5", 1.6805f},  {"glass-F10", 1.7379f},   {"glass-F11", 1.7964f},
};

// Wyman, Sloan & Shirley 2013, "Simple Analytic Approximations to the CIE XYZ Color
// Matching Functions", JCGT 2(2), eq. 2 (multi-lobe piecewise Gaussian fit).
double piecewise_gaussian(double x, double mu, double sigma_below, double sigma_above) {
  double s = x < mu ? sigma_below : sigma_above;
  double t = (x - mu) / s;
  return std::exp(-0.5 * t * t);
}
double cie_x(double l) {
  return 1.056 * piecewise_gaussian(l, 599.8, 37.9, 31.0) + 0.362 * piecewise_gaussian(l, 442.0, 16.0, 26.7) -
         0.065 * piecewise_gaussian(l, 501.1, 20.4, 26.2);
}
double cie_y(double l) {
  return 0.821 * piecewise_gaussian(l, 568.8, 46.9, 40.5) + 0.286 * piecewise_gaussian(l, 530.9, 16.3, 31.1);
}
double cie_z(double l) {
  return 1.217 * piecewise_gaussian(l, 437.0, 11.8, 36.0) + 0.681 * piecewise_gaussian(l, 459.0, 26.0, 13.8);
}

// Planck's law, spectral radiance per unit wavelength (lambda in nm), up to a constant.
double planck(double lambda_nm, double kelvin) {
  const double c = 299792458.0, h = 6.62607015e-34, kb = 1.380649e-23;
  double l = lambda_nm * 1e-9;
  return 2 * h * c * c / (std::pow(l, 5) * (std::exp(h * c / (l * kb * kelvin)) - 1));
}

double piecewise_linear(const std::vector<double>& lambda, const std::vector<double>& value, double x) {
  if (lambda.empty() || x < lambda.front() || x > lambda.back()) return 0;
  size_t i = 0;
  while (i + 1 < lambda.size() && lambda[i + 1] < x) ++i;
  if (i + 1 == lambda.size()) return value[i];
  double t = (x - lambda[i]) / (lambda[i + 1] - lambda[i]);
  return value[i] + t * (value[i + 1] - value[i]);
}

double band_mean(const std::vector<double>& lambda, const std::vector<double>& value, double a, double b) {
  // Midpoint rule at 0.1 nm: exact to ~1e-6 relative for piecewise-linear data.
  const int n = int((b - a) * 10);
  double sum = 0;
  for (int i = 0; i < n; ++i) sum += piecewise_linear(lambda, value, a + (i + 0.5) * (b - a) / n);
  return sum / n;
}

}  // namespace

RGB band_average_rgb(const std::vector<double>& lambda, const std::vector<double>& value) {
  return RGB(float(band_mean(lambda, value, kBandEdgesNm[2], kBandEdgesNm[3])),
             float(band_mean(lambda, value, kBandEdgesNm[1], kBandEdgesNm[2])),
             float(band_mean(lambda, value, kBandEdgesNm[0], kBandEdgesNm[1])));
}

std::optional<RGB> named_spectrum_rgb(const std::string& name) {
  for (const MetalRGB& m : kMetals)
    if (name == m.name) return m.rgb;
  // pbrt-v4's brass table is not bundled; copper is the closest documented stand-in.
  if (name == "metal-CuZn-eta") return kMetals[0].rgb;
  if (name == "metal-CuZn-k") return kMetals[1].rgb;
  // D65 is the white point of Rec.709: the RGB white.
  if (name == "stdillum-D65") return RGB(1, 1, 1);
  return std::nullopt;
}

std::optional<float> named_glass_ior(const std::string& name) {
  for (const GlassIor& g : kGlasses)
    if (name == g.name) return g.ior;
  return std::nullopt;
}

std::string named_spectrum_list() {
  std::string s;
  for (const MetalRGB& m : kMetals) s += std::string(m.name) + ", ";
  s += "metal-CuZn-eta, metal-CuZn-k, stdillum-D65";
  for (const GlassIor& g : kGlasses) s += ", " + std::string(g.name);
  return s;
}

RGB blackbody_rgb(double kelvin) {
  double X = 0, Y = 0, Z = 0;
  for (double l = 360; l <= 830; l += 1) {
    double b = planck(l, kelvin);
    X += b * cie_x(l);
    Y += b * cie_y(l);
    Z += b * cie_z(l);
  }
  X /= Y;
  Z /= Y;
  Y = 1;
  // CIE XYZ to linear Rec.709 / sRGB (IEC 61966-2-1, D65 white).
  double r = 3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z;
  double g = -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z;
  double b = 0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z;
  return RGB(float(std::max(0.0, r)), float(std::max(0.0, g)), float(std::max(0.0, b)));
}

namespace {

void check_pairs(const ParsedParam& p) {
  const auto& v = p.param.numbers;
  if (v.size() < 2 || v.size() % 2 != 0)
    throw SceneError(p.value_loc, fmt::format("spectrum '{}' needs [wavelength value ...] pairs, got {} numbers",
                                              p.param.name, v.size()));
  for (size_t i = 2; i < v.size(); i += 2)
    if (v[i] <= v[i - 2])
      throw SceneError(p.value_at(i), fmt::format("spectrum '{}': wavelengths must increase ({} after {})",
                                                  p.param.name, v[i], v[i - 2]));
}

void split_pairs(const std::vector<double>& v, std::vector<double>& lambda, std::vector<double>& value) {
  for (size_t i = 0; i + 1 < v.size(); i += 2) {
    lambda.push_back(v[i]);
    value.push_back(v[i + 1]);
  }
}

}  // namespace

RGB spectrum_param_rgb(const ParsedParam& p, Diagnostics& diag) {
  p.used = true;
  if (p.type == "rgb") {
    if (p.param.numbers.size() != 3)
      throw SceneError(p.value_loc, fmt::format("parameter \"{} {}\" expects 3 values, got {}", p.param.type,
                                                p.param.name, p.param.numbers.size()));
    return RGB(float(p.param.numbers[0]), float(p.param.numbers[1]), float(p.param.numbers[2]));
  }
  if (p.type == "blackbody") {
    const auto& v = p.param.numbers;
    if (v.size() != 1 && v.size() != 2)
      throw SceneError(p.value_loc, fmt::format("parameter \"blackbody {}\" expects a temperature in kelvin, got "
                                                "{} values",
                                                p.param.name, v.size()));
    if (v[0] <= 0)
      throw SceneError(p.value_at(0), fmt::format("blackbody temperature must be positive, got {}", v[0]));
    RGB rgb = blackbody_rgb(v[0]);
    if (v.size() == 2) rgb *= float(v[1]);  // pbrt-v3's [T scale]
    return rgb;
  }
  if (p.type == "spectrum") {
    if (!p.param.strings.empty()) {
      const std::string& name = p.param.strings[0];
      if (auto rgb = named_spectrum_rgb(name)) {
        if (name.rfind("metal-CuZn", 0) == 0)
          diag.warn(p.param.loc, fmt::format("'{}' is approximated by copper's RGB values (brass data not "
                                             "bundled)",
                                             name));
        return *rgb;
      }
      if (auto ior = named_glass_ior(name)) return RGB(*ior);
      throw SceneError(p.value_loc, fmt::format("unknown named spectrum '{}' (spectrum files are not supported); "
                                                "valid names: {}",
                                                name, named_spectrum_list()));
    }
    check_pairs(p);
    std::vector<double> lambda, value;
    split_pairs(p.param.numbers, lambda, value);
    diag.warn(p.param.loc, fmt::format("sampled spectrum '{}' reduced to RGB by averaging over 600-700, "
                                       "500-600 and 400-500 nm",
                                       p.param.name));
    return band_average_rgb(lambda, value);
  }
  throw SceneError(p.param.loc, fmt::format("parameter '{}' has type '{}', expected rgb, spectrum or blackbody",
                                            p.param.name, p.param.type));
}

float ior_param(const ParsedParam& p, Diagnostics& diag) {
  p.used = true;
  if (p.type == "float") {
    if (p.param.numbers.size() != 1)
      throw SceneError(p.value_loc, fmt::format("parameter \"float {}\" expects exactly one value", p.param.name));
    return float(p.param.numbers[0]);
  }
  if (p.type == "spectrum") {
    if (!p.param.strings.empty()) {
      if (auto ior = named_glass_ior(p.param.strings[0])) return *ior;
      throw SceneError(p.value_loc, fmt::format("unknown named spectrum '{}' for an index of refraction; valid "
                                                "names: glass-BK7, glass-BAF10, glass-FK51A, glass-LASF9, "
                                                "glass-F5, glass-F10, glass-F11",
                                                p.param.strings[0]));
    }
    check_pairs(p);
    std::vector<double> lambda, value;
    split_pairs(p.param.numbers, lambda, value);
    diag.warn(p.param.loc, fmt::format("sampled spectrum '{}' reduced to its mean over 400-700 nm", p.param.name));
    return float(band_mean(lambda, value, kBandEdgesNm[0], kBandEdgesNm[3]));
  }
  throw SceneError(p.param.loc, fmt::format("parameter '{}' has type '{}', expected float or spectrum",
                                            p.param.name, p.param.type));
}

}  // namespace dermis
