// Radial bins [r_i, r_{i+1}) over [0, r_max] for exit profiles R(r), linear or
// logarithmic, with the annulus area of each bin.
#pragma once

#include <utility>
#include <vector>

namespace dermis::sss {

class RadialBins {
 public:
  // `count` equal bins over [0, r_max].
  static RadialBins linear(double r_max, int count);
  // A first bin [0, r_min), then count - 1 bins with geometrically growing edges
  // from r_min to r_max.
  static RadialBins logarithmic(double r_min, double r_max, int count);

  RadialBins() : RadialBins(linear(16.0, 64)) {}

  int count() const { return int(edges_.size()) - 1; }
  double r_max() const { return edges_.back(); }
  double lo(int i) const { return edges_[i]; }
  double hi(int i) const { return edges_[i + 1]; }
  // pi (hi^2 - lo^2)
  double annulus_area(int i) const;
  // The bin holding r >= 0, or -1 when r >= r_max.
  int index(double r) const;
  bool log_spaced() const { return log_spaced_; }

 private:
  RadialBins(std::vector<double> edges, bool log_spaced) : edges_(std::move(edges)), log_spaced_(log_spaced) {}
  std::vector<double> edges_;
  bool log_spaced_ = false;
  double inv_width_ = 0;      // linear: count / r_max
  double inv_log_ratio_ = 0;  // logarithmic: 1 / ln(edge ratio)
};

}  // namespace dermis::sss
