// Geometry and quadrature for the probe-sampler tests (included by *_test.cpp only):
// analytic crossings of a segment with a plane and a sphere, planes in polar
// coordinates, nested adaptive Gauss-Kronrod in 2D, and a sample-mean with its error.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "dermis/core/vec.h"
#include "dermis/sss/probe/probe_types.h"
#include "dermis/sss/profiles/quadrature.h"

namespace dermis::sss::testing {

// The plane through `origin` with unit normal `normal`; e1, e2 span it.
struct TestPlane {
  Vec3d origin, normal, e1, e2;
  TestPlane(Vec3d o, Vec3d n) : origin(o), normal(normalize(n)) {
    const Framed f(normal);
    e1 = f.s;
    e2 = f.t;
  }
  Vec3d point(double s, double psi) const { return origin + (e1 * std::cos(psi) + e2 * std::sin(psi)) * s; }
  // Polar coordinates (s, psi in [0, 2 pi)) of a point on the plane.
  void polar(Vec3d x, double* s, double* psi) const {
    const Vec3d o = x - origin;
    const double a = dot(o, e1), b = dot(o, e2);
    *s = std::sqrt(a * a + b * b);
    *psi = std::atan2(b, a);
    if (*psi < 0) *psi += 2 * kPiD;
  }
};

// Crossing of a segment with a plane: returns false if none (parallel or outside [0, length]).
inline bool intersect(const ProbeSegment& seg, const TestPlane& plane, Vec3d* hit) {
  const double denom = dot(seg.direction, plane.normal);
  if (denom == 0) return false;
  const double t = dot(plane.origin - seg.origin, plane.normal) / denom;
  if (!(t >= 0 && t <= seg.length)) return false;
  *hit = seg.origin + seg.direction * t;
  return true;
}

// Crossings of a segment with the sphere |x - centre| = radius (0, 1 or 2), in order.
inline int intersect_sphere(const ProbeSegment& seg, Vec3d centre, double radius, Vec3d hits[2]) {
  const Vec3d o = seg.origin - centre;
  const double b = dot(o, seg.direction), c = dot(o, o) - radius * radius;
  const double disc = b * b - c;
  if (disc <= 0) return 0;
  const double root = std::sqrt(disc);
  int n = 0;
  for (double t : {-b - root, -b + root})
    if (t >= 0 && t <= seg.length) hits[n++] = seg.origin + seg.direction * t;
  return n;
}

// Adaptive Gauss-Kronrod with the recursion capped at 2^16 pieces, so that a wrong
// sampler (an integrand that never meets the tolerance) fails instead of hanging.
template <class F>
double integrate_capped(const F& f, double a, double b, double tol) {
  return detail::adaptive_gk(f, a, b, tol, 16);
}

// Adaptive Gauss-Kronrod over [a, b] split at the given breakpoints (those inside).
template <class F>
double integrate_pieces(const F& f, double a, double b, std::vector<double> breaks, double tol) {
  breaks.push_back(a);
  breaks.push_back(b);
  std::sort(breaks.begin(), breaks.end());
  double sum = 0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double lo = std::max(a, breaks[i]), hi = std::min(b, breaks[i + 1]);
    if (hi > lo) sum += integrate_capped(f, lo, hi, tol);
  }
  return sum;
}

// int over psi in [psi0, psi1], s in [s0, s1] of f(plane.point(s, psi)) s ds dpsi, the
// s-integral split at `s_breaks` (where the integrand jumps).
template <class F>
double integrate_plane_polar(const TestPlane& plane, const F& f, double s0, double s1, double psi0, double psi1,
                             const std::vector<double>& s_breaks, double tol) {
  auto inner = [&](double psi) {
    return integrate_pieces([&](double s) { return f(plane.point(s, psi)) * s; }, s0, s1, s_breaks,
                            tol / (psi1 - psi0));
  };
  return integrate_capped(inner, psi0, psi1, tol);
}

// Mean of a sample and the standard error of that mean.
struct MeanAndError {
  double sum = 0, sum2 = 0;
  long n = 0;
  void add(double x) {
    sum += x;
    sum2 += x * x;
    ++n;
  }
  double mean() const { return sum / n; }
  double error() const {
    const double m = mean();
    return std::sqrt(std::max(0.0, sum2 / n - m * m) / (n - 1));
  }
};

}  // namespace dermis::sss::testing
