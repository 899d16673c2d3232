// A piecewise cubic Hermite interpolant (Fritsch & Carlson 1980, eq. 2) and where a
// non-increasing one crosses a level: the albedo inversion's A(t) (albedo_inversion.h),
// one table's or two tables' blend.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace dermis::sss {

// A node: its abscissa, value and slope.
struct HermiteNode {
  double t, y, m;
};

// The cubic between nodes a and b at t (a.t <= t <= b.t); its derivative in *dydt.
inline double hermite_between(const HermiteNode& a, const HermiteNode& b, double t, double* dydt = nullptr) {
  const double h = b.t - a.t, s = (t - a.t) / h;
  // The cubic Hermite basis (Fritsch & Carlson 1980, eq. 2).
  const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
  const double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
  if (dydt) {  // d/dt of the basis, times h (in s)
    const double d00 = 6 * s * (s - 1), d10 = (1 - s) * (1 - 3 * s), d11 = s * (3 * s - 2);
    *dydt = (d00 * (a.y - b.y)) / h + d10 * a.m + d11 * b.m;
  }
  return h00 * a.y + h10 * h * a.m + h01 * b.y + h11 * h * b.m;
}

// For a non-increasing interpolant on n >= 2 nodes (node(k) gives node k, in increasing
// t): t* = sup{t : A(t) > level}, the first node's t where A never exceeds the level and
// the last's where it always does. On a flat part at the level, the end with the least t.
// The node interval by bisection on the node values, then Newton on its cubic, bracketed
// (a step leaving the bracket bisects instead: Press et al., Numerical Recipes, 3rd ed.,
// sec. 9.4), to a few ulps of max(|t|, 1): where the cubic meets the level with slope 0 (the
// edge of a flat part) that pins t* only to about 1e-8.
// steps (if given): the Newton or bisection steps taken.
template <class NodeAt>
double crossing_of_non_increasing(int n, NodeAt&& node, double level, int* steps = nullptr) {
  if (steps) *steps = 0;
  const HermiteNode first = node(0), last = node(n - 1);
  if (!(first.y > level)) return first.t;
  if (last.y > level) return last.t;
  int lo_node = 0, hi_node = n - 1;  // A(t_lo) > level >= A(t_hi)
  while (hi_node - lo_node > 1) {
    const int mid = (lo_node + hi_node) / 2;
    (node(mid).y > level ? lo_node : hi_node) = mid;
  }
  const HermiteNode a = node(lo_node), b = node(lo_node + 1);
  double lo = a.t, hi = b.t;
  double t = a.y > b.y ? lo + (hi - lo) * (a.y - level) / (a.y - b.y) : lo;  // the chord's crossing
  // Converged when a step or the bracket is a few ulps of the scale max(|t|, 1) (1e-16
  // would be under one ulp near t = 1, where Newton then alternates between neighbours;
  // a tolerance relative to t, under the rounding of A near t = 0).
  const double tolerance = 4 * std::numeric_limits<double>::epsilon() * std::max({1.0, std::abs(lo), std::abs(hi)});
  for (int i = 0; i < 100 && hi - lo > tolerance; ++i) {
    if (steps) ++*steps;
    double slope;
    const double f = hermite_between(a, b, t, &slope) - level;
    (f > 0 ? lo : hi) = t;
    if (slope < 0) {
      const double newton = t - f / slope;
      // Converged: a Newton step of a few ulps (it may round onto the bracket's end that
      // t has just become).
      if (std::abs(newton - t) <= tolerance) break;
      if (newton > lo && newton < hi) {
        t = newton;
        continue;
      }
    }
    t = 0.5 * (lo + hi);  // a step that leaves the bracket, or no slope: bisection
  }
  return std::clamp(t, lo, hi);
}

}  // namespace dermis::sss
