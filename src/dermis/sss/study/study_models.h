// The models the Christensen-Burley study compares with the brute-force reference, all
// at mean free path l = 1 and surface albedo A (Christensen & Burley 2015; METHODS 1.3-1.5).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "dermis/sss/profiles/tabulated.h"

namespace dermis::sss {

struct StudyModel {
  std::string key;                       // CSV column name, e.g. "cb_volume_mfp"
  std::string label;                     // for tables and plots
  std::function<double(double r)> eval;  // R(r) at l = 1
};

// Burley's unfitted profile, w = A and s = 1: R(r) = A (e^{-r} + e^{-r/3}) / (8 pi r)
// at l = 1 (Christensen & Burley 2015, eq. 1 with w = A, s = 1); it integrates to A.
double burley_unfitted(double albedo, double r);

// The table the "tabulated" model reads: built from the dipole family at this eta
// (dipole_family(eta) with the default ProfileTableOptions), as the Cycles page tabulates
// a dipole-type profile (002_...; METHODS 1.5).
std::shared_ptr<const ProfileTable> study_profile_table(double eta);

// In order: burley_s1 (w = A, s = 1), cb_volume_mfp (s = 1.85 - A + 7|A - 0.8|^3),
// cb_seed_text (s = 1.85 - A + 7(0.8 - A)^3), dipole (Jensen et al. 2001 from A, l = 1, eta),
// tabulated (the table above at A, l = 1).
std::vector<StudyModel> study_models(double albedo, double eta, const std::shared_ptr<const ProfileTable>& table);

// The annulus mean of R over [lo, hi): int_lo^hi R 2 pi r dr / (pi (hi^2 - lo^2)), by
// 16-point Gauss-Legendre on 4 equal pieces in ln r (in r for lo = 0): the quantity a
// radial bin of the simulator estimates.
double annulus_mean(const std::function<double(double)>& R, double lo, double hi);

}  // namespace dermis::sss
