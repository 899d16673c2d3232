// Gauss-Legendre quadrature nodes and weights on an interval, computed by Newton's
// method on the Legendre polynomial P_n (Abramowitz & Stegun 1964, 25.4.29).
#pragma once

#include <vector>

namespace dermis {

struct QuadratureRule {
  std::vector<double> nodes;    // ascending
  std::vector<double> weights;  // positive, summing to the interval length
};

// n-point rule on [a, b]: exact for polynomials of degree <= 2n - 1. Throws
// std::invalid_argument for n < 1 or an empty interval.
QuadratureRule gauss_legendre(int n, double a = -1.0, double b = 1.0);

}  // namespace dermis
