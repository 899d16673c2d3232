// One step of the volumetric random walk: sample a flight (direction and free path)
// from a one-sample MIS mixture of classical and Dwivedi-guided sampling over all
// colour channels, and the per-channel weight that keeps the walk unbiased
// (Krivanek & d'Eon 2014; METHODS.md sections 4 and 5). The half-space simulator
// (N = 1, halfspace/walk_sampling.h) and the renderer's walk (N = 3, random_walk.h)
// are two drivers of this one implementation.
//
// Derivation. A flight starts at a point x (the entry point, or a collision where the
// path scatters) and ends at a collision at distance s, or passes the boundary at
// distance d. In channel k the physical measure of a flight from a scattering event is
//   f_k(w, s) = alpha_k p(w_in . w) sigma_t,k exp(-sigma_t,k s)           (collision)
//   F_k(w, d) = alpha_k p(w_in . w) exp(-sigma_t,k d)                     (passage)
// per steradian (and per unit length for a collision), p the HG phase function and
// alpha_k the single-scattering albedo of the scattering event (implicit capture).
// After entry (or a Fresnel reflection) the direction is given: drop alpha_k p(.).
// One-sample MIS picks a channel c with probability q_c (the current throughput,
// normalised), then the guided strategy with probability P_g, else the classical one
// (P_c = 1 - P_g), and samples the flight from it. The sampled flight has the mixture
// density (balance heuristic; Veach 1997, section 9.2.4: the weight of a one-sample
// balance-heuristic estimate is f / sum of all strategy densities weighted by their
// choice probabilities)
//   q(w, s) = sum_c q_c [P_c p(w_in . w) sigma_t,c exp(-sigma_t,c s)
//                        + P_g d_c(w) sigma'_c exp(-sigma'_c s)],
//   d_c(w) = beta p_c(u)/2pi + (1 - beta) p(w_in . w)   (guided direction density, per sr;
//   beta = 1 for isotropic scattering: the seed's Dwivedi pdf p_c(u), see
//   dwivedi_direction_fraction),
//   sigma'_c = sigma_t,c (1 - kappa_c u),   u = w . n (n: the principal axis, outward),
// and a sampled distance beyond the boundary (s > d) is the passage event, with
// probability  Q(w, d) = sum_c q_c [P_c p exp(-sigma_t,c d) + P_g d_c(w) exp(-sigma'_c d)]
// (each strategy's own probability of flying past: exponential tails). The walk
// multiplies channel k's throughput by f_k/q or F_k/Q: every (w, s) with f_k > 0 has
// q > 0 (the classical term, or, for P_c = 0, the guided density, positive everywhere),
// so E[weight x score] is the physical expectation: unbiased for any q_c, P_g, kappa.
// Simplifications used: p_c(u) sigma'_c = sigma_t,c kappa_c / L_c (dwivedi.h), so
// the guided collision density is finite even where p_c(u) is not; every term is
// a_i exp(b_i) and the weights are evaluated as ratios after subtracting max b_i, so
// no exponential overflows or underflows to 0/0.
// For isotropic scattering, P_g = 1 and one channel, the weight of a scattering step
// is exp(-kappa sigma_t u s): the product telescopes to I(x_0)/I(x_end), the
// zero-variance property.
//
// Backward guiding (GuideAxes): a guided flight in channel c uses a second principal
// axis, the outward normal where the object ends below the entry point, with
// probability b_c (back_share), else the entry normal. The guided term of the mixture
// becomes (1 - b_c) d_c(w; front) sigma'_c,front exp(-sigma'_c,front s) + b_c d_c(w; back)
// sigma'_c,back exp(-sigma'_c,back s); the argument above holds unchanged (b_c may depend
// on the point where the flight starts, not on the flight itself).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "dermis/core/frame.h"
#include "dermis/core/henyey_greenstein.h"
#include "dermis/core/rng.h"
#include "dermis/core/vec.h"
#include "dermis/sss/walk/dwivedi.h"

namespace dermis::sss {

enum class WalkSampling {
  Classical,  // analog free paths and phase-function directions
  Dwivedi,    // Dwivedi's guided pdfs only (P_guided = 1)
  Mis,        // one-sample MIS of both with choice probability P_guided
};

// "classical", "dwivedi" or "mis"; throws std::invalid_argument otherwise.
WalkSampling parse_walk_sampling(const std::string& text);
const char* walk_sampling_name(WalkSampling sampling);
// The guided choice probability of a strategy: 0, 1 or p_guided (validated in [0, 1]).
double guided_choice_probability(WalkSampling sampling, double p_guided);

// A sampled flight: unit direction, its cosines to the principal axes, the phase
// function value (per steradian) if it follows a scattering event, and the free path.
struct FlightProposal {
  Vec3d direction;
  double cos_axis = 0;  // to GuideAxes::front (the entry normal)
  double cos_back = 0;  // to GuideAxes::back (backward guiding only)
  double phase = 0;
  double distance = 0;  // may be +infinity (a guided flight straight out with sigma' = 0)
  bool scattered = false;
};

// The unit vector (cos phi, sin phi): the azimuth's sine and cosine in single precision (an
// angle error of 1e-7 rad), the pair normalised in double so that directions stay unit
// vectors over a walk's steps. Double-precision sincos and exp took a fifth of a walk
// step's time on the skin-like sphere.
inline std::pair<double, double> azimuth_unit(double phi) {
  const double c = std::cos(float(phi)), s = std::sin(float(phi));
  const double inv = 1 / std::sqrt(c * c + s * s);
  return {c * inv, s * inv};
}

// A new propagation direction at cosine cos_theta to `axis` (unit) and azimuth phi about it.
inline Vec3d direction_about(const Vec3d& axis, double cos_theta, double phi) {
  const double sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
  const auto [c, s] = azimuth_unit(phi);
  return Framed(axis).to_world({sin_theta * c, sin_theta * s, cos_theta});
}

// The principal axes of guided flights, outward normals of the planes whose Dwivedi
// importance exp(-kappa sigma_t D) (D the depth below the plane) is followed: `front`, the
// normal at the entry point (the seed's axis), and, for backward guiding, `back`, the
// normal where the object ends below the entry point (its far side); back_share[c] is the
// probability that a guided flight in channel c follows `back` (MixtureWalkStep::
// back_shares). Converts from a single frame: the seed's scheme, front only.
template <int N>
struct GuideAxes {
  Framed front;
  Framed back;
  std::array<double, N> back_share{};
  bool has_back = false;
  GuideAxes() = default;
  GuideAxes(const Framed& front_axis) : front(front_axis) {}  // NOLINT: implicit on purpose
};

template <int N>
class MixtureWalkStep {
 public:
  using Channels = std::array<double, N>;

  // sigma_t > 0 and albedo in [0, 1] per channel, g in (-1, 1), p_guided in [0, 1]
  // (the probability of the guided strategy), channel_preference >= 0 (the exponent k of
  // channel_probabilities); throws std::invalid_argument otherwise.
  const Channels& sigma_t() const { return sigma_t_; }
  const Channels& albedo() const { return albedo_; }
  double g() const { return g_; }
  MixtureWalkStep(const Channels& sigma_t, const Channels& albedo, double g, double p_guided,
                  double channel_preference = 0)
      : sigma_t_(sigma_t), albedo_(albedo), g_(g), any_guided_(p_guided > 0) {
    p_guided_.fill(p_guided);
    p_classical_.fill(1 - p_guided);
    auto fail = [](const std::string& m) { throw std::invalid_argument("random walk: " + m); };
    if (!(g > -1 && g < 1)) fail("HG anisotropy g must be in (-1, 1), got " + std::to_string(g));
    if (!(p_guided >= 0 && p_guided <= 1))
      fail("guided sampling probability must be in [0, 1], got " + std::to_string(p_guided));
    for (int c = 0; c < N; ++c) {
      if (!(sigma_t[c] > 0 && std::isfinite(sigma_t[c])))
        fail("extinction sigma_t must be positive and finite in every channel, got " + std::to_string(sigma_t[c]));
      if (!(albedo[c] >= 0 && albedo[c] <= 1))
        fail("single-scattering albedo sigma_s/sigma_t must be in [0, 1], got " + std::to_string(albedo[c]));
      if (p_guided > 0) guide_[c] = DwivediGuide(albedo[c], g);
    }
    if (!(channel_preference >= 0 && std::isfinite(channel_preference)))
      fail("channel preference exponent must be finite and >= 0, got " + std::to_string(channel_preference));
    for (int c = 0; c < N; ++c)
      channel_preference_[c] = std::pow(std::max(1 - albedo[c], kMinChannelAbsorption), -channel_preference);
    dwivedi_direction_fraction_ = dwivedi_direction_fraction(g);
  }

  // Fraction beta of guided directions drawn from Dwivedi's pdf; the rest follow the HG
  // phase function (only their free path is guided). Dwivedi's pdf ignores the phase
  // function: its weight ratio p_HG/p_dwivedi reaches (1 + |g|)/(1 - |g|)^2 in the forward
  // peak and compounds over the steps of a path into a heavy tail (measured in
  // docs/random-walk.md: g = 0.7 with beta = 1 is far worse than classical). beta = 1 at
  // g = 0 (the seed's scheme), falling linearly to 0 at |g| = kDwivediDirectionMaxG.
  static double dwivedi_direction_fraction(double g) { return std::max(0.0, 1 - std::abs(g) / kDwivediDirectionMaxG); }

  // The probabilities q of drawing each channel's flight (one-sample spectral MIS: any
  // q > 0 wherever a channel carries throughput keeps every channel unbiased, as proposal
  // and weights use the same q): q_c proportional to throughput_c (1 - albedo_c)^-k.
  // With k = 0, the throughput alone (the hero channel; METHODS.md sec. 5). A one-sample
  // mixture's channel c is estimated mostly by the walks drawn in it, so its variance goes
  // about as V_c / q_c, and the sum over channels is least for q_c proportional to
  // sqrt(V_c) (the optimal allocation of stratified sampling, Neyman 1934). A walk's
  // variance grows with its length, and the mean number of collisions before absorption
  // is 1 / (1 - albedo): k = 1/2 (WalkSettings) takes V_c proportional to that, which
  // lowers the variance where one channel's albedo is near 1 (skin: docs/random-walk.md).
  Channels channel_probabilities(const Channels& throughput) const {
    Channels q;
    double sum = 0;
    for (int c = 0; c < N; ++c) sum += q[c] = throughput[c] * channel_preference_[c];
    for (double& v : q) v /= sum;
    return q;
  }

  // The decay length of channel c's Dwivedi importance exp(-kappa sigma_t D), 1/(kappa
  // sigma_t): the depth scale over which guided flights pull toward the entry plane (its
  // walks' reach). Infinite without guides (a classical step) or at kappa = 0.
  double importance_length(int c) const {
    const double k = guide_[std::size_t(c)].kappa() * sigma_t_[std::size_t(c)];
    return any_guided_ && k > 0 ? 1 / k : std::numeric_limits<double>::infinity();
  }

  // The guided choice probability of a flight drawn in channel c.
  double p_guided(int c = 0) const { return p_guided_[std::size_t(c)]; }

  // The same step with channel c's flights guided with probability shares[c] instead: a
  // one-sample mixture whose choice probabilities differ by channel, P_g,c and
  // P_c,c = 1 - P_g,c in the derivation above (any in [0, 1] keeps the walk unbiased, as
  // proposal and weights use the same). Only for a step built with a guided share > 0
  // (its guides exist); throws std::invalid_argument otherwise.
  MixtureWalkStep with_guided_shares(const Channels& shares) const {
    if (!any_guided_) throw std::invalid_argument("random walk: per-channel guided shares need a guided step");
    MixtureWalkStep s = *this;
    s.any_guided_ = false;
    for (int c = 0; c < N; ++c) {
      if (!(shares[c] >= 0 && shares[c] <= 1))
        throw std::invalid_argument("random walk: guided sampling probability must be in [0, 1], got " +
                                    std::to_string(shares[c]));
      s.p_guided_[c] = shares[c];
      s.p_classical_[c] = 1 - shares[c];
      s.any_guided_ = s.any_guided_ || shares[c] > 0;
    }
    return s;
  }
  const DwivediGuide& guide(int c) const { return guide_[c]; }

  // Backward guiding: with the importance of a point taken as the sum of both planes'
  // eigenmodes, I = exp(-kappa sigma_t D_front) + exp(-kappa sigma_t D_back), sampling the
  // kernel times I picks each plane's guided pdf in proportion to its share of I (each
  // guided kernel integrates to the same constant by the eigenvalue equation), so
  //   b_c = I_back / I = 1 / (1 + exp(kappa_c sigma_t,c (D_back - D_front))),
  // depths of the flight's starting point below each plane. One half where kappa = 0.
  // For a slab (planes parallel, d apart) the summed importance is the diffusion solution
  // with both faces absorbing, cosh(kappa sigma_t (D_front - d/2)) / cosh(kappa sigma_t d/2).
  // Shares below 1/1000 are set to 0 (the back term would be at most 1/2000 of the
  // mixture, next to 1/2 for classical sampling): the walk then skips the back terms,
  // which cost a third of a step's exponentials. Any share keeps the walk unbiased, as
  // proposal and weight use the same one: so it is computed in single precision, and only
  // for the channels a flight may be drawn in (q_c > 0; the others' are never read: with
  // one colour channel per walk, one of three).
  Channels back_shares(double depth_front, double depth_back, const Channels& q) const {
    Channels b{};
    for (int c = 0; c < N; ++c) {
      if (!(q[c] > 0)) continue;
      const double x = guide_[c].kappa() * sigma_t_[c] * (depth_back - depth_front);
      if (x > kNegligibleBackExponent) continue;      // b = 0
      const float e = std::exp(-float(std::abs(x)));  // the logistic without overflow
      b[c] = x >= 0 ? double(e / (1 + e)) : double(1 / (1 + e));
    }
    return b;
  }

  // A flight along a given direction (after entry or a reflection): only its length is sampled.
  template <class Random>
  FlightProposal propose_flight(const Vec3d& direction, const GuideAxes<N>& axes, const Channels& q,
                                Random& rng) const {
    const int c = choose_channel(q, rng);
    FlightProposal f;
    f.direction = direction;
    f.cos_axis = dot(direction, axes.front.n);
    if (axes.has_back) f.cos_back = dot(direction, axes.back.n);
    const bool guided = choose_guided(c, rng);
    const bool back = guided && choose_back(axes, c, rng);
    f.distance = free_path(c, guided, back ? f.cos_back : f.cos_axis, rng);
    return f;
  }

  // A scattering event at the end of a flight along direction_in: new direction and flight.
  template <class Random>
  FlightProposal propose_scatter(const Vec3d& direction_in, const GuideAxes<N>& axes, const Channels& q,
                                 Random& rng) const {
    const int c = choose_channel(q, rng);
    const bool guided = choose_guided(c, rng);
    const bool back = guided && choose_back(axes, c, rng);
    FlightProposal f;
    f.scattered = true;
    const double phi = 2 * kPiD * rng.uniform_double();
    if (guided && (dwivedi_direction_fraction_ >= 1 || rng.uniform_double() < dwivedi_direction_fraction_)) {
      // Krivanek & d'Eon 2014: cosine from p(u) about the principal axis, azimuth uniform.
      const double u = guide_[c].sample_cos(rng.uniform_double());
      f.direction = (back ? axes.back : axes.front).to_world(local_direction(u, phi));
      f.phase = henyey_greenstein(dot(direction_in, f.direction), g_);
      if (back) {
        f.cos_back = u;
        f.cos_axis = dot(f.direction, axes.front.n);
      } else {
        f.cos_axis = u;
        if (axes.has_back) f.cos_back = dot(f.direction, axes.back.n);
      }
    } else {
      // Henyey & Greenstein 1941: the phase function about the propagation direction.
      const double cos_theta = sample_henyey_greenstein_cos(rng.uniform_double(), g_);
      f.direction = direction_about(direction_in, cos_theta, phi);
      f.cos_axis = dot(f.direction, axes.front.n);
      if (axes.has_back) f.cos_back = dot(f.direction, axes.back.n);
      f.phase = henyey_greenstein(cos_theta, g_);
    }
    f.distance = free_path(c, guided, back ? f.cos_back : f.cos_axis, rng);
    return f;
  }

  // Per-channel weight f_k / q of a flight that ends in a collision after f.distance;
  // axes and q as given to the proposal. A channel with q_c = 0 gets 0: it must carry no
  // throughput (as with channel_probabilities, where q_c is proportional to it).
  Channels collision_weights(const FlightProposal& f, const GuideAxes<N>& axes, const Channels& q) const {
    return weights(f, axes, f.distance, true, q);
  }
  // Per-channel weight F_k / Q of a flight that passes the boundary at distance d <= f.distance.
  Channels passage_weights(const FlightProposal& f, const GuideAxes<N>& axes, double d, const Channels& q) const {
    return weights(f, axes, d, false, q);
  }

 private:
  static Vec3d local_direction(double cos_theta, double phi) {
    const double sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
    const auto [c, s] = azimuth_unit(phi);
    return {sin_theta * c, sin_theta * s, cos_theta};
  }

  template <class Random>
  int choose_channel(const Channels& q, Random& rng) const {
    if constexpr (N == 1) {
      return 0;
    } else {
      double xi = rng.uniform_double();
      for (int c = 0; c < N - 1; ++c) {
        if (xi < q[c]) return c;
        xi -= q[c];
      }
      for (int c = N - 1; c > 0; --c)  // round-off: the last channel with q > 0
        if (q[c] > 0) return c;
      return 0;
    }
  }

  template <class Random>
  bool choose_guided(int c, Random& rng) const {
    const double p = p_guided_[std::size_t(c)];
    if (p <= 0) return false;
    if (p >= 1) return true;
    return rng.uniform_double() < p;
  }

  // Backward guiding: the back axis with probability back_share[c] (no draw without one,
  // nor where the share is 0: far from the far side, most of a walk's flights).
  template <class Random>
  static bool choose_back(const GuideAxes<N>& axes, int c, Random& rng) {
    return axes.has_back && axes.back_share[c] > 0 && rng.uniform_double() < axes.back_share[c];
  }

  // Exponential free path -ln(1 - xi)/sigma (Beer-Lambert), sigma = sigma_t classically
  // or sigma_t (1 - kappa u) guided (Krivanek & d'Eon 2014). xi is a multiple of 2^-53
  // (Rng::uniform_double, Sampler's 32-bit fractions), so 1 - xi is exact in double and
  // log(1 - xi) is as accurate as log1p(-xi), and faster (glibc).
  template <class Random>
  double free_path(int c, bool guided, double u, Random& rng) const {
    const double sigma = guided ? sigma_t_[c] * guide_[c].extinction_scale(u) : sigma_t_[c];
    const double optical = -std::log(1 - rng.uniform_double());
    return sigma > 0 ? optical / sigma : std::numeric_limits<double>::infinity();
  }

  // Guided density about one axis, u the flight's cosine to it, without the exponential:
  // direction density (per sr) times the free-path density (collision) or 1 (passage);
  // beta Dwivedi + (1 - beta) HG for a scattering event, no direction for a flight.
  double guided_density(int c, double u, double phase, bool scattered, bool collision) const {
    const DwivediGuide& guide = guide_[c];
    double density = collision ? sigma_t_[c] * guide.extinction_scale(u) : 1.0;
    if (scattered) {
      const double beta = dwivedi_direction_fraction_;
      const double dwivedi =
          beta > 0 ? beta * (collision ? guide.kappa_over_L() * sigma_t_[c] : guide.pdf_cos(u)) / (2 * kPiD) : 0.0;
      density = dwivedi + (1 - beta) * phase * density;
    }
    return density;
  }

  // exp(x) of a ratio of two terms a exp(b): in single precision where x <= 0 (its
  // relative error, 1e-7, is far below the estimate's noise; a term under e^-87 of the
  // largest becomes 0), in double above (a term of a channel not sampled, or of pure
  // Dwivedi sampling, may exceed the largest by more than float's range).
  static double exp_ratio(double x) { return x <= 0 ? double(std::exp(float(x))) : std::exp(x); }

  // The derivation at the top of this file: numerator and mixture as sums of a exp(b),
  // per channel the classical term and the guided term about each axis in use. The
  // classical exponentials serve the numerator too.
  Channels weights(const FlightProposal& f, const GuideAxes<N>& axes, double length, bool collision,
                   const Channels& q) const {
    if (!any_guided_) {
      // Classical sampling in one channel c alone (q_c = 1: the walk carries c only, as
      // with one colour channel per walk): the mixture is channel c's own term, which the
      // numerator cancels but for the albedo. The other channels carry nothing: 0.
      int only = -1;
      for (int c = 0; c < N; ++c)
        if (q[c] > 0) only = only == -1 ? c : N;
      if (only >= 0 && only < N) {
        Channels w{};
        w[std::size_t(only)] = f.scattered ? albedo_[std::size_t(only)] : 1.0;
        return w;
      }
    }
    const double phase = f.scattered ? f.phase : 1.0;
    double a_classical[N], b_classical[N], a_guided[2 * N], b_guided[2 * N];
    int guided_terms = 0;
    double b_max = -std::numeric_limits<double>::infinity();
    auto add_guided = [&](double a_i, double b_i) {
      if (!(a_i > 0)) return;
      a_guided[guided_terms] = a_i, b_guided[guided_terms] = b_i, ++guided_terms;
      b_max = std::max(b_max, b_i);
    };
    for (int c = 0; c < N; ++c) {
      b_classical[c] = -sigma_t_[c] * length;
      a_classical[c] = q[c] * p_classical_[c] * phase * (collision ? sigma_t_[c] : 1.0);
      if (a_classical[c] > 0) b_max = std::max(b_max, b_classical[c]);
      if (p_guided_[c] > 0 && q[c] > 0) {
        const double back = axes.has_back ? axes.back_share[c] : 0.0;
        const double guided = q[c] * p_guided_[c];
        if (back < 1)
          add_guided(guided * (1 - back) * guided_density(c, f.cos_axis, phase, f.scattered, collision),
                     -sigma_t_[c] * guide_[c].extinction_scale(f.cos_axis) * length);
        if (back > 0)
          add_guided(guided * back * guided_density(c, f.cos_back, phase, f.scattered, collision),
                     -sigma_t_[c] * guide_[c].extinction_scale(f.cos_back) * length);
      }
    }
    Channels w;
    w.fill(0.0);
    if (!std::isfinite(b_max)) return w;  // no strategy could have sampled this flight
    // A channel no flight is drawn in (q_c = 0) carries no throughput (q_c is proportional
    // to it: channel_probabilities): its weight is left 0, its exponential not taken (with
    // one colour channel per walk, two of a step's three).
    double mixture = 0, e[N];
    for (int c = 0; c < N; ++c) {
      e[c] = q[c] > 0 ? exp_ratio(b_classical[c] - b_max) : 0.0;
      mixture += a_classical[c] * e[c];
    }
    for (int i = 0; i < guided_terms; ++i) mixture += a_guided[i] * exp_ratio(b_guided[i] - b_max);
    if (!(mixture > 0)) return w;
    for (int c = 0; c < N; ++c)
      if (q[c] > 0) w[c] = (f.scattered ? albedo_[c] * phase : 1.0) * (collision ? sigma_t_[c] : 1.0) * e[c] / mixture;
    return w;
  }

  static constexpr double kDwivediDirectionMaxG = 0.25;
  static constexpr double kNegligibleBackExponent = 6.907755278982137;  // ln 1000

  // The smallest 1 - albedo channel_probabilities uses: a channel without absorption
  // is preferred as one of albedo 1 - 1e-6 (1000x at k = 1/2), not infinitely.
  static constexpr double kMinChannelAbsorption = 1e-6;
  Channels sigma_t_, albedo_, channel_preference_;
  std::array<DwivediGuide, N> guide_{};
  double g_;
  Channels p_guided_, p_classical_;  // per channel: P_g,c and P_c,c = 1 - P_g,c
  bool any_guided_;                  // some P_g,c > 0 (else classical sampling alone)
  double dwivedi_direction_fraction_ = 1;
};

}  // namespace dermis::sss
