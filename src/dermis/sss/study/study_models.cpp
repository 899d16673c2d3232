#include "dermis/sss/study/study_models.h"

#include <cmath>

#include "dermis/sss/profiles/profile.h"
#include "dermis/sss/profiles/quadrature.h"

namespace dermis::sss {

double burley_unfitted(double albedo, double r) {
  r = std::max(r, 1e-12);
  return albedo * (std::exp(-r) + std::exp(-r / 3)) / (8 * kPiD * r);  // Christensen & Burley 2015, eq. 1, w = A, s = 1
}

std::shared_ptr<const ProfileTable> study_profile_table(double eta) {
  return std::make_shared<const ProfileTable>(dipole_family(eta));
}

std::vector<StudyModel> study_models(double albedo, double eta, const std::shared_ptr<const ProfileTable>& table) {
  const BurleyProfile cb_volume(albedo, 1.0, BurleyParameterisation::VolumeMeanFreePath);
  const BurleyProfile cb_seed(albedo, 1.0, BurleyParameterisation::VolumeMeanFreePathSeedText);
  const DipoleProfile dipole = DipoleProfile::from_albedo(albedo, 1.0, eta);
  const TabulatedProfile tabulated(table, albedo, 1.0);
  return {
      {"burley_s1", "Burley (w=A, s=1)", [albedo](double r) { return burley_unfitted(albedo, r); }},
      {"cb_volume_mfp", "C-B fit |A-0.8|^3", [cb_volume](double r) { return cb_volume.eval(r); }},
      {"cb_seed_text", "C-B fit (0.8-A)^3", [cb_seed](double r) { return cb_seed.eval(r); }},
      {"dipole", "dipole", [dipole](double r) { return dipole.eval(r); }},
      {"tabulated", "tabulated dipole", [tabulated](double r) { return tabulated.eval(r); }},
  };
}

double annulus_mean(const std::function<double(double)>& R, double lo, double hi) {
  auto integrand = [&](double r) { return R(r) * 2 * kPiD * r; };
  double sum = 0;
  if (lo <= 0) {
    for (int k = 0; k < 4; ++k) sum += gauss_legendre_16(integrand, hi * k / 4, hi * (k + 1) / 4);
  } else {
    // Substituting r = e^t: int f(r) dr = int f(e^t) e^t dt, smooth for profiles ~ e^{-r}/r.
    const double a = std::log(lo), b = std::log(hi);
    auto in_log = [&](double t) {
      const double r = std::exp(t);
      return integrand(r) * r;
    };
    for (int k = 0; k < 4; ++k) sum += gauss_legendre_16(in_log, a + (b - a) * k / 4, a + (b - a) * (k + 1) / 4);
  }
  return sum / (kPiD * (hi * hi - lo * lo));
}

}  // namespace dermis::sss
