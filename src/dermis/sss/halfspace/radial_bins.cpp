#include "dermis/sss/halfspace/radial_bins.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dermis::sss {

RadialBins RadialBins::linear(double r_max, int count) {
  if (!(r_max > 0 && std::isfinite(r_max)))
    throw std::invalid_argument("radial bins: r_max must be positive and finite, got " + std::to_string(r_max));
  if (count < 1) throw std::invalid_argument("radial bins: need at least one bin, got " + std::to_string(count));
  std::vector<double> edges(count + 1);
  for (int i = 0; i <= count; ++i) edges[i] = r_max * i / count;
  RadialBins bins(std::move(edges), false);
  bins.inv_width_ = count / r_max;
  return bins;
}

RadialBins RadialBins::logarithmic(double r_min, double r_max, int count) {
  if (!(r_max > 0 && std::isfinite(r_max)))
    throw std::invalid_argument("radial bins: r_max must be positive and finite, got " + std::to_string(r_max));
  if (!(r_min > 0 && r_min < r_max))
    throw std::invalid_argument("radial bins: logarithmic bins need 0 < r_min < r_max, got r_min = " +
                                std::to_string(r_min));
  if (count < 2) throw std::invalid_argument("radial bins: logarithmic bins need at least 2 bins");
  std::vector<double> edges(count + 1);
  edges[0] = 0;
  const double log_ratio = std::log(r_max / r_min) / (count - 1);
  for (int i = 1; i <= count; ++i) edges[i] = r_min * std::exp(log_ratio * (i - 1));
  edges[count] = r_max;
  RadialBins bins(std::move(edges), true);
  bins.inv_log_ratio_ = 1 / log_ratio;
  return bins;
}

double RadialBins::annulus_area(int i) const {
  return 3.14159265358979323846 * (edges_[i + 1] * edges_[i + 1] - edges_[i] * edges_[i]);
}

int RadialBins::index(double r) const {
  const int n = count();
  if (!(r < edges_[n])) return -1;
  int i = log_spaced_ ? (r < edges_[1] ? 0 : 1 + int(std::log(r / edges_[1]) * inv_log_ratio_)) : int(r * inv_width_);
  i = std::clamp(i, 0, n - 1);
  // The formula may be off by one at an edge through rounding: settle it on the edges.
  while (i > 0 && r < edges_[i]) --i;
  while (i < n - 1 && r >= edges_[i + 1]) ++i;
  return i;
}

}  // namespace dermis::sss
