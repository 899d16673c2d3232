// The Christensen-Burley study (Christensen & Burley 2015, sec. 3; METHODS 1.4 and 6):
// for each surface albedo A, the brute-force reference R(r) of a semi-infinite medium
// at l = 1, g = 0, normal incidence ("searchlight"), and the annulus means of each model
// (study_models.h) on the same log-spaced bins, with their errors (fit_error.h).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "dermis/sss/profiles/tabulated.h"
#include "dermis/sss/study/fit_error.h"

namespace dermis::sss {

std::vector<double> default_study_albedos();  // 0.01, 0.05, 0.1, 0.2, ..., 0.9, 0.95, 0.99

struct ProfileStudyOptions {
  std::vector<double> albedos = default_study_albedos();  // surface albedos, each in (0, 1)
  double eta = 1.0;                                       // boundary n_medium / n_outside (1: index-matched)
  uint64_t paths = 400000;                                // reference paths per albedo
  uint64_t seed = 1;
  int bins = 100;                    // log-spaced radial bins: [0, r_min), then to r_max(A)
  double r_min = 0.005;              // first bin edge, in mean free paths
  double error_r_lo = 0.01;          // r_a of the range measures, in mean free paths
  double energy_fraction = 0.99;     // r_b: the radius holding this fraction of the reference energy
  uint64_t inversion_paths = 50000;  // per simulation of the alpha search when eta != 1
};

// Throws std::invalid_argument with a message naming the option for bad values.
void validate(const ProfileStudyOptions& o);

// The outer radius of the bins for a medium of single-scattering albedo alpha (g = 0,
// l = 1): max(16, 16 / sigma_tr) with sigma_tr = sqrt(3 (1 - alpha)) (the diffusion
// decay rate, METHODS 1.3), so that e^{-16} of the diffusion tail lies beyond it.
double study_r_max(double single_scattering_albedo);

constexpr int kErrorMeasures = 3;  // LogRadius, LinearRadius, Energy
constexpr std::array<ErrorMeasure, kErrorMeasures> kStudyMeasures = {ErrorMeasure::LogRadius,
                                                                     ErrorMeasure::LinearRadius, ErrorMeasure::Energy};

struct AlbedoStudy {
  double surface_albedo = 0;                                 // the target A
  double single_scattering_albedo = 0;                       // alpha found for it
  double simulated_albedo = 0, simulated_albedo_stderr = 0;  // per entering power, all radii
  double beyond_rmax = 0;                                    // part of it beyond the last bin
  double r_a = 0, r_b = 0;                                   // range of the range measures
  BinnedProfile reference;                                   // per entering power
  std::vector<std::string> model_keys, model_labels;
  std::vector<BinnedProfile> models;
  // [model][measure]; NaN for a range measure when the reference has an empty bin in the range.
  std::vector<std::array<double, kErrorMeasures>> errors;
  std::array<double, kErrorMeasures> noise{};  // the reference's noise floor per measure
  uint64_t paths = 0;
  double seconds = 0;  // simulation wall-clock time
};

// One albedo of the study (table: study_profile_table(o.eta)).
AlbedoStudy study_albedo(double surface_albedo, const ProfileStudyOptions& o,
                         const std::shared_ptr<const ProfileTable>& table);

// CSV: r_lo, r_hi, r_mid (geometric mid, hi/2 for the first bin), R_ref, R_ref_stderr,
// then one column per model (annulus means), per entering power.
void write_profile_csv(const AlbedoStudy& s, std::ostream& out);
// CSV of the errors: albedo, alpha, model, then one column per measure, and a noise-floor row per albedo.
void write_error_csv(const std::vector<AlbedoStudy>& studies, std::ostream& out);

}  // namespace dermis::sss
