#include "dermis/sss/profiles/photon_beam_diffusion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "dermis/core/vec.h"
#include "dermis/sss/profiles/profile.h"
#include "dermis/sss/profiles/profile_test_support.h"
#include "dermis/sss/profiles/quadrature.h"

namespace dermis::sss {
namespace {

// The energy of a profile: int_0^inf R(r) 2 pi r dr, adaptive, in pieces of r.
template <class F>
double plane_integral(const F& f) {
  return integrate_to_infinity([&](double r) { return f(r) * 2 * kPiD * r; }, 1e-3, 1e-11);
}

// Single scattering through an index-matched boundary with isotropic scattering has a
// closed-form total: the light scattered once at depth t leaves if it reaches the surface
// unscattered, R_1 = int_0^inf rho e^{-t} int_0^1 e^{-t / mu} dmu dt / 2 = (rho / 2)(1 - ln 2).
// The profile's plane integral (its quadrature in depth, then adaptive in r) must equal it.
TEST(PhotonBeamDiffusion, SingleScatteringIntegratesToTheClosedFormTotal) {
  for (double rho : {0.3, 0.8, 0.99}) {
    const PhotonBeamDiffusion p(rho, 0.0, 1.0);
    const double total = plane_integral([&](double r) { return p.single(r); });
    EXPECT_NEAR(total / (rho / 2 * (1 - std::log(2.0))), 1.0, 2e-4) << rho;
  }
}

// Each dipole's exitance integrates over the plane to the closed form of its fluence and
// flux (plane_exitance), for a matched and a mismatched boundary.
TEST(PhotonBeamDiffusion, DipoleExitanceIntegratesToItsClosedForm) {
  for (double eta : {1.0, 1.33, 1.5})
    for (double rho : {0.5, 0.95, 0.999})
      for (double z : {0.05, 1.0, 4.0}) {
        const PhotonBeamDiffusion p(rho, 0.3, eta);
        const double numeric = plane_integral([&](double r) { return p.dipole_exitance(z, r); });
        EXPECT_NEAR(numeric / p.plane_exitance(z), 1.0, 1e-6) << eta << " " << rho << " " << z;
      }
}

// The depth quadrature (unit pieces of a log-stretched depth) against adaptive
// Gauss-Kronrod on the same integrand, over radii from 1e-4 to 30 mean free paths.
TEST(PhotonBeamDiffusion, DepthQuadratureMatchesAdaptiveIntegration) {
  for (double rho : {0.2, 0.9, 0.999})
    for (double r : {1e-4, 0.01, 0.3, 3.0, 30.0}) {
      const double g = 0.4, eta = 1.4;
      const PhotonBeamDiffusion p(rho, g, eta);
      const double stp = p.reduced_extinction();
      const double sigma_sp = rho * (1 - g), rho_p = sigma_sp / stp;
      const double ms = integrate_to_infinity(
          [&](double z) {
            const double kappa = 1 - std::exp(-2 * stp * (std::sqrt(r * r + z * z) + z));
            return stp * std::exp(-stp * z) * rho_p * rho_p * kappa * p.dipole_exitance(z, r);
          },
          std::min(r, 1.0), 1e-10 * p.multiple(r));
      EXPECT_NEAR(p.multiple(r) / ms, 1.0, 1e-7) << rho << " " << r;
    }
}

// Without scattering there is nothing; without absorption (rho = 1) the multiple-
// scattering profile is finite, positive and decays like a power of r.
TEST(PhotonBeamDiffusion, LimitsOfTheAlbedo) {
  const PhotonBeamDiffusion none(0.0, 0.0, 1.33);
  EXPECT_EQ(none.eval(0.5), 0.0);
  const PhotonBeamDiffusion clear(1.0, 0.0, 1.33);
  for (double r : {0.1, 1.0, 10.0, 100.0}) {
    EXPECT_GT(clear.multiple(r), 0.0);
    EXPECT_TRUE(std::isfinite(clear.multiple(r)));
  }
  EXPECT_LT(clear.multiple(100.0), 1e-3 * clear.multiple(1.0));
}

// The effective albedo rho_eff(rho) of the tabulated family rises with rho (and exceeds 1
// by up to 2% as rho -> 1 at eta = 1.33: the model's, not conserved energy); the table reproduces the profile between
// its nodes, and a reflectance inverts to the albedo it came from.
TEST(PhotonBeamDiffusion, TabulatedFamily) {
  const auto table = std::make_shared<const ProfileTable>(photon_beam_family(0.0, 1.33), photon_beam_table_options());
  double previous = 0;
  for (double rho : table->albedos()) {
    const double e = table->lookup(rho).energy;
    EXPECT_GT(e, previous) << rho;
    previous = e;
  }
  for (double rho : {0.05, 0.5, 0.9, 0.99, 0.9995}) {
    const TabulatedProfile tab(table, rho, 1.0);
    const PhotonBeamDiffusion exact(rho, 0.0, 1.33);
    const double energy = plane_integral([&](double r) { return exact.eval(r); });
    EXPECT_NEAR(tab.albedo() / energy, 1.0, 2e-3) << rho;
    for (double fraction : {0.1, 0.5, 0.9}) {
      const double r = tab.r_max(fraction);
      EXPECT_NEAR(tab.eval(r) / exact.eval(r), 1.0, 1e-2) << rho << " at r = " << r;
    }
    EXPECT_NEAR(table->albedo_for_energy(tab.albedo()), rho, 1e-6 + 1e-4 * (1 - rho)) << rho;
  }
}

// The photon-beam profile as the renderer samples it (a TabulatedProfile at a mean free
// path of 0.3): it integrates to its albedo, its radial pdf to one, and its sampler
// follows its pdf (chi-square; profile_test_support.h), between nodes, near rho = 1 and
// at a low albedo, with g and eta that are not the defaults.
TEST(PhotonBeamDiffusion, TabulatedProfileIsConsistentAndSamplesItsPdf) {
  const auto table = std::make_shared<const ProfileTable>(photon_beam_family(0.3, 1.4), photon_beam_table_options());
  uint64_t seed = 71;
  for (double rho : {0.1, 0.77, 0.9993})
    testing::expect_consistent_profile(RadialProfile(TabulatedProfile(table, rho, 0.3)),
                                       "photonbeam rho " + std::to_string(rho), seed++);
}

}  // namespace
}  // namespace dermis::sss
