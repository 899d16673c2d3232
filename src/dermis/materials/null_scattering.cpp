#include "dermis/materials/null_scattering.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "dermis/materials/free_flight.h"

namespace dermis {

namespace {

// The channels' densities are carried up to a common factor, which cancels in the balance
// heuristic: brought back near 1 when they drift toward the ends of float's range.
void renormalise(RGB& a) {
  const float m = a.max();
  if (m > 0 && (m < 1e-20f || m > 1e20f)) a *= 1 / m;
}

}  // namespace

NullScatteringFlight sample_null_scattering_flight(const GridMediumView& m, const Ray& ray, float t_max,
                                                   const RGB& beta, const RGB& preference, float u_channel, Rng& rng,
                                                   Absorption absorption) {
  NullScatteringFlight f;
  RGB q;
  float qsum = 0;
  for (int c = 0; c < 3; ++c) qsum += q[c] = std::abs(beta[c]) * preference[c];
  if (!(qsum > 0)) return f;
  q /= qsum;
  const int c = u_channel < q[0] ? 0 : (u_channel < q[0] + q[1] ? 1 : 2);
  auto mixture = [&q](const RGB& x) { return q[0] * x[0] + q[1] * x[1] + q[2] * x[2]; };

  // a[k]: channel k's density of the tentative collisions and events drawn so far, each
  // collision at distance s in a cell of majorant m_k contributing T_k = e^(-m_k s) times
  // sigma_n,k (null) or sigma_s,k (scattering); the null-scattering integrand of channel k
  // is the same product (Miller et al. 2019 eq. 18), so a channel's weight is
  // a[k] / sum_j q_j a[j] (Veach 1997 eq. 9.10).
  RGB a(1);
  MajorantTraversal cells(m, ray, t_max);
  MajorantSegment seg;
  while (cells.next(seg)) {
    const float majorant = seg.sigma_maj[c];
    float t = seg.t0;
    while (majorant > 0) {
      const float step = exponential_quantile(rng.uniform()) / majorant;
      if (!(t + step < seg.t1)) break;
      if (f.null_collisions >= kMaxTentativeCollisions) {
        f.stalled = true;
        return f;
      }
      t += step;
      const RGB tr = exp(seg.sigma_maj * -step);
      // In a uniform cell the coefficients are known without a look-up (the same values).
      const MediumCoefficients k = seg.exact && !m.emissive
                                       ? MediumCoefficients{m.sigma_a_unit * seg.density, m.sigma_s_unit * seg.density}
                                       : m.at(ray.o + ray.d * t);
      ++f.null_collisions;
      if (m.emissive) {
        // sigma_a Le at a tentative collision, whatever its event: channel k's density of the
        // collision is a[k] T_k m_k, its integrand a[k] T_k sigma_a,k Le_k (Miller et al. 2019 eq. 18).
        const float pdf = mixture(a * tr * seg.sigma_maj);
        if (pdf > 0) f.emitted += a * tr * k.sigma_a * k.Le / pdf;
      }
      const float u = rng.uniform();
      const float p_absorb = k.sigma_a[c] / majorant, p_scatter = k.sigma_s[c] / majorant;
      const bool weighted = absorption == Absorption::Weighted;
      if (!weighted && u < p_absorb) return f;  // absorbed: the path ends
      if (u < p_absorb + p_scatter) {
        // Channel k's integrand a[k] T_k sigma_s,k; its density a[k] T_k sigma_s,k (analog) or
        // a[k] T_k sigma_t,k (weighted: every real collision scatters).
        const RGB fk = a * tr * k.sigma_s;
        const float pdf = mixture(weighted ? a * tr * (k.sigma_a + k.sigma_s) : fk);
        if (!(pdf > 0)) return f;
        f.valid = f.scattered = true;
        f.t = t;
        f.weight = fk / pdf;
        return f;
      }
      RGB sigma_n;
      for (int j = 0; j < 3; ++j) sigma_n[j] = std::max(seg.sigma_maj[j] - k.sigma_a[j] - k.sigma_s[j], 0.0f);
      a *= tr * sigma_n;
      if (!(mixture(a) > 0)) return f;
      renormalise(a);
    }
    a *= exp(seg.sigma_maj * -(seg.t1 - t));
    if (!(mixture(a) > 0)) return f;
    renormalise(a);
  }
  f.valid = true;
  f.t = t_max;
  f.weight = a / mixture(a);
  return f;
}

RGB ratio_tracking_transmittance(const GridMediumView& m, const Ray& ray, float t_max, Rng& rng, bool* stalled) {
  RGB tr(1);
  RGB depth(0);  // the optical depth of the uniform stretches not yet multiplied into tr
  // Russian roulette once the estimate falls below 5 %; the uniform stretches' depth is first
  // folded in (one exp for several cells) when it alone would bring it there.
  auto roulette = [&](bool fold) {
    if (fold) {
      for (int j = 0; j < 3; ++j) tr[j] *= std::exp(-depth[j]);
      depth = RGB(0);
    }
    if (tr.max() >= 0.05f) return false;
    if (rng.uniform() < 0.75f) return true;
    tr /= 0.25f;
    return false;
  };
  int collisions = 0;
  MajorantTraversal cells(m, ray, t_max);
  MajorantSegment seg;
  while (cells.next(seg)) {
    const float majorant = seg.sigma_maj.max();
    if (!(majorant > 0)) continue;
    if (seg.exact) {  // a uniform stretch: its transmittance in closed form (Beer-Lambert), exact
      depth += seg.sigma_maj * (seg.t1 - seg.t0);
      if (std::min({depth[0], depth[1], depth[2]}) > 3 && roulette(true)) return RGB(0);  // exp(-3) < 5 %
      continue;
    }
    for (float t = seg.t0;;) {
      const float next = t + exponential_quantile(rng.uniform()) / majorant;
      if (!(next < seg.t1)) break;
      if (++collisions >= kMaxTentativeCollisions) {
        if (stalled) *stalled = true;
        return RGB(0);
      }
      t = next;
      const MediumCoefficients k = m.at(ray.o + ray.d * t);
      for (int j = 0; j < 3; ++j) tr[j] *= std::max(1 - (k.sigma_a[j] + k.sigma_s[j]) / majorant, 0.0f);
      if (roulette(false)) return RGB(0);
    }
  }
  for (int j = 0; j < 3; ++j) tr[j] *= std::exp(-depth[j]);
  return tr;
}

Rng tracking_rng(float u, const Ray& ray) {
  auto bits = [](Vec3 v) {
    return mix64(std::bit_cast<uint32_t>(v.x) ^ (uint64_t(std::bit_cast<uint32_t>(v.y)) << 21) ^
                 (uint64_t(std::bit_cast<uint32_t>(v.z)) << 42));
  };
  return Rng(std::bit_cast<uint32_t>(u), bits(ray.o), bits(ray.d));
}

}  // namespace dermis
