#include "dermis/spectral/cie_observer.h"

#include <algorithm>
#include <string_view>
#include <vector>

#include "dermis/spectral/named_spectra_data.h"
#include "dermis/spectral/piecewise_linear.h"

namespace dermis {

const CieTables& cie_tables() {
  static const CieTables tables = [] {
    CieTables t;
    std::vector<double> l, x, y, z;
    for (const CieObserverSample& s : cie_1931_observer()) {
      l.push_back(s.lambda);
      x.push_back(s.x);
      y.push_back(s.y);
      z.push_back(s.z);
    }
    std::vector<double> dl, dv;
    for (const NamedSpectrumTable& n : named_spectrum_tables())
      if (std::string_view(n.name) == "stdillum-D65")
        for (std::size_t i = 0; i + 1 < n.pairs.size(); i += 2) dl.push_back(n.pairs[i]), dv.push_back(n.pairs[i + 1]);
    PiecewiseLinear fx(l, x, SpectrumEnds::Zero), fy(l, y, SpectrumEnds::Zero), fz(l, z, SpectrumEnds::Zero);
    PiecewiseLinear fd(dl, dv, SpectrumEnds::Extend);
    for (int i = 0; i < CieTables::kSamples; ++i) {
      const double lambda = CieTables::kLambdaMin + i;
      t.x[i] = fx.at(lambda);
      t.y[i] = fy.at(lambda);
      t.z[i] = fz.at(lambda);
      t.d65[i] = fd.at(lambda);
      t.y_sum += t.y[i];
      t.d65_y += t.d65[i] * t.y[i];
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
