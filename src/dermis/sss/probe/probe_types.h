// Value types shared by the probe samplers (METHODS 2; docs/probe-sampling.md): the
// shading point with its frame, and the probe segment the renderer traces.
#pragma once

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dermis/core/frame.h"
#include "dermis/core/rgb.h"
#include "dermis/core/vec.h"

namespace dermis::sss {

// Shading point P with an orthonormal frame (N, T, B). Double precision: the renderer
// converts its float geometry (Vec3d(v)) once per shading point.
struct ProbeFrame {
  Vec3d p;
  Vec3d n{0, 0, 1}, t{1, 0, 0}, b{0, 1, 0};

  ProbeFrame() = default;
  ProbeFrame(Vec3d point, Vec3d normal, Vec3d tangent, Vec3d bitangent)
      : p(point), n(normal), t(tangent), b(bitangent) {}
  // Any tangent frame around `normal` (unit length) (Duff et al. 2017).
  static ProbeFrame around(Vec3d point, Vec3d normal) {
    const Framed f(normal);
    return {point, f.n, f.s, f.t};
  }
  // Axis 0 = N, 1 = T, 2 = B.
  Vec3d axis(int a) const { return a == 0 ? n : (a == 1 ? t : b); }
};

// A probe segment: the points origin + s * direction, s in [0, length]; direction is
// unit length. The renderer reports every surface crossing on it.
struct ProbeSegment {
  Vec3d origin;
  Vec3d direction{0, 0, 1};
  double length = 0;
  Vec3d end() const { return origin + direction * length; }
};

// Uniform direction on the unit sphere from u in [0,1)^2 (Archimedes' hat-box theorem:
// z uniform in [-1, 1]).
inline Vec3d uniform_sphere_direction(double u0, double u1) {
  const double z = 1 - 2 * u0;
  const double s = std::sqrt(std::max(0.0, 1 - z * z));
  const double phi = 2 * kPiD * u1;
  return {s * std::cos(phi), s * std::sin(phi), z};
}

// Channel weights normalised to probabilities; throws unless they are finite, >= 0 and
// not all zero.
inline std::array<double, 3> normalised_channel_weights(RGB w, const char* who) {
  double sum = 0;
  for (int c = 0; c < 3; ++c) {
    if (!(w[c] >= 0) || !std::isfinite(w[c]))
      throw std::invalid_argument(std::string(who) + ": channel weights must be finite and >= 0 (channel " +
                                  std::to_string(c) + " is " + std::to_string(w[c]) + ")");
    sum += w[c];
  }
  if (!(sum > 0))
    throw std::invalid_argument(std::string(who) +
                                ": all channel weights are zero; pass e.g. throughput x albedo, or RGB(1)");
  return {w[0] / sum, w[1] / sum, w[2] / sum};
}

}  // namespace dermis::sss
