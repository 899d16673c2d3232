// Numerical quadrature for building profile tables and for the tests that check
// profiles against their albedo: fixed 16-point Gauss-Legendre on an interval and
// adaptive Gauss-Kronrod (7/15 points) with a tolerance (Press et al., Numerical
// Recipes 3rd ed., sections 4.6 and 4.7).
#pragma once

#include <cmath>
#include <stdexcept>

namespace dermis::sss {

// 16-point Gauss-Legendre rule on [a, b]: exact for polynomials of degree 31.
template <class F>
double gauss_legendre_16(const F& f, double a, double b) {
  // Abscissae and weights on [-1, 1] (positive half; Abramowitz & Stegun, table 25.4).
  static constexpr double x[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                                  0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
  static constexpr double w[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
                                  0.1246289712555339, 0.0951585116824928, 0.0622535239386479, 0.0271524594117541};
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  double sum = 0;
  for (int i = 0; i < 8; ++i) sum += w[i] * (f(mid - half * x[i]) + f(mid + half * x[i]));
  return sum * half;
}

namespace detail {
// One Gauss-Kronrod 7/15 step: returns the K15 estimate, *error = |K15 - G7|.
template <class F>
double gauss_kronrod_15(const F& f, double a, double b, double* error) {
  static constexpr double xk[8] = {
      0.991455371120812639, 0.949107912342758525, 0.864864423359769073, 0.741531185599394440,
      0.586087235467691130, 0.405845151377397167, 0.207784955007898468, 0.0};
  static constexpr double wk[8] = {0.022935322010529225, 0.063092092629978553, 0.104790010322250184,
                                   0.140653259715525919, 0.169004726639267903, 0.190350578064785410,
                                   0.204432940075298892, 0.209482141084727828};
  static constexpr double wg[4] = {0.129484966168869693, 0.279705391489276668, 0.381830050505118945,
                                   0.417959183673469388};  // at xk[1], xk[3], xk[5], xk[7]
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  const double fc = f(mid);
  double k15 = wk[7] * fc, g7 = wg[3] * fc;
  for (int i = 0; i < 7; ++i) {
    const double s = f(mid - half * xk[i]) + f(mid + half * xk[i]);
    k15 += wk[i] * s;
    if (i % 2 == 1) g7 += wg[i / 2] * s;
  }
  *error = std::abs((k15 - g7) * half);
  return k15 * half;
}

template <class F>
double adaptive_gk(const F& f, double a, double b, double abs_tol, int depth) {
  double err;
  const double v = gauss_kronrod_15(f, a, b, &err);
  if (err <= abs_tol || depth <= 0) return v;
  const double m = 0.5 * (a + b);
  return adaptive_gk(f, a, m, 0.5 * abs_tol, depth - 1) + adaptive_gk(f, m, b, 0.5 * abs_tol, depth - 1);
}
}  // namespace detail

// Adaptive Gauss-Kronrod on [a, b] to an absolute tolerance.
template <class F>
double integrate(const F& f, double a, double b, double abs_tol = 1e-12) {
  if (!(b >= a)) throw std::invalid_argument("integrate: the interval must satisfy a <= b");
  return detail::adaptive_gk(f, a, b, abs_tol, 40);
}

// Integral over [0, inf) of f, split at 0, s, 2s, 4s, ... (geometric pieces of a
// natural length scale s) until a piece contributes less than abs_tol.
template <class F>
double integrate_to_infinity(const F& f, double s, double abs_tol = 1e-12) {
  double total = integrate(f, 0.0, s, abs_tol);
  for (double a = s; a < 1e300; a *= 2) {
    const double piece = integrate(f, a, 2 * a, abs_tol);
    total += piece;
    if (std::abs(piece) < abs_tol && a > 64 * s) break;
  }
  return total;
}

}  // namespace dermis::sss
