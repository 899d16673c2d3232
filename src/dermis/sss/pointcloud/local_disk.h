// The local term of Langlands & Mertens' split (seed 001; METHODS 3):
//   M_local(x) = 2 pi E(x) int_0^alpha w(r) R(r) r dr,  w(r) = (1 - (r/alpha)^2)^2,
// tabulated once per profile channel over a log-spaced grid of disk radii alpha.
#pragma once

#include <array>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/sss/profiles/profile.h"

namespace dermis::sss::pointcloud {

// One channel: alpha -> 2 pi int_0^alpha w(r) R(r) r dr ("the local albedo": it tends to
// the profile's albedo as alpha -> infinity and to 0 as alpha -> 0).
class LocalDiskTable {
 public:
  static constexpr int kDefaultEntries = 512;
  // The grid spans [1e-4, 1e3] x the profile's median radius r_max(0.5), log-spaced.
  explicit LocalDiskTable(const RadialProfile& profile, int entries = kDefaultEntries);

  // Interpolated linearly in (ln alpha, ln value); outside the grid, direct quadrature.
  double local_albedo(double alpha) const;
  // The same value by adaptive Gauss-Kronrod quadrature on dyadic pieces of [0, alpha].
  double integrate_directly(double alpha) const;

  double alpha_min() const { return alpha_lo_; }
  double alpha_max() const { return alpha_hi_; }
  std::size_t memory_bytes() const { return log_value_.capacity() * sizeof(double); }

 private:
  RadialProfile profile_;
  double alpha_lo_ = 0, alpha_hi_ = 0, log_lo_ = 0, inv_step_ = 0;
  bool zero_ = false;              // a black channel: every value is 0
  std::vector<double> log_value_;  // ln(local albedo) at alpha_lo * exp(i / inv_step)
};

// The local albedo 2 pi int_0^alpha w(r) R(r) r dr of one profile at one alpha, without
// a table (a profile made per shading point, textured parameters): 16-point
// Gauss-Legendre on 40 dyadic pieces of [0, alpha] (about 650 evaluations), on each of
// which a profile singular or steep at r = 0 is smooth.
double local_albedo_of(const RadialProfile& profile, double alpha);

struct LocalDiskTableRGB {
  std::array<LocalDiskTable, 3> channel;
  explicit LocalDiskTableRGB(const ProfileRGB& profile, int entries = LocalDiskTable::kDefaultEntries);
  // The local term for irradiance E at x: E * local_albedo(alpha), per channel.
  RGB local_term(RGB irradiance, double alpha) const {
    return RGB(float(irradiance[0] * channel[0].local_albedo(alpha)),
               float(irradiance[1] * channel[1].local_albedo(alpha)),
               float(irradiance[2] * channel[2].local_albedo(alpha)));
  }
  std::size_t memory_bytes() const {
    return channel[0].memory_bytes() + channel[1].memory_bytes() + channel[2].memory_bytes();
  }
};

}  // namespace dermis::sss::pointcloud
