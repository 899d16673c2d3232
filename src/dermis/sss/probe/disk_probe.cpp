#include "dermis/sss/probe/disk_probe.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dermis::sss {

DiskProbeSampler::DiskProbeSampler(const ProfileRGB& profile, RGB channel_weights, ProbeAxisProbabilities axes) {
  const double a[3] = {axes.normal, axes.tangent, axes.bitangent};
  double axis_sum = 0;
  for (double p : a) {
    if (!(p >= 0) || !std::isfinite(p))
      throw std::invalid_argument("disk probe: axis probabilities must be finite and >= 0 (got " + std::to_string(p) +
                                  ")");
    axis_sum += p;
  }
  if (!(axis_sum > 0)) throw std::invalid_argument("disk probe: the axis probabilities are all zero");
  for (int i = 0; i < 3; ++i) axis_probability_[i] = a[i] / axis_sum;

  const auto q = normalised_channel_weights(channel_weights, "disk probe");
  for (int c = 0; c < 3; ++c) {
    if (q[c] == 0) continue;
    const RadialProfile& channel = profile[c];
    if (const auto* sum = channel.get_if<SumOfGaussiansProfile>()) {
      // One-sample MIS over the lobes of all channels (King et al. 2013, "weight MIS").
      for (int j = 0; j < sum->lobe_count(); ++j) {
        const double pj = q[c] * sum->lobe_probability(j);
        if (pj == 0) continue;
        Strategy& s = strategies_[count_++];
        s.probability = pj;
        s.lobe = j;
        s.lobe_profile = sum->lobe(j);
        s.r_max = s.lobe_profile.r_max();
      }
    } else {
      Strategy& s = strategies_[count_++];
      s.probability = q[c];
      s.channel = &channel;
      s.burley = channel.get_if<BurleyProfile>();
      s.r_max = channel.r_max();
    }
  }
  // Channels of one profile shape (a grey material's three, a Gaussian lobe that two
  // channels share) are one strategy: the same samples and the same density, a third of
  // the density's terms at every probe hit.
  int merged = 0;
  for (int i = 0; i < count_; ++i) {
    int j = 0;
    while (j < merged && !strategies_[j].samples_as(strategies_[i])) ++j;
    if (j < merged) {
      strategies_[j].probability += strategies_[i].probability;
      continue;
    }
    strategies_[merged++] = strategies_[i];
  }
  count_ = merged;
  double total = 0;
  for (int i = 0; i < count_; ++i) {
    if (!(strategies_[i].r_max > 0) || !std::isfinite(strategies_[i].r_max))
      throw std::invalid_argument("disk probe: a profile has no positive, finite r_max");
    total += strategies_[i].probability;
    cumulative_[i] = total;
    max_radius_ = std::max(max_radius_, strategies_[i].r_max);
  }
  for (int i = 0; i < count_; ++i) {
    strategies_[i].probability /= total;
    cumulative_[i] /= total;
  }
  cumulative_[count_ - 1] = 1;
}

int DiskProbeSampler::axis_of(double u) const {
  int axis = u < axis_probability_[0] ? 0 : (u < axis_probability_[0] + axis_probability_[1] ? 1 : 2);
  while (axis_probability_[axis] == 0) axis = (axis + 2) % 3;  // rounding at the last edge
  return axis;
}

int DiskProbeSampler::strategy_of(double u) const {
  const int i = int(std::upper_bound(cumulative_.begin(), cumulative_.begin() + count_, u) - cumulative_.begin());
  return std::min(i, count_ - 1);
}

DiskProbeSample DiskProbeSampler::sample(const ProbeFrame& frame, double u_axis, double u_strategy, double u_radius,
                                         double u_angle) const {
  return sample_chosen(frame, axis_of(u_axis), strategy_of(u_strategy), u_radius, u_angle);
}

DiskProbeSample DiskProbeSampler::sample(const ProbeFrame& frame, double u, double u_angle) const {
  // What is left of u in [lo, lo + p), rescaled to [0, 1) (kept below 1 against rounding).
  auto rest = [](double u, double lo, double p) { return std::clamp((u - lo) / p, 0.0, 0x1.fffffffffffffp-1); };
  const int axis = axis_of(u);
  const double axis_lo = axis == 0   ? 0.0
                         : axis == 1 ? axis_probability_[0]
                                     : axis_probability_[0] + axis_probability_[1];
  u = rest(u, axis_lo, axis_probability_[axis]);
  const int i = strategy_of(u);
  const double strategy_lo = i == 0 ? 0.0 : cumulative_[i - 1];
  return sample_chosen(frame, axis, i, rest(u, strategy_lo, cumulative_[i] - strategy_lo), u_angle);
}

DiskProbeSample DiskProbeSampler::sample_chosen(const ProbeFrame& frame, int axis, int strategy, double u_radius,
                                                double u_angle) const {
  DiskProbeSample out;
  out.axis = axis;
  out.strategy = strategy;
  const Strategy& s = strategies_[strategy];

  // The disk perpendicular to V, spanned by the two other frame axes.
  const Vec3d v = frame.axis(out.axis);
  const Vec3d u = frame.axis((out.axis + 1) % 3), w = frame.axis((out.axis + 2) % 3);
  const double r = std::min(s.sample_radius(u_radius), s.r_max);
  const double phi = 2 * kPiD * u_angle;
  const Vec3d disk_point = frame.p + (u * std::cos(phi) + w * std::sin(phi)) * r;
  // King et al. 2013, fig. 2: the chord along V of the sphere of radius R_i around P.
  const double h = std::sqrt(std::max(0.0, s.r_max * s.r_max - r * r));
  out.segment = {disk_point + v * h, -v, 2 * h};
  out.disk_radius = r;
  return out;
}

bool DiskProbeSampler::Strategy::samples_as(const Strategy& o) const {
  if (lobe >= 0 || o.lobe >= 0)
    return lobe >= 0 && o.lobe >= 0 && lobe_profile.variance() == o.lobe_profile.variance() && r_max == o.r_max;
  if (burley && o.burley)
    return burley->shape_length() == o.burley->shape_length() && burley->kept_fraction() == o.burley->kept_fraction();
  return channel == o.channel;
}

double DiskProbeSampler::pdf_disk(double r, double d) const {
  // Radial pdf to area density on the disk: dA = r dr dphi, phi uniform (King et al. 2013,
  // eq. 1), r kept off 0 by 1e-12 of each strategy's radius.
  if (!(r >= 1e-12 * max_radius_)) {
    double sum = 0;
    for (int i = 0; i < count_; ++i) {
      const Strategy& s = strategies_[i];
      if (d > s.r_max) continue;
      const double rc = std::max(r, 1e-12 * s.r_max);
      sum += s.probability * s.pdf_radius(rc) / (2 * kPiD * rc);
    }
    return sum;
  }
  double sum = 0;  // the same with one division: r >= 1e-12 R_i for every strategy
  for (int i = 0; i < count_; ++i) {
    const Strategy& s = strategies_[i];
    if (d > s.r_max) continue;
    sum += s.probability * s.pdf_radius(r);
  }
  return sum / (2 * kPiD * r);
}

double DiskProbeSampler::pdf_area(const ProbeFrame& frame, Vec3d x, Vec3d n_x) const {
  const Vec3d offset = x - frame.p;
  const double d2 = length_squared(offset);
  if (d2 > max_radius_ * max_radius_) return 0;
  const double d = std::sqrt(d2);
  double pdf = 0;
  for (int a = 0; a < 3; ++a) {
    if (axis_probability_[a] == 0) continue;
    const Vec3d v = frame.axis(a);
    const double along = dot(offset, v);
    const double cos_v = std::abs(dot(v, n_x));
    if (cos_v == 0) continue;
    const double r_a = std::sqrt(std::max(0.0, d2 - along * along));
    // Balance heuristic over axes (King et al. 2013, "Axis MIS"): the disk area density
    // times the projection Jacobian |V_a . n_x| from the disk to the surface.
    pdf += axis_probability_[a] * cos_v * pdf_disk(r_a, d);
  }
  return pdf;
}

}  // namespace dermis::sss
