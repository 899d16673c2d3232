#include "dermis/spectral/blackbody.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "dermis/spectral/cie_observer.h"

namespace dermis {

double planck(double lambda_nm, double kelvin) {
  const double c = 299792458.0, h = 6.62607015e-34, kb = 1.380649e-23;
  const double l = lambda_nm * 1e-9;
  return 2 * h * c * c / (std::pow(l, 5) * (std::exp(h * c / (l * kb * kelvin)) - 1));
}

float normalized_blackbody(float lambda_nm, float kelvin) {
  if (!(kelvin > 0)) return 0;
  const double peak_nm = 2.8977721e-3 / kelvin * 1e9;  // Wien's displacement law
  return float(planck(lambda_nm, kelvin) / planck(peak_nm, kelvin));
}

namespace {

constexpr double kMinKelvin = 100, kMaxKelvin = 1e5;
constexpr int kEntries = 1024;

// ln X, ln Y, ln Z of the film's sum (CIE 1931 over 360-830 nm, divided by the integral of y).
std::array<double, 3> log_xyz(double kelvin) {
  const CieTables& cie = cie_tables();
  double X = 0, Y = 0, Z = 0;
  for (int i = 0; i < CieTables::kSamples; ++i) {
    const double v = planck(CieTables::kLambdaMin + i, kelvin) / cie.y_sum;
    X += v * cie.x[std::size_t(i)], Y += v * cie.y[std::size_t(i)], Z += v * cie.z[std::size_t(i)];
  }
  const double peak = planck(2.8977721e-3 / kelvin * 1e9, kelvin);
  return {std::log(X / peak), std::log(Y / peak), std::log(Z / peak)};
}

// The table holds the logarithms: in ln T they are nearly linear (Wien's tail, e^(-c / T)),
// where the colours themselves change by orders of magnitude between entries at low T.
const std::vector<std::array<double, 3>>& log_xyz_table() {
  static const std::vector<std::array<double, 3>> table = [] {
    std::vector<std::array<double, 3>> t(kEntries);
    for (int i = 0; i < kEntries; ++i)
      t[std::size_t(i)] = log_xyz(kMinKelvin * std::pow(kMaxKelvin / kMinKelvin, double(i) / (kEntries - 1)));
    return t;
  }();
  return table;
}

}  // namespace

RGB normalized_blackbody_rgb(float kelvin) {
  if (!(kelvin > kMinKelvin)) return RGB(0);
  const std::vector<std::array<double, 3>>& t = log_xyz_table();
  const double x = std::min(std::log(double(kelvin) / kMinKelvin) / std::log(kMaxKelvin / kMinKelvin) * (kEntries - 1),
                            double(kEntries - 1));
  const int i = std::min(int(x), kEntries - 2);
  const double f = x - i;
  std::array<double, 3> xyz;
  for (int c = 0; c < 3; ++c)
    xyz[std::size_t(c)] =
        std::exp(t[std::size_t(i)][std::size_t(c)] * (1 - f) + t[std::size_t(i) + 1][std::size_t(c)] * f);
  const auto rgb = xyz_to_linear_srgb(xyz[0], xyz[1], xyz[2]);
  return RGB(float(rgb[0]), float(rgb[1]), float(rgb[2]));
}

}  // namespace dermis
