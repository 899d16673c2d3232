#include "dermis/sss/probe/sphere_lines.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "dermis/sss/profiles/quadrature.h"

namespace dermis::sss {

SphereLineTable::SphereLineTable(const RadialProfile& profile, double rho_max, int bins) {
  if (bins < 2) throw std::invalid_argument("sphere-line table: at least 2 bins (got " + std::to_string(bins) + ")");
  rho_max_ = rho_max > 0 ? rho_max : profile.r_max();
  if (!(rho_max_ > 0) || !std::isfinite(rho_max_))
    throw std::invalid_argument("sphere-line table: rho_max must be positive and finite (got " +
                                std::to_string(rho_max_) + ")");
  bins_ = bins;
  density_.assign(bins, 0.0);
  cdf_.assign(bins + 1, 0.0);
  tail_.assign(bins + 1, 0.0);
  if (profile.albedo() == 0) return;  // empty: never sampled

  // Bin masses int_a^b -rho^2 R'(rho) d rho, by parts: a^2 R(a) - b^2 R(b) + int_a^b 2 rho R d rho
  // (so that p(rho) ∝ -rho^2 R'(rho), the Cycles page's "multiple overlapping spheres").
  std::vector<double> mass(bins);
  double total = 0, energy_over_pi = 0;
  double r_a = 0;  // a^2 R(a) at the current lower edge (0 at rho = 0)
  for (int k = 0; k < bins; ++k) {
    const double a = edge(k), b = edge(k + 1);
    const double r_b = b * b * profile.eval(b);
    const double e = gauss_legendre_16([&](double r) { return 2 * r * profile.eval(r); }, a, b);
    mass[k] = std::max(0.0, r_a - r_b + e);  // clamps rounding where R is flat
    total += mass[k];
    energy_over_pi += e;
    r_a = r_b;
  }
  if (!(total > 0) || !std::isfinite(total))
    throw std::invalid_argument("sphere-line table: the profile has no decreasing part on [0, rho_max]");
  energy_ = kPiD * energy_over_pi;
  empty_ = false;
  for (int k = 0; k < bins; ++k) {
    density_[k] = mass[k] / total / (edge(k + 1) - edge(k));
    cdf_[k + 1] = cdf_[k] + mass[k] / total;
  }
  cdf_[bins] = 1;
  // q(rho_k) = sum_{j >= k} p_j (1/rho_j - 1/rho_{j+1}) / (2 pi): the exact integral of the
  // piecewise-constant p against 1 / (2 pi rho^2) (Walter et al. 2012, App. B).
  for (int k = bins - 1; k >= 1; --k)
    tail_[k] = tail_[k + 1] + density_[k] * (1 / edge(k) - 1 / edge(k + 1)) / (2 * kPiD);
  tail_[0] = tail_[1];  // unused: q is unbounded near P when p_0 > 0 (see hit_density)
}

int SphereLineTable::bin_of(double rho) const {
  int k = std::clamp(int(bins_ * std::sqrt(rho / rho_max_)), 0, bins_ - 1);
  while (k > 0 && edge(k) > rho) --k;
  while (k < bins_ - 1 && edge(k + 1) <= rho) ++k;
  return k;
}

double SphereLineTable::sample_radius(double u) const {
  const int k = std::clamp(int(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin()) - 1, 0, bins_ - 1);
  const double width = cdf_[k + 1] - cdf_[k];
  const double t = width > 0 ? std::clamp((u - cdf_[k]) / width, 0.0, 1.0) : 0.5;
  return edge(k) + t * (edge(k + 1) - edge(k));
}

double SphereLineTable::pdf_radius(double rho) const {
  if (empty_ || rho < 0 || rho > rho_max_) return 0;
  return density_[bin_of(rho)];
}

double SphereLineTable::hit_density(double d) const {
  if (empty_ || d >= rho_max_) return 0;
  d = std::max(d, 1e-12 * rho_max_);  // a hit at P itself has measure zero; keep q finite
  const int k = bin_of(d);
  // q(d) = q(rho_{k+1}) + p_k (1/d - 1/rho_{k+1}) / (2 pi) (Walter et al. 2012, App. B).
  return tail_[k + 1] + density_[k] * (1 / d - 1 / edge(k + 1)) / (2 * kPiD);
}

SphereLineTablesRGB::SphereLineTablesRGB(const ProfileRGB& profile, int bins) {
  const double rho_max = profile.r_max();
  for (int c = 0; c < 3; ++c) channel[c] = SphereLineTable(profile[c], rho_max, bins);
}

SphereLineSampler::SphereLineSampler(const SphereLineTablesRGB& tables, RGB channel_weights,
                                     std::array<double, 3> radius_scale)
    : tables_(&tables), scale_(radius_scale) {
  RGB w = channel_weights;
  for (int c = 0; c < 3; ++c) {
    if (!(scale_[c] > 0) || !std::isfinite(scale_[c]))
      throw std::invalid_argument("sphere-line probe: radius scales must be positive and finite");
    if (tables.channel[c].is_empty() && w[c] >= 0) w[c] = 0;
  }
  q_ = normalised_channel_weights(w, "sphere-line probe");
  for (int c = 0; c < 3; ++c)
    if (q_[c] > 0) max_radius_ = std::max(max_radius_, scale_[c] * tables.channel[c].rho_max());
}

SphereLineSample SphereLineSampler::sample(Vec3d p, double u_channel, double u_radius, Vec2d u_first,
                                           Vec2d u_second) const {
  SphereLineSample out;
  int c = u_channel < q_[0] ? 0 : (u_channel < q_[0] + q_[1] ? 1 : 2);
  while (q_[c] == 0) c = (c + 2) % 3;  // rounding at the last edge
  out.channel = c;
  const double rho = scale_[c] * tables_->channel[c].sample_radius(u_radius);
  out.sphere_radius = rho;
  // Two independent uniform points on the sphere of radius rho (Walter et al. 2012, App. B).
  const Vec3d a = p + uniform_sphere_direction(u_first.x, u_first.y) * rho;
  const Vec3d b = p + uniform_sphere_direction(u_second.x, u_second.y) * rho;
  const double len = length(b - a);
  out.segment = {a, len > 0 ? (b - a) / len : Vec3d(0, 0, 1), len};
  return out;
}

SphereLineSample SphereLineSampler::sample(Vec3d p, double u, Vec2d u_first, Vec2d u_second) const {
  int c = u < q_[0] ? 0 : (u < q_[0] + q_[1] ? 1 : 2);
  while (q_[c] == 0) c = (c + 2) % 3;
  const double lo = c == 0 ? 0.0 : c == 1 ? q_[0] : q_[0] + q_[1];
  const double rest = std::clamp((u - lo) / q_[c], 0.0, 0x1.fffffffffffffp-1);
  // The channel's own interval's midpoint chooses it again in the four-number form.
  return sample(p, lo + q_[c] / 2, rest, u_first, u_second);
}

double SphereLineSampler::pdf_area(Vec3d p, Vec3d x) const {
  const double d = length(x - p);
  double pdf = 0;
  for (int c = 0; c < 3; ++c)
    if (q_[c] > 0) pdf += q_[c] * tables_->channel[c].hit_density(d / scale_[c]) / (scale_[c] * scale_[c]);
  return pdf;
}

}  // namespace dermis::sss
