#include "dermis/render/subsurface/profile_from_params.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include "dermis/core/cache_dir.h"
#include "dermis/source_hashes.h"  // generated (cmake/source_hashes.cmake)
#include "dermis/sss/profiles/photon_beam_diffusion.h"
#include "dermis/sss/profiles/profile_table_io.h"

namespace dermis {

namespace {

// The photon-beam-diffusion table of one (g, eta), shared by every material with these
// parameters: built once per machine (about 1.8 s of CPU) and cached on disk
// (core/cache_dir.h, sss/profiles/profile_table_io.h), read in milliseconds after that.
std::shared_ptr<const sss::ProfileTable> photon_beam_table(float g, float eta) {
  static std::mutex mutex;
  static std::map<std::pair<float, float>, std::shared_ptr<const sss::ProfileTable>> tables;
  const std::lock_guard lock(mutex);
  auto& table = tables[{g, eta}];
  if (!table) {
    table = sss::cached_profile_table(default_cache_dir(), photon_beam_table_key(g, eta), [&] {
      return sss::ProfileTable(sss::photon_beam_family(g, eta), sss::photon_beam_table_options());
    });
  }
  return table;
}

// pbrt-v4's parameterisation of the photon-beam table: per channel the single-scattering
// albedo rho and the mean free path 1 / sigma_t, from the coefficients or from
// (reflectance, mfp), the reflectance inverted through the table's effective albedo
// rho_eff(rho) (PBR 3rd ed. sec. 15.5.6, SubsurfaceFromDiffuse) and mfp = 1 / sigma_t.
sss::ProfileRGB photon_beam_profile(const MediumAt& at, const std::shared_ptr<const sss::ProfileTable>& table) {
  RGB rho, l;
  const double lo = table->albedos().front(), hi = table->albedos().back();
  for (int c = 0; c < 3; ++c) {
    double rho_c, l_c;
    if (at.sigma_a) {
      const double sigma_t = double((*at.sigma_a)[c]) + (*at.sigma_s)[c];
      // A textured medium may be empty at a point: the table's least albedo there, at a
      // finite length (the parser refuses sigma_t = 0 for constants).
      rho_c = sigma_t > 0 ? (*at.sigma_s)[c] / sigma_t : 0;
      l_c = sigma_t > 0 ? 1 / sigma_t : 1;
    } else {
      rho_c = table->albedo_for_energy((*at.reflectance)[c]);
      l_c = (*at.mfp)[c];
    }
    rho[c] = float(std::clamp(rho_c, lo, hi));  // outside the table's nodes: its first or last
    l[c] = float(l_c);
  }
  return sss::make_tabulated_rgb(table, rho, l);
}

}  // namespace

std::string photon_beam_table_key(float g, float eta) {
  const sss::ProfileTableOptions options = sss::photon_beam_table_options();
  return fmt::format("photonbeam-v{}-{}-g{:.9g}-eta{:.9g}-a{}-r{}-x{:.9g}-{:.9g}.table", sss::kPhotonBeamTableVersion,
                     source_hash::kPhotonBeamTable, g, eta, options.albedos.size(), options.radial_nodes, options.x_min,
                     options.x_max);
}

std::shared_ptr<const sss::ProfileTable> profile_table(const SubsurfaceParams& p) {
  // The Cycles page's table: the (A, r/l) reparameterised dipole, at this eta.
  if (p.profile == SubsurfaceParams::Profile::Tabulated)
    return std::make_shared<const sss::ProfileTable>(sss::dipole_family(p.eta));
  if (p.profile == SubsurfaceParams::Profile::PhotonBeam) return photon_beam_table(p.g, p.eta);
  return nullptr;
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
    case Profile::PhotonBeam:
      return photon_beam_profile(at, table);
  }
  return sss::make_burley_rgb(A, l);
}

}  // namespace dermis
