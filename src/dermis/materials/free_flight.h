// Free-flight sampling in a homogeneous chromatic medium (METHODS.md sec. 5): the
// channel that drives the distance is chosen in proportion to the path throughput and
// the distance from that channel's exponential; the weight is the one-sample balance
// heuristic over the channels (spectral MIS), so every channel stays unbiased.
#pragma once

#include <cmath>
#include <limits>

#include "dermis/core/rgb.h"
#include "dermis/materials/medium.h"

namespace dermis {

struct FreeFlight {
  bool valid = false;      // false: nothing carries on (zero throughput or zero pdf)
  bool scattered = false;  // a scattering event at distance t before t_max
  float t = 0;
  RGB weight;              // multiplies the throughput: sigma_s T(t) / pdf, or T(t_max) / P(pass)
};

// beta: the path throughput (chooses the channel); t_max: distance to the next surface
// (infinity allowed); u_channel, u_distance uniform in [0, 1).
inline FreeFlight sample_free_flight(const HomogeneousMedium& m, const RGB& beta, float t_max, float u_channel,
                                     float u_distance) {
  FreeFlight f;
  float q[3], qsum = 0;
  for (int c = 0; c < 3; ++c) qsum += q[c] = std::abs(beta[c]);
  if (!(qsum > 0)) return f;
  for (float& v : q) v /= qsum;
  const int c = u_channel < q[0] ? 0 : (u_channel < q[0] + q[1] ? 1 : 2);
  const float st = m.sigma_t[c];
  const float t = st > 0 ? -std::log1p(-u_distance) / st : std::numeric_limits<float>::infinity();
  if (t < t_max) {
    // p(t) = sum_k q_k sigma_t,k T_k(t) (balance heuristic over channels, Veach 1997 eq. 9.10).
    const RGB tr = m.transmittance(t);
    float pdf = 0;
    for (int k = 0; k < 3; ++k) pdf += q[k] * m.sigma_t[k] * tr[k];
    f.valid = pdf > 0;
    f.scattered = true;
    f.t = t;
    f.weight = m.sigma_s * tr / pdf;
    return f;
  }
  // Passed through: P = sum_k q_k T_k(t_max).
  const RGB tr = m.transmittance(t_max);
  float pdf = 0;
  for (int k = 0; k < 3; ++k) pdf += q[k] * tr[k];
  f.valid = pdf > 0;
  f.t = t_max;
  f.weight = tr / pdf;
  return f;
}

}  // namespace dermis
