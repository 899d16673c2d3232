// One channel's radial profile R(r) behind one value type (METHODS 0 and 1).
//
// Contract, for every alternative (lengths in scene units):
//   eval(r)          R(r), an area density on the surface
//   albedo()         A = the integral of eval over the plane, int_0^inf R(r) 2 pi r dr
//   sample_radius(xi) r in [0, r_max()] for xi in [0, 1), distributed as pdf_radius
//   pdf_radius(r)    the radial density of sample_radius (zero beyond r_max()); for a
//                    single-lobe analytic profile it is 2 pi r R(r) / (A kept), kept the
//                    energy fraction inside r_max(); for a sum of Gaussians it is the
//                    mixture of the truncated lobes, for a table the interpolated density
//   r_max()          the truncation radius of sample_radius
//   r_max(f)         the radius inside which the fraction f of the energy lies
//
// Why a std::variant and not a virtual base: the probe sampler evaluates these per
// candidate hit and per channel; std::visit over a closed set compiles to one indexed
// jump and lets the small alternatives inline, and a RadialProfile is a plain value
// (copyable, no heap except the shared, immutable tables of the dipole and tabulated
// alternatives). Code that needs a concrete type's extras (the Gaussian lobes for MIS)
// asks for it with get_if.
#pragma once

#include <array>
#include <memory>
#include <variant>

#include "dermis/core/rgb.h"
#include "dermis/sss/profiles/burley.h"
#include "dermis/sss/profiles/cubic.h"
#include "dermis/sss/profiles/dipole.h"
#include "dermis/sss/profiles/gaussian.h"
#include "dermis/sss/profiles/sum_of_gaussians.h"
#include "dermis/sss/profiles/tabulated.h"

namespace dermis::sss {

class RadialProfile {
 public:
  using Variant = std::variant<GaussianProfile, SumOfGaussiansProfile, CubicProfile, DipoleProfile, BurleyProfile,
                               TabulatedProfile>;

  RadialProfile() = default;  // a zero Gaussian: eval 0, albedo 0
  template <class P>
  requires std::is_constructible_v<Variant, P> RadialProfile(P profile) : v_(std::move(profile)) {}

  double eval(double r) const {
    return std::visit([r](const auto& p) { return p.eval(r); }, v_);
  }
  double sample_radius(double xi) const {
    return std::visit([xi](const auto& p) { return p.sample_radius(xi); }, v_);
  }
  double pdf_radius(double r) const {
    return std::visit([r](const auto& p) { return p.pdf_radius(r); }, v_);
  }
  double r_max() const {
    return std::visit([](const auto& p) { return p.r_max(); }, v_);
  }
  double r_max(double energy_fraction) const {
    return std::visit([energy_fraction](const auto& p) { return p.r_max(energy_fraction); }, v_);
  }
  double albedo() const {
    return std::visit([](const auto& p) { return p.albedo(); }, v_);
  }

  template <class P>
  const P* get_if() const {
    return std::get_if<P>(&v_);
  }
  const Variant& variant() const { return v_; }

 private:
  Variant v_;
};

// Three channels (R, G, B).
struct ProfileRGB {
  std::array<RadialProfile, 3> channel;
  const RadialProfile& operator[](int c) const { return channel[c]; }
  double r_max() const { return std::max(channel[0].r_max(), std::max(channel[1].r_max(), channel[2].r_max())); }
};

// Builders from what a user writes (all lengths in scene units).
ProfileRGB make_burley_rgb(RGB albedo, RGB mean_free_path,
                           BurleyParameterisation p = BurleyParameterisation::VolumeMeanFreePath);
ProfileRGB make_dipole_rgb(RGB albedo, RGB mean_free_path, double eta);
ProfileRGB make_dipole_rgb_from_coefficients(RGB sigma_a, RGB sigma_s, double g, double eta);
ProfileRGB make_cubic_rgb(RGB albedo, RGB radius);
ProfileRGB make_gaussian_rgb(RGB albedo, RGB variance);
// d'Eon & Luebke's skin (GPU Gems 3, Table 14-1), see sum_of_gaussians.h.
ProfileRGB make_skin_rgb(double scene_units_per_mm, RGB albedo = RGB(1.0f));
ProfileRGB make_tabulated_rgb(const std::shared_ptr<const ProfileTable>& table, RGB albedo, RGB mean_free_path);

// Profile families at l = 1 for ProfileTable (eta is a parameter of the dipole's).
ProfileFamily dipole_family(double eta);
ProfileFamily burley_family(BurleyParameterisation p = BurleyParameterisation::VolumeMeanFreePath);

}  // namespace dermis::sss
