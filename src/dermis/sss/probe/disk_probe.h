// Disk-projection probe sampling with axis MIS and channel/lobe MIS (King et al. 2013,
// seed 000_...; METHODS 2.1; docs/probe-sampling.md).
//
// One probe: choose an axis V in {N, T, B} with probability P_a, a strategy i (a channel,
// or one Gaussian lobe of a sum-of-Gaussians channel) with probability q_i, a radius r
// from strategy i's radial pdf and phi uniform; the disk point D = P + r (cos phi U +
// sin phi W) lies in the plane through P perpendicular to V. The segment runs along -V
// through strategy i's OWN sphere of radius R_i = r_max_i around P: from D + h V to
// D - h V, h = sqrt(R_i^2 - r^2). Every crossing x of the segment with the surface is a
// candidate, with the area density of the whole procedure (balance heuristic over axes
// and strategies, King et al. 2013, sec. "Axis and Weight MIS"):
//   pdf_area(x, n_x) = sum_a P_a |V_a . n_x| sum_i q_i [|x - P| <= R_i] pdf_i(r_a) / (2 pi r_a),
// r_a = |(x - P) - ((x - P) . V_a) V_a|. The estimator is sum_hits R(|x - P|) / pdf_area(x)
// (or one of k hits picked uniformly, times k).
//
// Why per-strategy spheres (and not one R_m for all): a narrow skin lobe then probes a
// short segment, so it does not collect far hits that only the wide lobes could weight
// well; the density above accounts for it exactly.
#pragma once

#include <array>

#include "dermis/core/rgb.h"
#include "dermis/sss/probe/probe_types.h"
#include "dermis/sss/profiles/profile.h"

namespace dermis::sss {

// Probabilities of probing along N, T and B (normalised on construction).
struct ProbeAxisProbabilities {
  double normal = 0.5, tangent = 0.25, bitangent = 0.25;
  // The seed's eq. (1): N only.
  static ProbeAxisProbabilities single_axis() { return {1, 0, 0}; }
};

// What one sample chose (for the renderer's statistics and the tests).
struct DiskProbeSample {
  ProbeSegment segment;
  int axis = 0;            // 0 = N, 1 = T, 2 = B
  int strategy = 0;        // index into the strategy list
  double disk_radius = 0;  // r
};

class DiskProbeSampler {
 public:
  // One strategy per channel, or per lobe for sum-of-Gaussians channels: 3 x kMaxLobes.
  static constexpr int kMaxStrategies = 3 * SumOfGaussiansProfile::kMaxLobes;

  // `profile` must outlive the sampler. channel_weights: the probability of sampling with
  // each channel's profile is proportional to them (e.g. throughput x albedo); lobes of a
  // sum of Gaussians share their channel's weight by lobe weight. Channels with weight 0
  // are never sampled (and then their hits only count through the other channels).
  // Throws std::invalid_argument on negative, non-finite or all-zero weights/probabilities.
  DiskProbeSampler(const ProfileRGB& profile, RGB channel_weights = RGB(1.0f), ProbeAxisProbabilities axes = {});

  // Four uniforms in [0, 1): axis, strategy, radius, angle.
  DiskProbeSample sample(const ProbeFrame& frame, double u_axis, double u_strategy, double u_radius,
                         double u_angle) const;
  // Two: u chooses the axis, what is left of it (rescaled to [0, 1)) the strategy, and what
  // is left of that the radius; u_angle the angle. The same density as the four-number
  // form; where u is stratified over a pixel's samples (the renderer's Sobol' points), so
  // is every (axis, strategy)'s set of radii, jointly with its angles (Cycles'
  // subsurface_disk remaps its disk number for the axis choice alike), where independent
  // numbers for the choices would give each strategy a random subset of the radii.
  DiskProbeSample sample(const ProbeFrame& frame, double u, double u_angle) const;

  // Area density of finding x (surface normal n_x, unit length, either orientation) with
  // one probe, summed over axes and strategies (see the file comment). Zero outside the
  // largest sphere.
  double pdf_area(const ProbeFrame& frame, Vec3d x, Vec3d n_x) const;

  // Area density on the disk perpendicular to one axis of the disk point at radius r,
  // for a hit at distance d from P: sum_i q_i [d <= R_i] pdf_i(r) / (2 pi r).
  double pdf_disk(double r, double d) const;

  int strategy_count() const { return count_; }
  double strategy_probability(int i) const { return strategies_[i].probability; }
  double strategy_radius(int i) const { return strategies_[i].r_max; }
  // The largest sphere radius in use: no candidate lies beyond it.
  double max_radius() const { return max_radius_; }
  double axis_probability(int a) const { return axis_probability_[a]; }

 private:
  struct Strategy {
    double probability = 0;
    double r_max = 0;
    const RadialProfile* channel = nullptr;  // used when lobe < 0
    const BurleyProfile* burley = nullptr;   // the channel's, when it is a Burley profile (no variant dispatch)
    GaussianProfile lobe_profile;            // used when lobe >= 0
    int lobe = -1;
    double sample_radius(double u) const {
      return lobe >= 0 ? lobe_profile.sample_radius(u) : burley ? burley->sample_radius(u) : channel->sample_radius(u);
    }
    double pdf_radius(double r) const {
      return lobe >= 0 ? lobe_profile.pdf_radius(r) : burley ? burley->pdf_radius(r) : channel->pdf_radius(r);
    }
    // Whether this strategy samples radii exactly as `o` does (the same profile shape): two
    // such strategies are one, with the sum of their probabilities.
    bool samples_as(const Strategy& o) const;
  };

  // The axis and the strategy a number in [0, 1) chooses (by the cumulative probabilities).
  int axis_of(double u) const;
  int strategy_of(double u) const;
  // The probe of a chosen axis and strategy from the radius and angle numbers.
  DiskProbeSample sample_chosen(const ProbeFrame& frame, int axis, int strategy, double u_radius, double u_angle) const;

  std::array<Strategy, kMaxStrategies> strategies_{};
  std::array<double, kMaxStrategies> cumulative_{};
  int count_ = 0;
  std::array<double, 3> axis_probability_{};
  double max_radius_ = 0;
};

}  // namespace dermis::sss
