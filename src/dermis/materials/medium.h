// A homogeneous participating medium with a Henyey-Greenstein phase function.
#pragma once

#include <limits>

#include "dermis/core/rgb.h"

namespace dermis {

struct HomogeneousMedium {
  RGB sigma_a, sigma_s, sigma_t;  // per scene unit, scale applied
  float g = 0;

  static HomogeneousMedium from_coefficients(RGB sigma_a, RGB sigma_s, float scale, float g) {
    HomogeneousMedium m;
    m.sigma_a = sigma_a * scale;
    m.sigma_s = sigma_s * scale;
    m.sigma_t = m.sigma_a + m.sigma_s;
    m.g = g;
    return m;
  }
  // Beer-Lambert transmittance over a distance.
  RGB transmittance(float distance) const {
    if (distance == std::numeric_limits<float>::infinity()) {
      RGB r;
      for (int c = 0; c < 3; ++c) r[c] = sigma_t[c] > 0 ? 0.0f : 1.0f;
      return r;
    }
    return exp(sigma_t * -distance);
  }
};

}  // namespace dermis
