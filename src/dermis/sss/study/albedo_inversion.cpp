#include "dermis/sss/study/albedo_inversion.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "dermis/sss/halfspace/chandrasekhar.h"
#include "dermis/sss/halfspace/halfspace.h"
#include "dermis/sss/walk/monotone_hermite.h"

namespace dermis::sss {

namespace {

void check_surface_albedo(double a) {
  if (!(a >= 0 && a <= 1))
    throw std::invalid_argument("surface albedo must lie in [0, 1] (got " + std::to_string(a) + ")");
}

// A as a function of u = sqrt(1 - alpha), index-matched.
double surface_albedo_of_u(double u) { return surface_albedo_index_matched(1 - u * u); }

}  // namespace

double surface_albedo_index_matched(double alpha) {
  if (!(alpha >= 0 && alpha <= 1))
    throw std::invalid_argument("single-scattering albedo must lie in [0, 1] (got " + std::to_string(alpha) + ")");
  const HFunction h(alpha);
  return halfspace_albedo_collimated(h, 1.0);  // 1 - H(1) sqrt(1 - alpha) (Chandrasekhar 1950, ch. V)
}

double surface_albedo_index_matched_tabulated(double alpha) {
  static const std::vector<HermiteNode> nodes = [] {
    constexpr int n = kSurfaceAlbedoNodes;
    constexpr double h = 1.0 / (n - 1);
    std::vector<HermiteNode> out(n);
    for (int k = 0; k < n; ++k) out[std::size_t(k)] = {k * h, surface_albedo_of_u(k * h * k * h), 0};
    for (int k = 0; k < n; ++k) {  // central differences; one-sided (second order) at the ends
      const auto y = [&](int i) { return out[std::size_t(i)].y; };
      out[std::size_t(k)].m = k == 0       ? (-3 * y(0) + 4 * y(1) - y(2)) / (2 * h)
                              : k == n - 1 ? (3 * y(n - 1) - 4 * y(n - 2) + y(n - 3)) / (2 * h)
                                           : (y(k + 1) - y(k - 1)) / (2 * h);
    }
    return out;
  }();
  const double t = std::sqrt(std::sqrt(1 - std::clamp(alpha, 0.0, 1.0)));
  const int k = std::min(int(t * (kSurfaceAlbedoNodes - 1)), kSurfaceAlbedoNodes - 2);
  return hermite_between(nodes[std::size_t(k)], nodes[std::size_t(k) + 1], t);
}

double single_scattering_albedo_index_matched(double a) {
  check_surface_albedo(a);
  if (a == 0) return 0;
  if (a == 1) return 1;
  // A(u) decreases from 1 (u = 0) to 0 (u = 1).
  double lo = 0, hi = 1;
  for (int it = 0; it < 200 && hi - lo > 1e-16; ++it) {
    const double mid = 0.5 * (lo + hi);
    const double f = surface_albedo_of_u(mid) - a;
    if (std::abs(f) <= 1e-13) return 1 - mid * mid;
    (f > 0 ? lo : hi) = mid;
  }
  const double u = 0.5 * (lo + hi);
  return 1 - u * u;
}

SimulatedInversion single_scattering_albedo_simulated(double a, double eta, uint64_t paths, uint64_t seed) {
  check_surface_albedo(a);
  if (!(eta > 0) || !std::isfinite(eta))
    throw std::invalid_argument("eta must be positive (got " + std::to_string(eta) + ")");
  if (paths < 1) throw std::invalid_argument("the inversion needs at least one path");
  SimulatedInversion out;
  const double alpha_matched = single_scattering_albedo_index_matched(a);
  if (eta == 1.0 || a == 0 || a == 1) {
    out.single_scattering_albedo = alpha_matched;
    out.surface_albedo = a;
    return out;
  }
  auto simulate = [&](double u, double* stderr_out) {
    HalfspaceConfig c;
    c.albedo = 1 - u * u;
    c.eta = eta;
    c.paths = paths;
    c.seed = seed;
    c.bins = RadialBins::linear(1.0, 1);
    const HalfspaceResult r = simulate_halfspace(c);
    ++out.simulations;
    *stderr_out = r.albedo_per_entering_stderr();
    return r.albedo_per_entering();
  };
  // A(u) decreases in u. Bracket: u = 0 gives A = 1 (no absorption) exactly; the
  // index-matched answer's u is an upper end when the boundary keeps light inside
  // (eta != 1 only lengthens paths), widened until the simulated A falls below the target.
  double u_lo = 0, f_lo = 1 - a;
  double u_hi = std::sqrt(1 - alpha_matched), se_hi = 0;
  double f_hi = simulate(u_hi, &se_hi) - a;
  while (f_hi > 0 && u_hi < 1) {
    u_lo = u_hi, f_lo = f_hi;
    u_hi = std::min(1.0, 2 * u_hi);
    f_hi = simulate(u_hi, &se_hi) - a;
  }
  double u = u_hi, f = f_hi, se = se_hi;
  int side = 0;  // Illinois: which end was kept last time
  for (int it = 0; it < 40; ++it) {
    if (std::abs(f) <= se || u_hi - u_lo < 1e-12) break;
    u = (u_lo * f_hi - u_hi * f_lo) / (f_hi - f_lo);
    f = simulate(u, &se) - a;
    if (f > 0) {
      u_lo = u, f_lo = f;
      if (side == +1) f_hi *= 0.5;
      side = +1;
    } else {
      u_hi = u, f_hi = f;
      if (side == -1) f_lo *= 0.5;
      side = -1;
    }
  }
  out.single_scattering_albedo = 1 - u * u;
  out.surface_albedo = f + a;
  out.surface_albedo_stderr = se;
  return out;
}

}  // namespace dermis::sss
