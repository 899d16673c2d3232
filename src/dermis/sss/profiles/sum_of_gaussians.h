// A sum of Gaussians per channel, R(r) = sum_i w_i G(v_i, r) (d'Eon & Luebke 2007,
// GPU Gems 3 ch. 14, eq. 14-4), with the six-Gaussian skin preset of that chapter.
// Sampling picks a lobe with probability w_i / W, then the lobe's truncated Gaussian
// warp (King et al. 2013); the radial pdf is the mixture of the truncated lobes.
#pragma once

#include <array>
#include <initializer_list>
#include <span>

#include "dermis/core/rgb.h"
#include "dermis/sss/profiles/gaussian.h"

namespace dermis::sss {

class SumOfGaussiansProfile {
 public:
  static constexpr int kMaxLobes = 8;

  SumOfGaussiansProfile() = default;
  // Lobes in scene units (variances in scene units^2); weights >= 0, at most kMaxLobes.
  SumOfGaussiansProfile(std::span<const double> variances, std::span<const double> weights);
  SumOfGaussiansProfile(std::initializer_list<double> variances, std::initializer_list<double> weights)
      : SumOfGaussiansProfile(std::span<const double>(variances.begin(), variances.size()),
                              std::span<const double>(weights.begin(), weights.size())) {}

  // The lobes, exposed for the probe sampler's one-sample MIS over lobes and channels.
  int lobe_count() const { return count_; }
  const GaussianProfile& lobe(int i) const { return lobes_[i]; }
  // Probability with which sample_radius picks lobe i: w_i / W (uniform when W = 0).
  double lobe_probability(int i) const { return probability_[i]; }

  double albedo() const { return albedo_; }
  double eval(double r) const {
    double sum = 0;
    for (int i = 0; i < count_; ++i) sum += lobes_[i].eval(r);
    return sum;
  }
  // Largest lobe truncation radius sqrt(12.46 v_i).
  double r_max() const { return r_max_; }
  // Radius keeping the fraction f of the (untruncated) energy: bisection on
  // sum_i w_i (1 - e^{-r^2/(2 v_i)}) = f W.
  double r_max(double energy_fraction) const;
  // Picks lobe i with probability w_i / W using xi, reuses the rescaled xi for the radius.
  double sample_radius(double xi) const {
    int i = 0;
    while (i < last_positive_ && xi >= probability_[i]) {
      xi -= probability_[i];
      ++i;
    }
    const double u = probability_[i] > 0 ? std::min(xi / probability_[i], 0x1.fffffffffffffp-1) : 0.0;
    return lobes_[i].sample_radius(u);
  }
  // Mixture of the truncated lobe pdfs: sum_i (w_i / W) pdf_i(r).
  double pdf_radius(double r) const {
    double sum = 0;
    for (int i = 0; i < count_; ++i) sum += probability_[i] * lobes_[i].pdf_radius(r);
    return sum;
  }

 private:
  std::array<GaussianProfile, kMaxLobes> lobes_{};
  std::array<double, kMaxLobes> probability_{};
  int count_ = 0;
  int last_positive_ = 0;  // last lobe with a nonzero probability (guards rounding of xi)
  double albedo_ = 0;
  double r_max_ = 0;
};

// The d'Eon & Luebke skin profile (GPU Gems 3 ch. 14, Table 14-1): six Gaussians with
// variances 0.0064 ... 7.41 mm^2 and per-channel weights (each channel's weights sum
// to 1), times `albedo` per channel. `scene_units_per_mm` converts millimetres to scene
// units (variances scale by its square).
std::array<SumOfGaussiansProfile, 3> skin_sum_of_gaussians(double scene_units_per_mm, RGB albedo = RGB(1.0f));

}  // namespace dermis::sss
