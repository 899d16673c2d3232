#include "dermis/spectral/cie_observer.h"

#include <algorithm>
#include <string_view>
#include <vector>

#include "dermis/spectral/named_spectra_data.h"
#include "dermis/spectral/piecewise_linear.h"

namespace dermis {

namespace {

// Values at every nanometre of a table at every 5 nm (`v[k]` at 360 + 5k nm) by Sprague's
// quintic interpolation, as CIE 167:2005 recommends for the colour-matching functions (a
// fifth-degree polynomial through six neighbours; linear in the two end intervals, where
// the functions are near zero).
std::array<double, CieTables::kSamples> sprague_5nm_to_1nm(const std::vector<double>& v) {
  std::array<double, CieTables::kSamples> out{};
  const int n = int(v.size());
  for (int i = 0; i < CieTables::kSamples; ++i) {
    const int k = std::min(i / 5, n - 2);
    const double x = double(i - 5 * k) / 5;
    if (k < 2 || k + 3 >= n) {
      out[std::size_t(i)] = (1 - x) * v[std::size_t(k)] + x * v[std::size_t(k) + 1];
      continue;
    }
    auto f = [&](int d) { return v[std::size_t(k + d)]; };
    const double a1 = (2 * f(-2) - 16 * f(-1) + 16 * f(1) - 2 * f(2)) / 24;
    const double a2 = (-f(-2) + 16 * f(-1) - 30 * f(0) + 16 * f(1) - f(2)) / 24;
    const double a3 = (-9 * f(-2) + 39 * f(-1) - 70 * f(0) + 66 * f(1) - 33 * f(2) + 7 * f(3)) / 24;
    const double a4 = (13 * f(-2) - 64 * f(-1) + 126 * f(0) - 124 * f(1) + 61 * f(2) - 12 * f(3)) / 24;
    const double a5 = (-5 * f(-2) + 25 * f(-1) - 50 * f(0) + 50 * f(1) - 25 * f(2) + 5 * f(3)) / 24;
    out[std::size_t(i)] = std::max(0.0, f(0) + x * (a1 + x * (a2 + x * (a3 + x * (a4 + x * a5)))));
  }
  return out;
}

}  // namespace

const CieTables& cie_tables() {
  static const CieTables tables = [] {
    CieTables t;
    std::vector<double> x, y, z;
    for (const CieObserverSample& s : cie_1931_observer()) x.push_back(s.x), y.push_back(s.y), z.push_back(s.z);
    t.x = sprague_5nm_to_1nm(x);
    t.y = sprague_5nm_to_1nm(y);
    t.z = sprague_5nm_to_1nm(z);
    // D65 linearly between its tabulated wavelengths (CIE 015:2004 sec. 7.2.1.1's advice).
    std::vector<double> dl, dv;
    for (const NamedSpectrumTable& n : named_spectrum_tables())
      if (std::string_view(n.name) == "stdillum-D65")
        for (std::size_t i = 0; i + 1 < n.pairs.size(); i += 2) dl.push_back(n.pairs[i]), dv.push_back(n.pairs[i + 1]);
    PiecewiseLinear fd(dl, dv, SpectrumEnds::Extend);
    for (int i = 0; i < CieTables::kSamples; ++i) {
      t.d65[std::size_t(i)] = fd.at(CieTables::kLambdaMin + i);
      t.y_sum += t.y[std::size_t(i)];
      t.d65_y += t.d65[std::size_t(i)] * t.y[std::size_t(i)];
    }
    return t;
  }();
  return tables;
}

float cie_table_at(const std::array<double, CieTables::kSamples>& table, float lambda_nm) {
  const float x = lambda_nm - CieTables::kLambdaMin;
  if (!(x >= 0 && x <= CieTables::kSamples - 1)) return 0;
  const int i = std::min(int(x), CieTables::kSamples - 2);
  const float f = x - float(i);
  return float((1 - f) * table[std::size_t(i)] + f * table[std::size_t(i) + 1]);
}

std::array<double, 3> xyz_to_linear_srgb(double X, double Y, double Z) {
  return {3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z, -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z,
          0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z};
}

}  // namespace dermis
