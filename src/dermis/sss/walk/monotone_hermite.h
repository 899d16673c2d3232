// A piecewise cubic Hermite interpolant (Fritsch & Carlson 1980, eq. 2) and where a
// non-increasing one crosses a level: the albedo inversion's A(t) (albedo_inversion.h),
// one table's or two tables' blend.
#pragma once

#include <algorithm>
#include <cmath>

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
// sec. 9.4), to double precision: where the cubic meets the level with slope 0 (the
// edge of a flat part) that pins t* only to about 1e-8.
template <class NodeAt>
double crossing_of_non_increasing(int n, NodeAt&& node, double level) {
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
  for (int i = 0; i < 100 && hi - lo > 1e-16; ++i) {
    double slope;
    const double f = hermite_between(a, b, t, &slope) - level;
    (f > 0 ? lo : hi) = t;
    const double newton = slope < 0 ? t - f / slope : lo - 1;
    const double next = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
    if (std::abs(next - t) <= 1e-16) break;
    t = next;
  }
  return std::clamp(t, lo, hi);
}

}  // namespace dermis::sss
