// Error measures between a binned reference profile R_ref (from the half-space
// simulator: the mean of R over each annulus [lo, hi)) and a model's annulus means R_m
// on the same bins. docs/profile-study.md says why each exists.
//
//   log-r mean     E_log = int |R_m - R_ref| / R_ref d(ln r) / ln(r_b / r_a)
//                  over [r_a, r_b]: the relative error averaged uniformly in ln r, what
//                  the eye reads off a log-log plot.
//   linear-r mean  E_lin = int |R_m - R_ref| / R_ref dr / (r_b - r_a) over [r_a, r_b]:
//                  the same averaged uniformly in r, what the eye reads off a plot of
//                  r R(r) with a linear r axis and a log vertical axis (the seed's Figure 1).
//   energy         E_energy = int |R_m - R_ref| 2 pi r dr / int R_ref 2 pi r dr over all
//                  bins: the L1 distance of the two energy distributions, relative to the
//                  reference's energy (independent of any range).
// Each integral is the sum over bins of the piecewise-constant integrand times the bin's
// overlap with [r_a, r_b] in the measure named (d ln r, dr, or annulus area).
#pragma once

#include <vector>

namespace dermis::sss {

struct BinnedProfile {
  std::vector<double> r_lo, r_hi;      // bin edges, increasing, r_hi[i] == r_lo[i + 1]
  std::vector<double> value;           // the annulus mean of R in each bin
  std::vector<double> standard_error;  // its standard error (0 for a model)
};

enum class ErrorMeasure { LogRadius, LinearRadius, Energy };

// Relative error of `model` against `reference` (same bins) in the given measure, over
// [r_a, r_b] for LogRadius / LinearRadius (Energy uses every bin). Bins whose reference
// value is 0 inside the range make the relative error undefined: they throw
// std::invalid_argument, as do mismatched bins and an empty range.
double relative_error(const BinnedProfile& reference, const BinnedProfile& model, ErrorMeasure measure, double r_a,
                      double r_b);

// What the same measure reports for a perfect model, from the reference's noise alone:
// |N(0, sigma_i)| has mean sigma_i sqrt(2 / pi), so the floor is the measure's weighted
// mean of sqrt(2/pi) standard_errori / R_ref,i (for Energy: sum sqrt(2/pi) standard_errori area_i / energy).
double noise_floor(const BinnedProfile& reference, ErrorMeasure measure, double r_a, double r_b);

// The radius inside which `fraction` of `total_energy` lies, from the binned reference
// (energy taken uniform in area inside a bin); r_hi of the last bin if never reached.
double energy_radius(const BinnedProfile& reference, double total_energy, double fraction);

const char* error_measure_name(ErrorMeasure m);

}  // namespace dermis::sss
