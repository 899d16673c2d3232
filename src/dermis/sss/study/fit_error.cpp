#include "dermis/sss/study/fit_error.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dermis/sss/profiles/gaussian.h"

namespace dermis::sss {

namespace {

void check_bins(const BinnedProfile& p, const char* what) {
  const size_t n = p.value.size();
  if (n == 0 || p.r_lo.size() != n || p.r_hi.size() != n)
    throw std::invalid_argument(std::string("fit error: ") + what + " has no bins or inconsistent bin arrays");
  for (size_t i = 0; i < n; ++i)
    if (!(p.r_hi[i] > p.r_lo[i]) || !(p.r_lo[i] >= 0))
      throw std::invalid_argument(std::string("fit error: ") + what + " has an empty or negative bin");
}

void check_same_bins(const BinnedProfile& a, const BinnedProfile& b) {
  check_bins(a, "the reference");
  check_bins(b, "the model");
  if (a.value.size() != b.value.size())
    throw std::invalid_argument("fit error: the model and the reference have different bins");
  for (size_t i = 0; i < a.value.size(); ++i)
    if (a.r_lo[i] != b.r_lo[i] || a.r_hi[i] != b.r_hi[i])
      throw std::invalid_argument("fit error: the model and the reference have different bin edges");
}

// The weight of bin [lo, hi) in the measure, restricted to [r_a, r_b].
double bin_weight(ErrorMeasure m, double lo, double hi, double r_a, double r_b) {
  switch (m) {
    case ErrorMeasure::Energy:
      return kPiD * (hi * hi - lo * lo);
    case ErrorMeasure::LinearRadius:
      return std::max(0.0, std::min(hi, r_b) - std::max(lo, r_a));
    case ErrorMeasure::LogRadius: {
      const double a = std::max(lo, r_a), b = std::min(hi, r_b);
      return b > a ? std::log(b / a) : 0.0;
    }
  }
  return 0;
}

void check_range(ErrorMeasure m, double r_a, double r_b) {
  if (m == ErrorMeasure::Energy) return;
  if (!(r_a > 0 && r_b > r_a) || !std::isfinite(r_b))
    throw std::invalid_argument("fit error: the radial range needs 0 < r_a < r_b (got [" + std::to_string(r_a) + ", " +
                                std::to_string(r_b) + "])");
}

// Weighted mean of term(i) / R_ref,i (range measures) or sum term(i) area_i / sum R_ref,i area_i (energy).
template <class Term>
double weighted(const BinnedProfile& ref, ErrorMeasure m, double r_a, double r_b, const Term& term) {
  check_range(m, r_a, r_b);
  double num = 0, den = 0;
  for (size_t i = 0; i < ref.value.size(); ++i) {
    const double w = bin_weight(m, ref.r_lo[i], ref.r_hi[i], r_a, r_b);
    if (w <= 0) continue;
    if (m == ErrorMeasure::Energy) {
      num += term(i) * w;
      den += ref.value[i] * w;
      continue;
    }
    if (!(ref.value[i] > 0))
      throw std::invalid_argument("fit error: the reference is zero in bin [" + std::to_string(ref.r_lo[i]) + ", " +
                                  std::to_string(ref.r_hi[i]) + ") inside the error range; narrow the range or " +
                                  "trace more paths");
    num += term(i) / ref.value[i] * w;
    den += w;
  }
  if (!(den > 0)) throw std::invalid_argument("fit error: no reference energy / no bin inside the error range");
  return num / den;
}

}  // namespace

double relative_error(const BinnedProfile& ref, const BinnedProfile& model, ErrorMeasure m, double r_a, double r_b) {
  check_same_bins(ref, model);
  return weighted(ref, m, r_a, r_b, [&](size_t i) { return std::abs(model.value[i] - ref.value[i]); });
}

double noise_floor(const BinnedProfile& ref, ErrorMeasure m, double r_a, double r_b) {
  check_bins(ref, "the reference");
  if (ref.standard_error.size() != ref.value.size())
    throw std::invalid_argument("fit error: the reference has no standard errors");
  const double k = std::sqrt(2 / kPiD);  // E|N(0, 1)|
  return weighted(ref, m, r_a, r_b, [&](size_t i) { return k * ref.standard_error[i]; });
}

double energy_radius(const BinnedProfile& ref, double total_energy, double fraction) {
  check_bins(ref, "the reference");
  if (!(fraction > 0 && fraction < 1)) throw std::invalid_argument("fit error: an energy fraction must lie in (0, 1)");
  if (!(total_energy > 0)) throw std::invalid_argument("fit error: the reference carries no energy");
  const double target = fraction * total_energy;
  double cumulative = 0;
  for (size_t i = 0; i < ref.value.size(); ++i) {
    const double lo2 = ref.r_lo[i] * ref.r_lo[i], hi2 = ref.r_hi[i] * ref.r_hi[i];
    const double e = ref.value[i] * kPiD * (hi2 - lo2);
    if (e > 0 && cumulative + e >= target) {
      const double t = (target - cumulative) / e;  // uniform in area inside the bin
      return std::sqrt(lo2 + t * (hi2 - lo2));
    }
    cumulative += e;
  }
  return ref.r_hi.back();
}

const char* error_measure_name(ErrorMeasure m) {
  switch (m) {
    case ErrorMeasure::LogRadius:
      return "log-r mean";
    case ErrorMeasure::LinearRadius:
      return "linear-r mean";
    case ErrorMeasure::Energy:
      return "energy";
  }
  return "?";
}

}  // namespace dermis::sss
