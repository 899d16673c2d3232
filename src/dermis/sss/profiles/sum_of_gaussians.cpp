#include "dermis/sss/profiles/sum_of_gaussians.h"

#include <string>

namespace dermis::sss {

SumOfGaussiansProfile::SumOfGaussiansProfile(std::span<const double> variances, std::span<const double> weights) {
  if (variances.size() != weights.size())
    throw std::invalid_argument("sum of Gaussians: " + std::to_string(variances.size()) + " variances but " +
                                std::to_string(weights.size()) + " weights");
  if (variances.empty() || variances.size() > std::size_t(kMaxLobes))
    throw std::invalid_argument("sum of Gaussians: between 1 and " + std::to_string(kMaxLobes) +
                                " lobes are supported (got " + std::to_string(variances.size()) + ")");
  count_ = int(variances.size());
  for (int i = 0; i < count_; ++i) {
    lobes_[i] = GaussianProfile(variances[i], weights[i]);
    albedo_ += weights[i];
    r_max_ = std::max(r_max_, lobes_[i].r_max());
  }
  for (int i = 0; i < count_; ++i) {
    probability_[i] = albedo_ > 0 ? weights[i] / albedo_ : 1.0 / count_;
    if (probability_[i] > 0) last_positive_ = i;
  }
}

double SumOfGaussiansProfile::r_max(double energy_fraction) const {
  GaussianProfile::check_fraction(energy_fraction);
  auto kept = [&](double r) {
    double s = 0;
    for (int i = 0; i < count_; ++i) s += probability_[i] * -std::expm1(-r * r / (2 * lobes_[i].variance()));
    return s;
  };
  double lo = 0, hi = 0;
  for (int i = 0; i < count_; ++i) hi = std::max(hi, lobes_[i].r_max(energy_fraction));
  for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (kept(mid) < energy_fraction ? lo : hi) = mid;
  }
  return hi;
}

std::array<SumOfGaussiansProfile, 3> skin_sum_of_gaussians(double scene_units_per_mm, RGB albedo) {
  if (!(scene_units_per_mm > 0) || !std::isfinite(scene_units_per_mm))
    throw std::invalid_argument("skin sum of Gaussians: scene_units_per_mm must be positive (got " +
                                std::to_string(scene_units_per_mm) + ")");
  // d'Eon & Luebke 2007, GPU Gems 3 ch. 14, Table 14-1: variances (mm^2) and RGB weights.
  static constexpr double kVarianceMm2[6] = {0.0064, 0.0484, 0.187, 0.567, 1.99, 7.41};
  static constexpr double kWeight[6][3] = {{0.233, 0.455, 0.649}, {0.100, 0.336, 0.344}, {0.118, 0.198, 0.0},
                                           {0.113, 0.007, 0.007}, {0.358, 0.004, 0.0},   {0.078, 0.0, 0.0}};
  std::array<SumOfGaussiansProfile, 3> rgb;
  for (int c = 0; c < 3; ++c) {
    double v[6], w[6];
    for (int i = 0; i < 6; ++i) {
      v[i] = kVarianceMm2[i] * scene_units_per_mm * scene_units_per_mm;
      w[i] = kWeight[i][c] * double(albedo[c]);
    }
    rgb[c] = SumOfGaussiansProfile(std::span<const double>(v, 6), std::span<const double>(w, 6));
  }
  return rgb;
}

}  // namespace dermis::sss
