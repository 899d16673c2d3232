// Probe lines through spheres (the Cycles page, seed 002_..., after Walter et al. 2012,
// App. B; METHODS 2.2; docs/probe-sampling.md).
//
// One probe: a channel c with probability q_c; a sphere radius rho from the channel's
// table p_c(rho) ∝ -rho^2 R_c'(rho) on [0, rho_max]; two independent uniform points on
// the sphere of radius rho around P; the chord between them. A chord between two uniform
// points of a sphere crosses any surface element dA inside the sphere, whatever its
// position and orientation, 1/(2 pi rho^2) times per unit area on average (derivation in
// docs/probe-sampling.md), so a surface point at distance d from P is found with area
// density
//   q(d) = sum_c q_c q_c(d),  q_c(d) = int_d^rho_max p_c(rho) / (2 pi rho^2) d rho,
// and with p ∝ -rho^2 R': q_c(d) ∝ R_c(d) - R_c(rho_max). The estimator is
// sum_hits R(d) / q(d) per line (unbiased), or the page's retry variant.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/core/rng.h"
#include "dermis/sss/probe/probe_types.h"
#include "dermis/sss/profiles/profile.h"

namespace dermis::sss {

// The sphere-radius distribution of one channel and its hit density q(d), as tables.
// Bins rho_k = rho_max (k / n)^2 (finer near P, where the profiles are steep); p is
// piecewise constant with bin masses int -rho^2 R' d rho, computed by parts as
// a^2 R(a) - b^2 R(b) + int_a^b 2 rho R d rho (16-point Gauss-Legendre), so no derivative
// of R is needed. q(d) is then the EXACT density of this piecewise-constant p
// (closed form per bin), so sampler and pdf agree to rounding; its agreement with
// R(d) - R(rho_max) is the table's accuracy (tested).
class SphereLineTable {
 public:
  static constexpr int kDefaultBins = 1024;

  SphereLineTable() = default;
  // rho_max <= 0 means the profile's r_max(). Throws on bins < 2 or a non-finite rho_max.
  // A profile with zero albedo gives an empty table (is_empty()).
  explicit SphereLineTable(const RadialProfile& profile, double rho_max = 0, int bins = kDefaultBins);

  bool is_empty() const { return empty_; }
  double rho_max() const { return rho_max_; }
  int bins() const { return bins_; }
  // int_0^rho_max R(r) 2 pi r dr (the plane energy the unbiased estimator recovers).
  double energy_within() const { return energy_; }

  // Sphere radius for u in [0, 1), distributed as pdf_radius.
  double sample_radius(double u) const;
  // The piecewise-constant density p(rho) on [0, rho_max].
  double pdf_radius(double rho) const;
  // q(d) = int_d^rho_max p(rho) / (2 pi rho^2) d rho (Walter et al. 2012, App. B); 0 for d >= rho_max.
  double hit_density(double d) const;

 private:
  double edge(int k) const {
    const double s = double(k) / bins_;
    return rho_max_ * s * s;
  }
  int bin_of(double rho) const;

  double rho_max_ = 0;
  int bins_ = 0;
  bool empty_ = true;
  double energy_ = 0;
  std::vector<double> density_;  // p_k on bin k
  std::vector<double> cdf_;      // n + 1 entries, cdf_[0] = 0, cdf_[n] = 1
  std::vector<double> tail_;     // tail_[k] = q(rho_k), n + 1 entries, tail_[n] = 0
};

// Three channel tables on one common rho_max (the largest channel r_max), built once
// per material (about 16 n profile evaluations per channel).
struct SphereLineTablesRGB {
  std::array<SphereLineTable, 3> channel;
  SphereLineTablesRGB() = default;
  explicit SphereLineTablesRGB(const ProfileRGB& profile, int bins = SphereLineTable::kDefaultBins);
};

struct SphereLineSample {
  ProbeSegment segment;  // the chord, inside the sphere
  int channel = 0;
  double sphere_radius = 0;
};

// Outcome of the retry loop (the page's variant): `lines` traced; `hits` on the last one
// (0: none of kRetryMaxLines hit, stay at P); `chosen` in [0, hits) the hit to use.
struct SphereLineRetry {
  int lines = 0;
  int hits = 0;
  int chosen = -1;
  ProbeSegment segment;
};

class SphereLineSampler {
 public:
  static constexpr int kRetryMaxLines = 8;  // the Cycles page: "We set the limit to 8"

  // `tables` must outlive the sampler. Channels with empty tables get weight 0.
  // Throws std::invalid_argument when no channel with a non-empty table has weight > 0.
  // radius_scale s_c > 0 stretches channel c's table by s_c: radii s_c rho, hit density
  // q_c(d / s_c) / s_c^2 (the density of s_c rho for rho ~ p_c). It lets one table serve
  // a family of profiles R_s(r) = R(r / s) / s^2 exactly, and any other profile of
  // similar reach unbiasedly (textured parameters: no table per entry point). Allocates
  // nothing: a sampler may live on the stack.
  SphereLineSampler(const SphereLineTablesRGB& tables, RGB channel_weights = RGB(1.0f),
                    std::array<double, 3> radius_scale = {1, 1, 1});

  // u_channel, u_radius in [0, 1); u_first, u_second in [0, 1)^2 pick the chord's ends.
  SphereLineSample sample(Vec3d p, double u_channel, double u_radius, Vec2d u_first, Vec2d u_second) const;
  // The same with one number cut into the channel and, what is left of it rescaled to
  // [0, 1), the radius: a stratified u gives every channel stratified radii
  // (DiskProbeSampler::sample's two-number form).
  SphereLineSample sample(Vec3d p, double u, Vec2d u_first, Vec2d u_second) const;

  // Area density of crossings at a surface point x (any orientation): sum_c q_c q_c(|x - P|).
  double pdf_area(Vec3d p, Vec3d x) const;

  double channel_probability(int c) const { return q_[c]; }
  double max_radius() const { return max_radius_; }

  // The page's retry variant: up to kRetryMaxLines lines until one has a hit.
  // count_hits(const ProbeSegment&) -> int traces a chord, keeps its crossings and
  // returns their number; the chosen one is picked uniformly. Weight of the chosen hit
  // at distance d: retry_weight(R_c(d), hits, pdf_area); with no hit, stay at P with
  // weight fallback_weight(c). Unbiased on a plane through P only (docs/probe-sampling.md).
  template <class Random, class CountHits>
  SphereLineRetry sample_retry(Vec3d p, Random& rng, CountHits&& count_hits) const {
    SphereLineRetry out;
    for (out.lines = 1; out.lines <= kRetryMaxLines; ++out.lines) {
      const double u0 = rng.uniform_double(), u1 = rng.uniform_double();
      const Vec2d a(rng.uniform_double(), rng.uniform_double()), b(rng.uniform_double(), rng.uniform_double());
      out.segment = sample(p, u0, u1, a, b).segment;
      out.hits = count_hits(out.segment);
      if (out.hits > 0) {
        out.chosen = std::min(int(rng.uniform_double() * out.hits), out.hits - 1);
        return out;
      }
    }
    out.lines = kRetryMaxLines;
    out.hits = 0;
    return out;
  }
  // k R(d) / (2 q(d)): a line through P hits a plane through P with probability 1/2 exactly.
  static double retry_weight(double profile_value, int hits, double pdf) {
    return pdf > 0 ? hits * profile_value / (2 * pdf) : 0.0;
  }
  // What the plane would have returned: the energy of channel c within its table's
  // rho_max (the tables' own profile: radius scales of 1).
  double fallback_weight(int c) const { return (*tables_).channel[c].energy_within(); }

 private:
  const SphereLineTablesRGB* tables_ = nullptr;
  std::array<double, 3> q_{};
  std::array<double, 3> scale_{1, 1, 1};
  double max_radius_ = 0;
};

}  // namespace dermis::sss
