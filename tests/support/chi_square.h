// Pearson's chi-square goodness-of-fit test for sampler tests: observed counts
// against expected counts (from integrating the sampler's pdf over each bin).
#pragma once

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace dermis::testing {

// Regularized upper incomplete gamma Q(a, x) (series for x < a + 1, Lentz's
// continued fraction otherwise; Abramowitz & Stegun 6.5.29 and 6.5.31).
inline double gamma_q(double a, double x) {
  if (x <= 0) return 1.0;
  const double gln = std::lgamma(a);
  if (x < a + 1) {
    double sum = 1.0 / a, term = sum;
    for (int n = 1; n < 100000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * 1e-15) break;
    }
    return 1.0 - sum * std::exp(-x + a * std::log(x) - gln);
  }
  double b = x + 1 - a, c = 1e300, d = 1 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < 1e-300) d = 1e-300;
    c = b + an / c;
    if (std::abs(c) < 1e-300) c = 1e-300;
    d = 1 / d;
    double del = d * c;
    h *= del;
    if (std::abs(del - 1) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - gln) * h;
}

struct ChiSquareResult {
  double statistic = 0;
  int dof = 0;
  double p_value = 1;
};

// Bins whose expected count is below min_expected are pooled together (the
// usual validity condition of the test). expected must sum to the sample count.
inline ChiSquareResult chi_square(const std::vector<double>& observed, const std::vector<double>& expected,
                                  double min_expected = 5.0) {
  if (observed.size() != expected.size()) throw std::invalid_argument("chi_square: size mismatch");
  ChiSquareResult r;
  double pooled_obs = 0, pooled_exp = 0;
  int cells = 0;
  for (std::size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < min_expected) {
      pooled_obs += observed[i];
      pooled_exp += expected[i];
      continue;
    }
    r.statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++cells;
  }
  if (pooled_exp >= min_expected) {
    r.statistic += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
    ++cells;
  } else if (pooled_obs > 10 * std::max(pooled_exp, 1.0)) {
    // Many samples where the pdf says almost none: count it as a gross failure.
    r.statistic += 1e9;
  }
  r.dof = cells - 1;
  r.p_value = r.dof > 0 ? gamma_q(r.dof / 2.0, r.statistic / 2.0) : 1.0;
  return r;
}

// Significance level for every sampler test: with Bonferroni over a handful of
// tests per suite, a correct sampler fails with probability < 1e-4 per run; the
// seeds are fixed, so a run is reproducible anyway.
inline constexpr double kChiSquareAlpha = 1e-4;

}  // namespace dermis::testing
