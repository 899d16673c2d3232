#include "dermis/sss/walk/dwivedi.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace dermis::sss {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Safeguarded Newton for an increasing function f on [lo, hi] with f(lo) < 0 < f(hi):
// a Newton step that leaves the bracket is replaced by bisection (Press et al.,
// Numerical Recipes, 3rd ed., section 9.4, rtsafe).
template <class F>
double safeguarded_newton(F&& f_and_derivative, double lo, double hi, double x) {
  for (int i = 0; i < 200; ++i) {
    double f, df;
    f_and_derivative(x, f, df);
    if (f == 0) return x;
    (f < 0 ? lo : hi) = x;
    double next = x - f / df;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const double step = std::abs(next - x);
    x = next;
    if (step <= 4 * std::numeric_limits<double>::epsilon() * std::abs(x) || hi - lo <= 1e-300) return x;
  }
  return x;
}

// G(x) = atanh(x)/x - 1 = sum_{k>=1} x^{2k}/(2k+1) and G'(x) (Taylor series of atanh,
// Abramowitz & Stegun 4.6.33), summed below x = 1/2 where the closed form cancels.
void atanh_ratio_minus_one(double x, double& g, double& dg) {
  if (x < 0.5) {
    const double x2 = x * x;
    double power = x2;  // x^{2k}
    g = 0, dg = 0;
    for (int k = 1; k < 200; ++k) {
      const double term = power / (2 * k + 1);
      g += term;
      dg += 2 * k * term / x;
      if (term < 1e-18 * g) break;
      power *= x2;
    }
    if (x == 0) dg = 0;
    return;
  }
  const double a = std::atanh(x);
  g = a / x - 1;
  dg = (x / (1 - x * x) - a) / (x * x);
}

}  // namespace

DwivediEigenvalue dwivedi_eigenvalue(double alpha) {
  if (!(alpha > 0 && alpha <= 1))
    throw std::invalid_argument("Dwivedi eigenvalue: single-scattering albedo must be in (0, 1], got " +
                                std::to_string(alpha));
  DwivediEigenvalue e;
  if (alpha == 1) {  // no absorption: nu0 = infinity, the guided pdfs are the classical ones
    e.nu0 = kInf, e.inv_nu0 = 0, e.log_nu0_minus_one = kInf;
    e.one_minus_inv_nu0 = 1, e.log_one_minus_inv_nu0 = 0;
    return e;
  }
  if (alpha < 0.5) {
    // nu0 = 1 + eps, eps < 0.045. With y = ln eps the equation (Krivanek & d'Eon 2014)
    // 1 = alpha nu0 atanh(1/nu0) = alpha (1 + eps) ln((2 + eps)/eps) / 2 becomes
    // F(y) = y - ln(2 + e^y) + 2 / (alpha (1 + e^y)) = 0, increasing on the bracket
    // [ln 2 - 2/alpha - 1, ln 0.05], with the eps -> 0 root ln 2 - 2/alpha as start.
    auto f = [alpha](double y, double& value, double& derivative) {
      const double eps = std::exp(y);
      value = y - std::log(2 + eps) + 2 / (alpha * (1 + eps));
      derivative = 1 - eps / (2 + eps) - 2 * eps / (alpha * (1 + eps) * (1 + eps));
    };
    const double start = std::log(2.0) - 2 / alpha;
    const double y = safeguarded_newton(f, start - 1, std::log(0.05), start);
    const double eps = std::exp(y);
    e.nu0 = 1 + eps;
    e.inv_nu0 = 1 / (1 + eps);
    e.log_nu0_minus_one = y;
    e.one_minus_inv_nu0 = eps / (1 + eps);
    e.log_one_minus_inv_nu0 = y - std::log1p(eps);
    return e;
  }
  // x = 1/nu0 in (0, 0.96]: atanh(x)/x - 1 = (1 - alpha)/alpha, increasing in x; the
  // right side is exact (1 - alpha is exact for alpha >= 1/2). Start from the first two
  // series terms x^2/3 + x^4/5 = c.
  const double c = (1 - alpha) / alpha;
  auto f = [c](double x, double& value, double& derivative) {
    atanh_ratio_minus_one(x, value, derivative);
    value -= c;
  };
  const double start = std::min(0.98, std::sqrt(2.5 * (std::sqrt(1.0 / 9 + 0.8 * c) - 1.0 / 3)));
  const double x = safeguarded_newton(f, 0.0, 0.99, start);
  e.nu0 = 1 / x;
  e.inv_nu0 = x;
  e.log_nu0_minus_one = std::log1p(-x) - std::log(x);
  e.one_minus_inv_nu0 = 1 - x;
  e.log_one_minus_inv_nu0 = std::log1p(-x);
  return e;
}

DwivediGuide::DwivediGuide(double alpha, double g) {
  if (!(alpha >= 0 && alpha <= 1))
    throw std::invalid_argument("Dwivedi guide: single-scattering albedo must be in [0, 1], got " +
                                std::to_string(alpha));
  if (!(g > -1 && g < 1))
    throw std::invalid_argument("Dwivedi guide: HG anisotropy must be in (-1, 1), got " + std::to_string(g));
  if (alpha < 1e-12) return;  // no scattering to guide: classical
  if (g <= 0) {
    const DwivediEigenvalue e = dwivedi_eigenvalue(alpha);
    set(e.inv_nu0, e.one_minus_inv_nu0, e.log_one_minus_inv_nu0);
    return;
  }
  // Similarity relation (Wyman, Patterson & Wilson 1989): kappa = (1 - alpha g)/nu0(alpha*).
  const double reduction = 1 - alpha * g;
  const DwivediEigenvalue e = dwivedi_eigenvalue(alpha * (1 - g) / reduction);
  const double one_minus_kappa = alpha * g + reduction * e.one_minus_inv_nu0;  // both terms >= 0
  set(reduction * e.inv_nu0, one_minus_kappa, std::log(one_minus_kappa));
}

void DwivediGuide::set(double kappa, double one_minus_kappa, double log_one_minus_kappa) {
  kappa_ = kappa;
  one_minus_kappa_ = one_minus_kappa;
  if (kappa == 0) {
    nu_minus_one_ = kInf, l_ = 0, kappa_over_l_ = 0.5;
    return;
  }
  nu_minus_one_ = one_minus_kappa / kappa;
  // L = ln((1 + kappa)/(1 - kappa)); 2 atanh is accurate at small kappa, the logarithms near 1.
  l_ = kappa < 0.5 ? 2 * std::atanh(kappa) : std::log1p(kappa) - log_one_minus_kappa;
  kappa_over_l_ = kappa / l_;
}

double DwivediGuide::pdf_cos(double u) const {
  if (!(u >= -1 && u <= 1)) return 0;
  if (kappa_ == 0) return 0.5;
  // p(u) = kappa/((1 - kappa u) L) = 1/((nu - u) L) (Krivanek & d'Eon 2014, normalised by L).
  if (kappa_ < 0.5) return kappa_over_l_ / (1 - kappa_ * u);
  const double nu_minus_u = std::max(nu_minus_one_ + (1 - u), 1e-300);
  return 1 / (nu_minus_u * l_);
}

double DwivediGuide::sample_cos(double xi) const {
  if (kappa_ == 0) return 2 * xi - 1;
  // nu - u = (nu + 1) r^xi with r = (nu - 1)/(nu + 1) = exp(-L) (Krivanek & d'Eon 2014).
  const double r_xi = std::exp(-xi * l_);
  double u;
  if (kappa_ < 0.5) {
    u = -std::expm1(-xi * l_) / kappa_ - r_xi;  // nu (1 - r^xi) - r^xi
  } else {
    u = 1 - ((2 + nu_minus_one_) * r_xi - nu_minus_one_);  // 1 - (nu - u) + (nu - 1)
  }
  return std::clamp(u, -1.0, 1.0);
}

}  // namespace dermis::sss
