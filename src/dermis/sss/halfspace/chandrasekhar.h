// Chandrasekhar's H-function for isotropic scattering and the exact total albedo of
// an index-matched, semi-infinite, isotropically scattering medium
// (Chandrasekhar, Radiative Transfer, 1950, ch. V): the independent reference for the
// half-space simulator.
#pragma once

#include <vector>

namespace dermis::sss {

// How the discretised H-equation is solved.
enum class HSolver {
  // H(mu) = 1 + (alpha/2) mu H(mu) int_0^1 H(mu') / (mu + mu') dmu'   (Chandrasekhar 1950, ch. V, the H-equation with
  // characteristic function Psi = alpha/2)
  Original,
  // 1/H(mu) = sqrt(1 - alpha) + (alpha/2) int_0^1 mu' H(mu') / (mu + mu') dmu'
  // (Chandrasekhar 1950, ch. V, the equivalent form from the zeroth-moment identity
  // int_0^1 H = (2/alpha)(1 - sqrt(1 - alpha))), iterated as a fixed point.
  Reciprocal,
  // Newton's method on the reciprocal form's residual. Both fixed-point iterations
  // slow down without bound as alpha -> 1 (the conservative case converges only
  // algebraically); Newton takes tens of steps for every alpha, including 1.
  Newton,
};

// H solved on Gauss-Legendre nodes of [0, 1], evaluated anywhere by Nystrom
// interpolation (the equation's right-hand side with the node values). The fixed-
// point iterations stop when no node changes by more than `tolerance`; Newton stops
// when the residual is below it. Throws std::runtime_error when not converged.
class HFunction {
 public:
  // Throws std::invalid_argument for alpha outside [0, 1] or nodes < 2.
  explicit HFunction(double alpha, int nodes = 128, HSolver solver = HSolver::Newton, double tolerance = 1e-14,
                     int max_iterations = 100000);

  double operator()(double mu) const;  // mu in [0, 1]
  double alpha() const { return alpha_; }
  int iterations() const { return iterations_; }  // iterations (fixed-point or Newton) used
  // Moments int_0^1 H(mu) mu^k dmu by the same quadrature.
  double moment(int k) const;
  const std::vector<double>& nodes() const { return nodes_; }
  const std::vector<double>& values() const { return h_; }

 private:
  double alpha_;
  HSolver solver_;
  std::vector<double> nodes_, weights_, h_;
  int iterations_ = 0;
};

// Total diffuse reflectance of the index-matched isotropic half-space with single-
// scattering albedo alpha, for collimated incidence at direction cosine mu0:
// R(mu0) = 1 - H(mu0) sqrt(1 - alpha)  (Chandrasekhar 1950, ch. V; METHODS.md section 6).
double halfspace_albedo_collimated(const HFunction& h, double mu0);
// The same under diffuse (cosine-weighted) incidence:
// R = 2 int_0^1 R(mu) mu dmu = 1 - 2 sqrt(1 - alpha) int_0^1 H(mu) mu dmu  (METHODS.md section 6).
double halfspace_albedo_diffuse(const HFunction& h);

}  // namespace dermis::sss
