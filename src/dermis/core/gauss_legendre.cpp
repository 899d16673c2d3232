#include "dermis/core/gauss_legendre.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "dermis/core/vec.h"

namespace dermis {

namespace {

// P_n(x) and P_n'(x) by the three-term recurrence
// (k+1) P_{k+1} = (2k+1) x P_k - k P_{k-1} (Abramowitz & Stegun 22.7.10),
// P_n'(x) = n (x P_n - P_{n-1}) / (x^2 - 1) (A&S 22.8.5).
void legendre(int n, double x, double& p, double& dp) {
  double p_prev = 1.0, p_cur = x;
  for (int k = 1; k < n; ++k) {
    double p_next = ((2 * k + 1) * x * p_cur - k * p_prev) / (k + 1);
    p_prev = p_cur;
    p_cur = p_next;
  }
  p = n == 0 ? 1.0 : p_cur;
  dp = n * (x * p_cur - p_prev) / (x * x - 1);
}

}  // namespace

QuadratureRule gauss_legendre(int n, double a, double b) {
  if (n < 1) throw std::invalid_argument("gauss_legendre: need at least 1 node, got " + std::to_string(n));
  if (!(b > a)) throw std::invalid_argument("gauss_legendre: interval [a, b] must have b > a");
  QuadratureRule rule;
  rule.nodes.resize(n);
  rule.weights.resize(n);
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    // Initial guess for the i-th largest root (A&S 22.16.6, Tricomi's leading term).
    double x = std::cos(kPiD * (i + 0.75) / (n + 0.5));
    double p = 0, dp = 1;
    for (int iter = 0; iter < 100; ++iter) {
      legendre(n, x, p, dp);
      double dx = p / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    legendre(n, x, p, dp);
    double w = 2.0 / ((1 - x * x) * dp * dp);  // A&S 25.4.29
    // Roots are symmetric: -x and x share the weight.
    rule.nodes[i] = mid - half * x;
    rule.nodes[n - 1 - i] = mid + half * x;
    rule.weights[i] = rule.weights[n - 1 - i] = half * w;
  }
  return rule;
}

}  // namespace dermis
