// Free-flight sampling in a homogeneous chromatic medium (METHODS.md sec. 5): the
// channel that drives the distance is chosen in proportion to the path throughput times
// the medium's channel preference (HomogeneousMedium::channel_preference: channels of
// little absorption, whose long paths hold most of the variance, more often) and the
// distance from that channel's exponential; the weight is the one-sample balance
// heuristic over the channels (spectral MIS), so every channel stays unbiased for any
// choice probabilities.
#pragma once

#include <cmath>
#include <limits>

#include "dermis/core/rgb.h"
#include "dermis/materials/medium.h"

namespace dermis {

// -ln(1 - u) for u in [0, 1): the exponential's inverse CDF at unit rate, in double, where
// 1 - u is exact for any float u >= 2^-29 (within 2^-54 below). glibc's double log is
// much faster than its log1pf, and a medium's segment draws two of these (free flight,
// next-event point).
inline float exponential_quantile(float u) { return float(-std::log(1.0 - double(u))); }

// The attenuation over a whole segment [0, t_max), computed once for the segment's free
// flight and its next-event point (below): T_c(t_max) and 1 - T_c(t_max) per channel.
struct MediumSegment {
  float t_max = 0;
  RGB transmittance;  // T(t_max): 0 in every attenuating channel for t_max = infinity
  RGB captured;       // 1 - T(t_max): the probability that a channel's free flight ends on it
};

inline MediumSegment medium_segment(const HomogeneousMedium& m, float t_max) {
  MediumSegment s;
  s.t_max = t_max;
  s.transmittance = m.transmittance(t_max);
  for (int c = 0; c < 3; ++c) {
    const float optical = m.sigma_t[c] * t_max;
    // 1 - e^-x loses digits below x = 1/16 (relative error up to 2^-24 e^-x / x): expm1 there.
    s.captured[c] = std::isinf(t_max) ? 1.0f : optical < 0.0625f ? -std::expm1(-optical) : 1 - s.transmittance[c];
  }
  return s;
}

struct FreeFlight {
  bool valid = false;      // false: nothing carries on (zero throughput or zero pdf)
  bool scattered = false;  // a scattering event at distance t before t_max
  float t = 0;
  RGB weight;  // multiplies the throughput: sigma_s T(t) / pdf, or T(t_max) / P(pass)
};

// beta: the path throughput (chooses the channel, with m.channel_preference); t_max: distance to the next surface
// (infinity allowed); u_channel, u_distance uniform in [0, 1).
inline FreeFlight sample_free_flight(const HomogeneousMedium& m, const MediumSegment& segment, const RGB& beta,
                                     float u_channel, float u_distance) {
  const float t_max = segment.t_max;
  FreeFlight f;
  float q[3], qsum = 0;
  for (int c = 0; c < 3; ++c) qsum += q[c] = std::abs(beta[c]) * m.channel_preference[c];
  if (!(qsum > 0)) return f;
  for (float& v : q) v /= qsum;
  const int c = u_channel < q[0] ? 0 : (u_channel < q[0] + q[1] ? 1 : 2);
  const float st = m.sigma_t[c];
  const float t = st > 0 ? exponential_quantile(u_distance) / st : std::numeric_limits<float>::infinity();
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
  const RGB& tr = segment.transmittance;
  float pdf = 0;
  for (int k = 0; k < 3; ++k) pdf += q[k] * tr[k];
  f.valid = pdf > 0;
  f.t = t_max;
  f.weight = tr / pdf;
  return f;
}

inline FreeFlight sample_free_flight(const HomogeneousMedium& m, const RGB& beta, float t_max, float u_channel,
                                     float u_distance) {
  return sample_free_flight(m, medium_segment(m, t_max), beta, u_channel, u_distance);
}

// A point of the segment [0, t_max) for next-event estimation, drawn whatever the free
// flight does (decoupled direct lighting: the path gathers direct light on every segment it
// crosses, also on those it passes through without scattering).
struct SegmentPoint {
  bool valid = false;  // false: no channel scatters on this segment
  float t = 0;
  RGB weight;  // sigma_s T(t) / p(t): multiplies the in-scattered radiance at t
};

// The distance is drawn from the channel's exponential truncated to the segment, the channel
// in proportion to |beta| among the channels that scatter; the weight is the one-sample balance
// heuristic over the channels (Veach 1997 eq. 9.10), so the estimate of
// int_0^t_max sigma_s T(t) L(t) dt stays unbiased in every channel.
inline SegmentPoint sample_segment_point(const HomogeneousMedium& m, const MediumSegment& segment, const RGB& beta,
                                         float u_channel, float u_distance) {
  const float t_max = segment.t_max;
  const RGB& captured = segment.captured;
  SegmentPoint sp;
  if (!(t_max > 0)) return sp;
  float q[3], qsum = 0;
  for (int c = 0; c < 3; ++c) {
    const bool scatters = m.sigma_s[c] > 0 && m.sigma_t[c] > 0;
    qsum += q[c] = scatters ? std::abs(beta[c]) : 0.0f;
  }
  if (!(qsum > 0)) return sp;
  for (float& v : q) v /= qsum;
  int c = 0;  // the first channel whose cumulative share exceeds u (the last one that scatters, at worst)
  for (float cdf = 0; int k : {0, 1, 2}) {
    if (q[k] == 0) continue;
    c = k;
    if (u_channel < (cdf += q[k])) break;
  }
  // Inversion of the truncated exponential: t = -ln(1 - u (1 - T_c(t_max))) / sigma_t,c.
  const float t = std::min(exponential_quantile(u_distance * captured[c]) / m.sigma_t[c], std::nextafter(t_max, 0.0f));
  // p(t) = sum_k q_k sigma_t,k T_k(t) / (1 - T_k(t_max)).
  const RGB tr = m.transmittance(t);
  float pdf = 0;
  for (int k = 0; k < 3; ++k)
    if (q[k] > 0) pdf += q[k] * m.sigma_t[k] * tr[k] / captured[k];
  if (!(pdf > 0) || !std::isfinite(pdf)) return sp;
  sp.valid = true;
  sp.t = t;
  sp.weight = m.sigma_s * tr / pdf;
  return sp;
}

inline SegmentPoint sample_segment_point(const HomogeneousMedium& m, const RGB& beta, float t_max, float u_channel,
                                         float u_distance) {
  return sample_segment_point(m, medium_segment(m, t_max), beta, u_channel, u_distance);
}

}  // namespace dermis
