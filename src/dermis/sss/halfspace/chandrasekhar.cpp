#include "dermis/sss/halfspace/chandrasekhar.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "dermis/core/gauss_legendre.h"

namespace dermis::sss {

namespace {

// The quadrature sum S(mu) = sum_j w_j f_j H_j / (mu + mu_j), with f_j = 1 for the
// original form and f_j = mu_j for the reciprocal form.
double kernel_sum(double mu, const std::vector<double>& nodes, const std::vector<double>& weights,
                  const std::vector<double>& h, bool original_form) {
  double sum = 0;
  for (size_t j = 0; j < nodes.size(); ++j) {
    double f = original_form ? 1.0 : nodes[j];
    sum += weights[j] * f * h[j] / (mu + nodes[j]);
  }
  return sum;
}

// The equation's right-hand side solved for H(mu) (the Nystrom formula).
double h_from_sum(double mu, double alpha, double sum, bool original_form) {
  if (original_form) return 1.0 / (1.0 - 0.5 * alpha * mu * sum);  // Chandrasekhar 1950, ch. V (H-equation)
  return 1.0 / (std::sqrt(1.0 - alpha) + 0.5 * alpha * sum);       // Chandrasekhar 1950, ch. V (reciprocal form)
}

// Solves the dense system a x = b in place (Gaussian elimination, partial pivoting).
void solve_linear(std::vector<double>& a, std::vector<double>& b, size_t n) {
  for (size_t col = 0; col < n; ++col) {
    size_t pivot = col;
    for (size_t r = col + 1; r < n; ++r)
      if (std::abs(a[r * n + col]) > std::abs(a[pivot * n + col])) pivot = r;
    if (a[pivot * n + col] == 0.0) throw std::runtime_error("HFunction: singular Newton system");
    if (pivot != col) {
      for (size_t c = 0; c < n; ++c) std::swap(a[col * n + c], a[pivot * n + c]);
      std::swap(b[col], b[pivot]);
    }
    for (size_t r = col + 1; r < n; ++r) {
      double factor = a[r * n + col] / a[col * n + col];
      if (factor == 0.0) continue;
      for (size_t c = col; c < n; ++c) a[r * n + c] -= factor * a[col * n + c];
      b[r] -= factor * b[col];
    }
  }
  for (size_t row = n; row-- > 0;) {
    double sum = b[row];
    for (size_t c = row + 1; c < n; ++c) sum -= a[row * n + c] * b[c];
    b[row] = sum / a[row * n + row];
  }
}

}  // namespace

HFunction::HFunction(double alpha, int nodes, HSolver solver, double tolerance, int max_iterations)
    : alpha_(alpha), solver_(solver) {
  if (!(alpha >= 0.0 && alpha <= 1.0))
    throw std::invalid_argument("HFunction: single-scattering albedo must be in [0, 1], got " + std::to_string(alpha));
  if (nodes < 2) throw std::invalid_argument("HFunction: need at least 2 quadrature nodes");
  QuadratureRule rule = gauss_legendre(nodes, 0.0, 1.0);
  nodes_ = std::move(rule.nodes);
  weights_ = std::move(rule.weights);
  const size_t n = nodes_.size();
  h_.assign(n, 1.0);
  const bool original = solver_ == HSolver::Original;

  if (solver_ != HSolver::Newton) {
    std::vector<double> next(n);
    for (iterations_ = 1; iterations_ <= max_iterations; ++iterations_) {
      double change = 0;
      for (size_t i = 0; i < n; ++i) {
        next[i] = h_from_sum(nodes_[i], alpha_, kernel_sum(nodes_[i], nodes_, weights_, h_, original), original);
        change = std::max(change, std::abs(next[i] - h_[i]));
      }
      h_.swap(next);
      if (change <= tolerance) return;
    }
  } else {
    // Residual of the reciprocal form: F_i = H_i (sqrt(1 - alpha) + (alpha/2) S_i) - 1,
    // S_i = sum_k w_k mu_k H_k / (mu_i + mu_k); Jacobian
    // dF_i/dH_k = delta_ik (sqrt(1 - alpha) + (alpha/2) S_i) + H_i (alpha/2) w_k mu_k / (mu_i + mu_k).
    const double root = std::sqrt(1.0 - alpha_);
    std::vector<double> jacobian(n * n), step(n);
    for (iterations_ = 1; iterations_ <= max_iterations; ++iterations_) {
      double residual = 0;
      for (size_t i = 0; i < n; ++i) {
        double bracket = root + 0.5 * alpha_ * kernel_sum(nodes_[i], nodes_, weights_, h_, false);
        step[i] = -(h_[i] * bracket - 1.0);
        residual = std::max(residual, std::abs(step[i]));
        for (size_t k = 0; k < n; ++k)
          jacobian[i * n + k] = h_[i] * 0.5 * alpha_ * weights_[k] * nodes_[k] / (nodes_[i] + nodes_[k]);
        jacobian[i * n + i] += bracket;
      }
      if (residual <= tolerance) return;
      solve_linear(jacobian, step, n);
      for (size_t i = 0; i < n; ++i) h_[i] += step[i];
    }
  }
  throw std::runtime_error("HFunction: the iteration did not converge in " + std::to_string(max_iterations) +
                           " iterations (alpha = " + std::to_string(alpha) + ")");
}

double HFunction::operator()(double mu) const {
  const bool original = solver_ == HSolver::Original;
  return h_from_sum(mu, alpha_, kernel_sum(mu, nodes_, weights_, h_, original), original);
}

double HFunction::moment(int k) const {
  double sum = 0;
  for (size_t j = 0; j < nodes_.size(); ++j) sum += weights_[j] * std::pow(nodes_[j], k) * h_[j];
  return sum;
}

double halfspace_albedo_collimated(const HFunction& h, double mu0) {
  return 1.0 - h(mu0) * std::sqrt(1.0 - h.alpha());  // Chandrasekhar 1950, ch. V; METHODS.md section 6
}

double halfspace_albedo_diffuse(const HFunction& h) {
  return 1.0 - 2.0 * std::sqrt(1.0 - h.alpha()) * h.moment(1);  // METHODS.md section 6
}

}  // namespace dermis::sss
