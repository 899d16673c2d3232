// The mean and standard error per colour channel of n draws of an RGB estimator, for tests
// that state their tolerance in standard errors.
#pragma once

#include <functional>

#include "dermis/core/rgb.h"
#include "support/running_mean.h"

namespace dermis::testing {

struct RgbEstimate {
  double mean[3] = {0, 0, 0}, se[3] = {0, 0, 0};
};

inline RgbEstimate estimate_rgb(int n, const std::function<RGB()>& f) {
  Mean m[3];
  for (int i = 0; i < n; ++i) {
    const RGB v = f();
    for (int c = 0; c < 3; ++c) m[c].add(v[c]);
  }
  RgbEstimate e;
  for (int c = 0; c < 3; ++c) e.mean[c] = m[c].mean(), e.se[c] = m[c].stderr_();
  return e;
}

}  // namespace dermis::testing
