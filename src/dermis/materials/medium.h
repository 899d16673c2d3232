// A homogeneous participating medium with a Henyey-Greenstein phase function.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "dermis/core/rgb.h"

namespace dermis {

struct HomogeneousMedium {
  RGB sigma_a, sigma_s, sigma_t;  // per scene unit, scale applied
  float g = 0;
  // The free flight's channel is chosen in proportion to throughput x this
  // (free_flight.h): (sigma_a / sigma_t)^-1/2, the random walk's rule
  // (sss::MixtureWalkStep::channel_probabilities: a channel's variance taken as its mean
  // number of collisions, 1 / (1 - albedo), and the channels allocated as their square
  // roots). A channel without absorption is preferred as one of 1 - albedo = 1e-6.
  RGB channel_preference = RGB(1);

  static HomogeneousMedium from_coefficients(RGB sigma_a, RGB sigma_s, float scale, float g) {
    HomogeneousMedium m;
    m.sigma_a = sigma_a * scale;
    m.sigma_s = sigma_s * scale;
    m.sigma_t = m.sigma_a + m.sigma_s;
    m.g = g;
    for (int c = 0; c < 3; ++c)
      if (m.sigma_t[c] > 0) m.channel_preference[c] = 1 / std::sqrt(std::max(m.sigma_a[c] / m.sigma_t[c], 1e-6f));
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
