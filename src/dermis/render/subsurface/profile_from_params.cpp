#include "dermis/render/subsurface/profile_from_params.h"

#include <cmath>
#include <memory>

#include "dermis/render/subsurface/coefficients.h"
#include "dermis/sss/profiles/tabulated.h"

namespace dermis {

sss::ProfileRGB make_profile(const SubsurfaceParams& p) {
  using Profile = SubsurfaceParams::Profile;
  const auto [A, l] = albedo_and_mfp(p);
  switch (p.profile) {
    case Profile::Burley:
      return sss::make_burley_rgb(A, l, sss::BurleyParameterisation::VolumeMeanFreePath);
    case Profile::BurleyDiffuseMfp:
      return sss::make_burley_rgb(A, l, sss::BurleyParameterisation::DiffuseMeanFreePath);
    case Profile::Dipole:
      if (p.sigma_a) return sss::make_dipole_rgb_from_coefficients(*p.sigma_a, *p.sigma_s, p.g, p.eta);
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
      return sss::make_skin_rgb(1.0 / p.scale, p.reflectance ? *p.reflectance : RGB(1.0f));
    case Profile::Tabulated: {
      // The Cycles page's table: the (A, r/l) reparameterised dipole, at this eta.
      auto table = std::make_shared<const sss::ProfileTable>(sss::dipole_family(p.eta));
      return sss::make_tabulated_rgb(table, A, l);
    }
  }
  return sss::make_burley_rgb(A, l);
}

}  // namespace dermis
