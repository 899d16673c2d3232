#include "dermis/sss/walk/walk_step.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dermis/core/gauss_legendre.h"
#include "support/chi_square.h"

namespace dermis::sss {
namespace {

// Mean and standard error of a per-sample estimate.
struct MeanEstimate {
  double sum = 0, sum_sq = 0;
  int n = 0;
  void add(double x) { sum += x, sum_sq += x * x, ++n; }
  double mean() const { return sum / n; }
  double stderr_() const { return std::sqrt(std::max(0.0, sum_sq / n - mean() * mean()) / (n - 1)); }
};

#define EXPECT_WITHIN_4_SIGMA(estimate, reference, what)                        \
  EXPECT_NEAR((estimate).mean(), (reference), 4 * (estimate).stderr_() + 1e-15) \
      << what << " mean=" << (estimate).mean() << " ref=" << (reference) << " stderr=" << (estimate).stderr_()

const Vec3d kAxis = normalize(Vec3d{0.3, -0.5, 0.8});
// The far side's outward normal for backward guiding: roughly opposite kAxis, as on a slab
// with non-parallel faces.
const Vec3d kBackAxis = normalize(Vec3d{-0.1, 0.6, -0.7});

// The guide configurations every weight test runs with: the seed's (front only), and
// front + back with a different back share per channel (one of them pure back).
std::vector<GuideAxes<3>> guide_configurations() {
  GuideAxes<3> front{Framed(kAxis)}, both{Framed(kAxis)};
  both.back = Framed(kBackAxis);
  both.has_back = true;
  both.back_share = {0.3, 0.7, 1.0};
  return {front, both};
}

// The guided joint density of (u, s): p(u) sigma' exp(-sigma' s), sigma' = sigma_t (1 - kappa u)
// (Krivanek & d'Eon 2014), checked on a 2D grid of (u, s) bins, u measured from the
// sampled direction vector against a tilted axis.
// With backward guiding and back share 1 the same joint holds about the back axis.
TEST(WalkStep, GuidedDirectionAndDistanceChiSquare) {
  const double sigma_t = 2.0;
  for (bool back : {false, true})
    for (double alpha : {0.5, 0.95}) {
      const MixtureWalkStep<1> step({sigma_t}, {alpha}, 0.0, 1.0);
      const DwivediGuide& guide = step.guide(0);
      const std::vector<double> u_edges = {-1, -0.5, 0, 0.4, 0.7, 0.9, 0.97, 1};
      const std::vector<double> s_edges = {0, 0.1, 0.25, 0.5, 1, 2, 4, 1e300};
      const int nu = int(u_edges.size()) - 1, ns = int(s_edges.size()) - 1, n = 200000;
      std::vector<double> observed(nu * ns, 0.0), expected(nu * ns, 0.0);
      Rng rng(11, uint64_t(alpha * 100), back);
      GuideAxes<1> axes{Framed(back ? kBackAxis : kAxis)};
      if (back)
        axes = GuideAxes<1>{Framed(kAxis)}, axes.back = Framed(kBackAxis), axes.has_back = true,
        axes.back_share = {1.0};
      const Vec3d sampled_axis = back ? kBackAxis : kAxis;
      for (int i = 0; i < n; ++i) {
        const FlightProposal f = step.propose_scatter({0, 0, -1}, axes, {1.0}, rng);
        const double u = dot(f.direction, sampled_axis);
        ASSERT_NEAR(u, back ? f.cos_back : f.cos_axis, 1e-9);
        ASSERT_NEAR(dot(f.direction, kAxis), f.cos_axis, 1e-9);
        ASSERT_NEAR(length(f.direction), 1.0, 1e-12);
        const int a = int(std::upper_bound(u_edges.begin(), u_edges.end(), u) - u_edges.begin()) - 1;
        const int b = int(std::upper_bound(s_edges.begin(), s_edges.end(), f.distance) - s_edges.begin()) - 1;
        observed[std::min(a, nu - 1) * ns + std::min(b, ns - 1)] += 1;
      }
      const QuadratureRule rule = gauss_legendre(32, 0.0, 1.0);
      for (int a = 0; a < nu; ++a)
        for (size_t j = 0; j < rule.nodes.size(); ++j) {
          const double h = u_edges[a + 1] - u_edges[a], u = u_edges[a] + h * rule.nodes[j];
          const double sigma = sigma_t * (1 - guide.kappa() * u);
          for (int b = 0; b < ns; ++b)
            expected[a * ns + b] += n * h * rule.weights[j] * guide.pdf_cos(u) *
                                    (std::exp(-sigma * s_edges[b]) - std::exp(-sigma * s_edges[b + 1]));
        }
      const auto r = testing::chi_square(observed, expected);
      EXPECT_GT(r.p_value, testing::kChiSquareAlpha)
          << "alpha=" << alpha << " back=" << back << " chi2=" << r.statistic;
    }
}

// Unbiasedness of the one-sample MIS weights over channels and strategies: for a
// scattering event followed by a collision (no boundary), E[w_k h] equals the physical
// alpha_k int p(w) sigma_t exp(-sigma_t s) h: alpha_k for h = 1, alpha_k / sigma_t,k for
// h = s, and alpha_k g (w_in . n) for h = u (the HG mean cosine, projected).
TEST(WalkStep, ScatterCollisionWeightsAreUnbiased) {
  const std::array<double, 3> sigma_t{1.0, 2.5, 0.4}, albedo{0.5, 0.9, 0.99}, q{0.2, 0.5, 0.3};
  const Vec3d w_in = normalize(Vec3d{0.2, 0.1, -1});
  for (const GuideAxes<3>& axis : guide_configurations())
    for (double g : {0.0, 0.6})
      for (double p_guided : {0.0, 0.5, 1.0}) {
        const MixtureWalkStep<3> step(sigma_t, albedo, g, p_guided);
        MeanEstimate w[3], ws[3], wu[3];
        Rng rng(3, uint64_t(p_guided * 10), uint64_t(g * 10) + 100 * axis.has_back);
        for (int i = 0; i < 200000; ++i) {
          const FlightProposal f = step.propose_scatter(w_in, axis, q, rng);
          const auto weight = step.collision_weights(f, axis, q);
          for (int c = 0; c < 3; ++c) {
            w[c].add(weight[c]);
            ws[c].add(weight[c] * f.distance);
            wu[c].add(weight[c] * f.cos_axis);
          }
        }
        for (int c = 0; c < 3; ++c) {
          const std::string what = "g=" + std::to_string(g) + " P_g=" + std::to_string(p_guided) +
                                   " c=" + std::to_string(c) + " back=" + std::to_string(axis.has_back);
          EXPECT_WITHIN_4_SIGMA(w[c], albedo[c], what);
          EXPECT_WITHIN_4_SIGMA(ws[c], albedo[c] / sigma_t[c], what);
          EXPECT_WITHIN_4_SIGMA(wu[c], albedo[c] * g * dot(w_in, kAxis), what);
        }
      }
}

// A flight along a given direction toward a plane boundary at distance d: the
// weighted collision and passage events reproduce 1 - exp(-sigma_t d) and exp(-sigma_t d).
TEST(WalkStep, FlightWeightsReproduceTransmittance) {
  const std::array<double, 3> sigma_t{1.0, 3.0, 0.3}, albedo{0.5, 0.9, 0.99}, q{0.5, 0.1, 0.4};
  const Vec3d direction = normalize(kAxis + Vec3d{0.4, 0, 0});  // toward the boundary: u > 0
  const double d = 0.8;
  for (const GuideAxes<3>& axis : guide_configurations())
    for (double p_guided : {0.0, 0.75, 1.0}) {
      const MixtureWalkStep<3> step(sigma_t, albedo, 0.3, p_guided);
      MeanEstimate collided[3], passed[3];
      Rng rng(5, uint64_t(p_guided * 100), axis.has_back);
      for (int i = 0; i < 100000; ++i) {
        const FlightProposal f = step.propose_flight(direction, axis, q, rng);
        const bool pass = f.distance >= d;
        const auto weight = pass ? step.passage_weights(f, axis, d, q) : step.collision_weights(f, axis, q);
        for (int c = 0; c < 3; ++c) collided[c].add(pass ? 0 : weight[c]), passed[c].add(pass ? weight[c] : 0);
      }
      for (int c = 0; c < 3; ++c) {
        EXPECT_WITHIN_4_SIGMA(passed[c], std::exp(-sigma_t[c] * d),
                              "P_g=" << p_guided << " c=" << c << " back=" << axis.has_back);
        EXPECT_WITHIN_4_SIGMA(collided[c], 1 - std::exp(-sigma_t[c] * d),
                              "P_g=" << p_guided << " c=" << c << " back=" << axis.has_back);
      }
    }
}

// A scattering event at depth D below a plane with outward normal n, incoming along n:
// E[w_k 1{pass}] = alpha_k int_0^1 2 pi p_HG(u) exp(-sigma_t,k D / u) du (quadrature).
TEST(WalkStep, ScatterPassageWeightsMatchQuadrature) {
  const std::array<double, 3> sigma_t{1.0, 2.0, 0.5}, albedo{0.6, 0.9, 0.99}, q{0.3, 0.3, 0.4};
  const double g = 0.5, depth = 0.7;
  const QuadratureRule rule = gauss_legendre(200, 0.0, 1.0);
  for (const GuideAxes<3>& axis : guide_configurations())
    for (double p_guided : {0.0, 0.75, 1.0}) {
      const MixtureWalkStep<3> step(sigma_t, albedo, g, p_guided);
      MeanEstimate passed[3];
      Rng rng(9, uint64_t(p_guided * 100), axis.has_back);
      for (int i = 0; i < 200000; ++i) {
        const FlightProposal f = step.propose_scatter(kAxis, axis, q, rng);
        const double boundary = f.cos_axis > 0 ? depth / f.cos_axis : 1e300;
        const bool pass = f.distance >= boundary;
        const auto weight = pass ? step.passage_weights(f, axis, boundary, q) : std::array<double, 3>{0, 0, 0};
        for (int c = 0; c < 3; ++c) passed[c].add(weight[c]);
      }
      for (int c = 0; c < 3; ++c) {
        double reference = 0;
        for (size_t j = 0; j < rule.nodes.size(); ++j) {
          const double u = rule.nodes[j];
          reference += rule.weights[j] * 2 * kPiD * henyey_greenstein(u, g) * std::exp(-sigma_t[c] * depth / u);
        }
        EXPECT_WITHIN_4_SIGMA(passed[c], albedo[c] * reference,
                              "P_g=" << p_guided << " c=" << c << " back=" << axis.has_back);
      }
    }
}

// The back share is the far plane's part of the summed importance exp(-kappa sigma_t D):
// the closed form (in single precision: 1e-6), one half at equal depths, complementary
// when the depths swap, finite for depths far beyond the range of exp, and 0 for a
// channel no flight is drawn in.
TEST(WalkStep, BackSharesFollowTheImportanceOfBothPlanes) {
  const std::array<double, 3> sigma_t{1.0, 2.0, 0.5}, albedo{0.5, 0.9, 1.0}, q{0.2, 0.3, 0.5};
  const MixtureWalkStep<3> step(sigma_t, albedo, 0.0, 0.5);
  for (auto [front, back] : {std::pair{0.2, 1.5}, {3.0, 0.1}, {1.0, 1.0}, {0.5, 5.0}}) {
    const auto b = step.back_shares(front, back, q), swapped = step.back_shares(back, front, q);
    for (int c = 0; c < 3; ++c) {
      const double k = step.guide(c).kappa() * sigma_t[c];
      const double i_front = std::exp(-k * front), i_back = std::exp(-k * back);
      EXPECT_NEAR(b[c], i_back / (i_front + i_back), 1e-6) << c;
      EXPECT_NEAR(b[c] + swapped[c], 1.0, 1e-6) << c;
    }
    const auto only_green = step.back_shares(front, back, {0.0, 1.0, 0.0});
    EXPECT_EQ(only_green[0], 0.0);
    EXPECT_EQ(only_green[1], b[1]);
    EXPECT_EQ(only_green[2], 0.0);
  }
  // Below 1/1000 the share is dropped (exactly 0: no back terms), above it kept.
  const double k0 = step.guide(0).kappa() * sigma_t[0];
  EXPECT_EQ(step.back_shares(0.0, std::log(1001.0) / k0, q)[0], 0.0);
  EXPECT_GT(step.back_shares(0.0, std::log(999.0) / k0, q)[0], 0.0);
  EXPECT_EQ(step.back_shares(0.0, 1e6, q)[0], 0.0);
  EXPECT_EQ(step.back_shares(1e6, 0.0, q)[0], 1.0);
  EXPECT_EQ(step.back_shares(0.0, 5.0, q)[2], 0.5);  // albedo 1: kappa = 0, no preference
}

// q_c is proportional to throughput_c (1 - albedo_c)^-k, sums to one, and leaves a
// channel without throughput out; k = 0 is the throughput alone.
TEST(WalkStep, ChannelProbabilitiesPreferLowAbsorption) {
  const std::array<double, 3> sigma_t{1.0, 2.0, 0.5}, albedo{0.99, 0.9, 0.0};
  const MixtureWalkStep<3> throughput_only(sigma_t, albedo, 0.0, 0.5, 0.0);
  const auto q0 = throughput_only.channel_probabilities({2.0, 1.0, 1.0});
  EXPECT_DOUBLE_EQ(q0[0], 0.5);
  EXPECT_DOUBLE_EQ(q0[1], 0.25);
  EXPECT_DOUBLE_EQ(q0[2], 0.25);
  const MixtureWalkStep<3> preferring(sigma_t, albedo, 0.0, 0.5, 0.5);
  const auto q = preferring.channel_probabilities({1.0, 1.0, 1.0});
  // (1 - albedo)^-1/2 = 10, sqrt(10), 1.
  const double sum = 10 + std::sqrt(10.0) + 1;
  EXPECT_NEAR(q[0], 10 / sum, 1e-6);
  EXPECT_NEAR(q[1], std::sqrt(10.0) / sum, 1e-6);
  EXPECT_NEAR(q[2], 1 / sum, 1e-6);
  const auto q_lost = preferring.channel_probabilities({0.0, 3.0, 1.0});
  EXPECT_EQ(q_lost[0], 0.0);
  EXPECT_NEAR(q_lost[1] + q_lost[2], 1.0, 1e-12);
  EXPECT_NEAR(q_lost[1] / q_lost[2], 3 * std::sqrt(10.0), 1e-6);
  // A channel without absorption is preferred finitely.
  const MixtureWalkStep<3> conservative({1.0, 1.0, 1.0}, {1.0, 0.5, 0.5}, 0.0, 0.5, 0.5);
  const auto qc = conservative.channel_probabilities({1.0, 1.0, 1.0});
  EXPECT_TRUE(std::isfinite(qc[0]) && qc[0] < 1);
  EXPECT_GT(qc[2], 0.0);
}

TEST(WalkStep, RejectsBadMedia) {
  EXPECT_THROW(MixtureWalkStep<1>({1.0}, {0.5}, 0.0, 0.5, -0.5), std::invalid_argument);
  EXPECT_THROW(MixtureWalkStep<1>({1.0}, {0.5}, 0.0, 0.5, std::nan("")), std::invalid_argument);
  EXPECT_THROW(MixtureWalkStep<1>({0.0}, {0.5}, 0.0, 0.5), std::invalid_argument);
  EXPECT_THROW(MixtureWalkStep<1>({1.0}, {1.5}, 0.0, 0.5), std::invalid_argument);
  EXPECT_THROW(MixtureWalkStep<1>({1.0}, {0.5}, 1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(MixtureWalkStep<1>({1.0}, {0.5}, 0.0, 1.5), std::invalid_argument);
  EXPECT_EQ(parse_walk_sampling("mis"), WalkSampling::Mis);
  EXPECT_EQ(parse_walk_sampling("dwivedi"), WalkSampling::Dwivedi);
  EXPECT_EQ(parse_walk_sampling("classical"), WalkSampling::Classical);
  EXPECT_THROW(parse_walk_sampling("guided"), std::invalid_argument);
  EXPECT_EQ(guided_choice_probability(WalkSampling::Dwivedi, 0.3), 1.0);
  EXPECT_EQ(guided_choice_probability(WalkSampling::Mis, 0.3), 0.3);
  EXPECT_THROW(guided_choice_probability(WalkSampling::Mis, -0.1), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
