#include "dermis/sss/study/profile_study.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "dermis/sss/halfspace/halfspace.h"
#include "dermis/sss/study/albedo_inversion.h"
#include "dermis/sss/study/study_models.h"

namespace dermis::sss {

std::vector<double> default_study_albedos() {
  return {0.01, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.99};
}

void validate(const ProfileStudyOptions& o) {
  if (o.albedos.empty()) throw std::invalid_argument("--albedos: give at least one surface albedo");
  for (double a : o.albedos)
    if (!(a > 0 && a < 1))
      throw std::invalid_argument(fmt::format("--albedos: each surface albedo must lie in (0, 1) (got {})", a));
  if (!(o.eta > 0) || !std::isfinite(o.eta))
    throw std::invalid_argument(fmt::format("--eta must be positive and finite (got {})", o.eta));
  if (o.paths < 1000) throw std::invalid_argument(fmt::format("--paths must be at least 1000 (got {})", o.paths));
  if (o.inversion_paths < 1000)
    throw std::invalid_argument(fmt::format("the inversion needs at least 1000 paths (got {})", o.inversion_paths));
  if (o.bins < 8 || o.bins > 100000)
    throw std::invalid_argument(fmt::format("--bins must lie in [8, 100000] (got {})", o.bins));
  if (!(o.r_min > 0 && o.r_min < 16))
    throw std::invalid_argument(fmt::format("the first bin edge must lie in (0, 16) (got {})", o.r_min));
  if (!(o.error_r_lo >= o.r_min && o.error_r_lo < 16))
    throw std::invalid_argument(fmt::format("the error range must start in [{}, 16) (got {})", o.r_min, o.error_r_lo));
  if (!(o.energy_fraction > 0 && o.energy_fraction < 1))
    throw std::invalid_argument(fmt::format("the energy fraction must lie in (0, 1) (got {})", o.energy_fraction));
}

double study_r_max(double alpha) {
  const double sigma_tr = std::sqrt(3 * (1 - alpha));  // Jensen et al. 2001 with sigma'_t = 1
  return std::clamp(16 / std::max(sigma_tr, 1e-300), 16.0, 1e5);
}

namespace {
// A range measure is undefined when the reference has an empty bin inside the range
// (too few paths): NaN, reported as "n/a", rather than a number from a silently narrowed range.
double error_or_nan(const BinnedProfile& ref, const BinnedProfile& model, ErrorMeasure m, double r_a, double r_b) {
  for (size_t i = 0; i < ref.value.size(); ++i)
    if (m != ErrorMeasure::Energy && ref.r_hi[i] > r_a && ref.r_lo[i] < r_b && !(ref.value[i] > 0))
      return std::numeric_limits<double>::quiet_NaN();
  return relative_error(ref, model, m, r_a, r_b);
}
}  // namespace

AlbedoStudy study_albedo(double a, const ProfileStudyOptions& o, const std::shared_ptr<const ProfileTable>& table) {
  AlbedoStudy s;
  s.surface_albedo = a;
  s.single_scattering_albedo =
      single_scattering_albedo_simulated(a, o.eta, o.inversion_paths, o.seed ^ 0x5eedULL).single_scattering_albedo;

  HalfspaceConfig c;
  c.albedo = s.single_scattering_albedo;
  c.sigma_t = 1;
  c.g = 0;
  c.eta = o.eta;
  c.incidence = Incidence::Normal;
  c.paths = o.paths;
  c.seed = o.seed;
  c.bins = RadialBins::logarithmic(o.r_min, study_r_max(s.single_scattering_albedo), o.bins);
  validate(c);
  const HalfspaceResult r = simulate_halfspace(c);
  const double per_entering = 1 / (1 - r.specular);
  s.simulated_albedo = r.albedo_per_entering();
  s.simulated_albedo_stderr = r.albedo_per_entering_stderr();
  s.beyond_rmax = r.beyond_rmax * per_entering;
  s.paths = r.paths;
  s.seconds = r.seconds;
  s.reference.r_lo = r.r_lo;
  s.reference.r_hi = r.r_hi;
  for (size_t i = 0; i < r.R.size(); ++i) {
    s.reference.value.push_back(r.R[i] * per_entering);
    s.reference.standard_error.push_back(r.R_stderr[i] * per_entering);
  }

  s.r_a = o.error_r_lo;
  s.r_b = std::max(energy_radius(s.reference, s.simulated_albedo, o.energy_fraction), 2 * s.r_a);
  for (const StudyModel& m : study_models(a, o.eta, table)) {
    BinnedProfile p;
    p.r_lo = s.reference.r_lo;
    p.r_hi = s.reference.r_hi;
    for (size_t i = 0; i < p.r_lo.size(); ++i) p.value.push_back(annulus_mean(m.eval, p.r_lo[i], p.r_hi[i]));
    p.standard_error.assign(p.value.size(), 0.0);
    std::array<double, kErrorMeasures> e{};
    for (int k = 0; k < kErrorMeasures; ++k) e[k] = error_or_nan(s.reference, p, kStudyMeasures[k], s.r_a, s.r_b);
    s.model_keys.push_back(m.key);
    s.model_labels.push_back(m.label);
    s.models.push_back(std::move(p));
    s.errors.push_back(e);
  }
  for (int k = 0; k < kErrorMeasures; ++k)
    s.noise[k] = std::isnan(s.errors.front()[k]) ? s.errors.front()[k]
                                                 : noise_floor(s.reference, kStudyMeasures[k], s.r_a, s.r_b);
  return s;
}

void write_profile_csv(const AlbedoStudy& s, std::ostream& out) {
  out << "r_lo,r_hi,r_mid,R_ref,R_ref_stderr";
  for (const auto& k : s.model_keys) out << ',' << k;
  out << '\n';
  const BinnedProfile& ref = s.reference;
  for (size_t i = 0; i < ref.value.size(); ++i) {
    const double mid = ref.r_lo[i] > 0 ? std::sqrt(ref.r_lo[i] * ref.r_hi[i]) : 0.5 * ref.r_hi[i];
    out << fmt::format("{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}", ref.r_lo[i], ref.r_hi[i], mid, ref.value[i],
                       ref.standard_error[i]);
    for (const auto& m : s.models) out << fmt::format(",{:.9g}", m.value[i]);
    out << '\n';
  }
}

void write_error_csv(const std::vector<AlbedoStudy>& studies, std::ostream& out) {
  out << "albedo,alpha,r_a,r_b,model";
  for (ErrorMeasure m : kStudyMeasures) out << ',' << error_measure_name(m);
  out << '\n';
  for (const AlbedoStudy& s : studies) {
    auto row = [&](const std::string& name, const std::array<double, kErrorMeasures>& e) {
      out << fmt::format("{},{:.12g},{:.6g},{:.6g},{}", s.surface_albedo, s.single_scattering_albedo, s.r_a, s.r_b,
                         name);
      for (double v : e) out << fmt::format(",{:.6g}", v);
      out << '\n';
    };
    for (size_t k = 0; k < s.models.size(); ++k) row(s.model_keys[k], s.errors[k]);
    row("reference_noise_floor", s.noise);
  }
}

}  // namespace dermis::sss
