// The weights of Langlands & Mertens' local/global split (seed 001; METHODS 3). The seed
// leaves w open; Dermis uses the smooth bump
//   w(r) = (1 - (r/alpha)^2)^2 on [0, alpha], 0 beyond;   wbar = 1 - w,
// with w(0) = 1, w(alpha) = 0, w'(0) = w'(alpha) = 0 (so wbar vanishes quadratically at
// r = 0, where the sparse cloud's nearest points would otherwise make splotches).
#pragma once

namespace dermis::sss::pointcloud {

// w(r): the share of the profile integrated over the local disk with E(x).
inline double local_weight(double r, double alpha) {
  if (!(r < alpha)) return 0.0;
  const double t = 1 - (r / alpha) * (r / alpha);
  return t * t;
}

// wbar(r) = 1 - w(r): the share summed over the points (alpha <= 0: every point whole).
inline double global_weight(double r, double alpha) { return 1.0 - local_weight(r, alpha); }

}  // namespace dermis::sss::pointcloud
