#include "dermis/render/subsurface/profile_from_params.h"

#include <cmath>
#include <memory>


namespace dermis {

std::shared_ptr<const sss::ProfileTable> profile_table(const SubsurfaceParams& p) {
  // The Cycles page's table: the (A, r/l) reparameterised dipole, at this eta.
  if (p.profile != SubsurfaceParams::Profile::Tabulated) return nullptr;
  return std::make_shared<const sss::ProfileTable>(sss::dipole_family(p.eta));
}

sss::ProfileRGB make_profile(const SubsurfaceParams& p, const MediumAt& at,
                             const std::shared_ptr<const sss::ProfileTable>& table) {
  using Profile = SubsurfaceParams::Profile;
  const auto [A, l] = albedo_and_mfp(at, p.g);
  switch (p.profile) {
    case Profile::Burley:
      return sss::make_burley_rgb(A, l, sss::BurleyParameterisation::VolumeMeanFreePath);
    case Profile::BurleyDiffuseMfp:
      return sss::make_burley_rgb(A, l, sss::BurleyParameterisation::DiffuseMeanFreePath);
    case Profile::Dipole:
      if (at.sigma_a) return sss::make_dipole_rgb_from_coefficients(*at.sigma_a, *at.sigma_s, p.g, p.eta);
      return sss::make_dipole_rgb(A, l, p.eta);
    case Profile::Gaussian:
    case Profile::Cubic: {
      // Matched to the Christensen-Burley profile of the same (A, l) by the mean squared
      // radius: Burley <r^2> = 14 d^2 (d = l/s); Gaussian <r^2> = 2v; cubic <r^2> = R^2/7.
      RGB v, R;
      for (int c = 0; c < 3; ++c) {
        double d = l[c] / sss::burley_scale(A[c], sss::BurleyParameterisation::VolumeMeanFreePath);
        v[c] = float(7 * d * d);
        R[c] = float(std::sqrt(98.0) * d);
      }
      return p.profile == Profile::Gaussian ? sss::make_gaussian_rgb(A, v) : sss::make_cubic_rgb(A, R);
    }
    case Profile::Skin6:
      // d'Eon & Luebke's variances are in mm; `scale` multiplies coefficients, i.e.
      // divides lengths, so scene units per mm = 1 / scale. Weights times the albedo
      // when reflectance is given.
      return sss::make_skin_rgb(1.0 / at.scale, at.reflectance ? *at.reflectance : RGB(1.0f));
    case Profile::Tabulated:
      return sss::make_tabulated_rgb(table, A, l);
  }
  return sss::make_burley_rgb(A, l);
}

}  // namespace dermis
