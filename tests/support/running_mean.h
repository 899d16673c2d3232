// A running mean and the standard error of the mean, for tests that state their tolerance
// in standard errors.
#pragma once

#include <algorithm>
#include <cmath>

namespace dermis::testing {

struct Mean {
  double n = 0, s = 0, s2 = 0;
  void add(double x) { n += 1, s += x, s2 += x * x; }
  double mean() const { return s / n; }
  double stderr_() const { return std::sqrt(std::max(0.0, s2 / n - mean() * mean()) / (n - 1)); }
};

}  // namespace dermis::testing
