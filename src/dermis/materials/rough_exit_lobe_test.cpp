// The exit lobe Sw through a rough boundary (rough_exit_lobe.h): the table's T against a
// Monte Carlo estimate of the rough dielectric's transmittance through its own sampler
// (bsdf_sample, the path the renderer's entry takes), Sw integrating to one against cos,
// the sampler against pdf (chi-square) and eval / pdf, and the limit alpha -> 0 (the
// smooth normalised-Fresnel lobe). Quadratures carry their own error estimate (a fine
// grid against one twice as coarse); Monte Carlo tolerances are 4 standard errors; fixed
// seeds.
#include "dermis/materials/rough_exit_lobe.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "dermis/core/frame.h"
#include "dermis/core/fresnel.h"
#include "dermis/core/rng.h"
#include "dermis/materials/bsdf.h"
#include "support/direction_grid.h"

namespace dermis {
namespace {

using testing::DirectionHistogram;
using testing::integrate_with_error;
using testing::kChiSquareAlpha;

constexpr double kFloatSlack = 1e-5;
const Vec3 kNormal = normalize(Vec3(-0.3f, 0.2f, 1.0f));

struct Roughness {
  float ax, ay;
};
constexpr Roughness kRoughness[] = {{0.3f, 0.3f}, {0.15f, 0.5f}, {0.7f, 0.7f}};

std::string describe(Roughness r) { return "alpha " + std::to_string(r.ax) + " x " + std::to_string(r.ay); }

BSDF exit_lobe(const RoughExitTable& t, float eta) {
  BSDF b;
  b.type = BSDF::Type::SubsurfaceExit;
  b.n = kNormal;
  b.eta = eta;
  b.sw_norm = t.norm;
  b.exit_table = &t;
  return b;
}

// The rough dielectric's transmittance from outside at cos theta = mu, by Monte Carlo
// through bsdf_sample (visible-normal sampling, the Fresnel choice of the lobe, eval /
// pdf): the mean of weight x etap^2 over transmitted samples, reflected and lost ones
// counting zero. Anisotropic: the azimuth of wo uniform, as the table averages over it.
struct Estimate {
  double mean = 0, standard_error = 0;
};
Estimate sampled_transmittance(float eta, Roughness r, float mu, int n, Rng& rng) {
  BSDF b;
  b.type = BSDF::Type::Dielectric;
  b.n = kNormal;
  b.eta = eta;
  b.alpha_x = r.ax;
  b.alpha_y = r.ay;
  const Frame f(kNormal);
  const float s = std::sqrt(1 - mu * mu);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const float phi = 2 * kPi * rng.uniform();
    const Vec3 wo = f.to_world(Vec3(s * std::cos(phi), s * std::sin(phi), mu));
    const float u_lobe = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    const auto smp = bsdf_sample(b, wo, u_lobe, {u1, u2});
    if (!smp || !smp->transmission) continue;
    const double w = double(smp->weight[0]) * smp->eta_scale;
    sum += w;
    sum2 += w * w;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1))};
}

TEST(RoughExitLobe, TableIsTheSampledTransmittanceOfTheRoughDielectric) {
  const float eta = 1.4f;
  Rng rng(1010, 0);
  for (Roughness r : kRoughness) {
    const RoughExitTable t = make_rough_exit_table(eta, r.ax, r.ay);
    for (int node : {8, 24, 40, 58, 64}) {
      const float mu = float(node) / (RoughExitTable::kNodes - 1);
      SCOPED_TRACE(describe(r) + ", mu " + std::to_string(mu));
      // The table's own quadrature error: its k = 64 rule against k = 128 (the azimuths
      // of an anisotropic wo: a midpoint rule on a smooth periodic function, exact far
      // below this).
      const double fine = rough_dielectric_transmittance(eta, r.ax, r.ay, mu, 128);
      const double table_error = std::abs(double(t.transmittance[node]) - fine);
      const Estimate e = sampled_transmittance(eta, r, mu, 400'000, rng);
      std::printf("%s mu %.3f: table %.5f, sampled %.5f +- %.5f, quadrature error %.1e\n", describe(r).c_str(), mu,
                  t.at(mu), e.mean, e.standard_error, table_error);
      EXPECT_NEAR(t.at(mu), e.mean, 4 * e.standard_error + table_error + kFloatSlack);
      EXPECT_LE(t.at(mu), 1.0f);
      EXPECT_GE(t.at(mu), 0.0f);
    }
  }
}

TEST(RoughExitLobe, IntegratesToOneAgainstCosine) {
  for (float eta : {1.2f, 1.4f, 2.0f})
    for (Roughness r : kRoughness) {
      SCOPED_TRACE("eta " + std::to_string(eta) + ", " + describe(r));
      const RoughExitTable t = make_rough_exit_table(eta, r.ax, r.ay);
      const BSDF b = exit_lobe(t, eta);
      const Frame f(kNormal);
      auto sw_cos = [&](Vec3 w) { return double(bsdf_eval(b, kNormal, f.to_world(w))[0]); };
      const auto I = integrate_with_error(sw_cos, kPiD / 2, 1024, 64);
      EXPECT_NEAR(I.value, 1.0, I.error + kFloatSlack);
      EXPECT_GT(t.norm, 0.0f);
      EXPECT_LE(t.norm, 1.0f);
    }
}

TEST(RoughExitLobe, SamplerMatchesPdfAndWeightsAreEvalOverPdf) {
  uint64_t seed = 300;
  for (Roughness r : kRoughness) {
    SCOPED_TRACE(describe(r));
    const RoughExitTable t = make_rough_exit_table(1.4f, r.ax, r.ay);
    const BSDF b = exit_lobe(t, 1.4f);
    const Frame f(kNormal);
    auto pdf = [&](Vec3 w) { return double(bsdf_pdf(b, kNormal, f.to_world(w))); };
    DirectionHistogram h(kPiD, 24, 48);
    Rng rng(seed++, 0);
    const int n = 200'000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
      const float u_lobe = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
      const auto s = bsdf_sample(b, kNormal, u_lobe, {u1, u2});
      if (!s) {
        h.add_lost();
        continue;
      }
      h.add(f.to_local(s->wi));
      EXPECT_NEAR(s->pdf, bsdf_pdf(b, kNormal, s->wi), 1e-5f * s->pdf);
      const float w = bsdf_eval(b, kNormal, s->wi)[0] / s->pdf;
      EXPECT_NEAR(s->weight[0], w, 1e-5f * w);
      sum += s->weight[0];
      sum2 += double(s->weight[0]) * s->weight[0];
    }
    const auto chi = h.test(pdf);
    EXPECT_GT(chi.p_value, kChiSquareAlpha) << "chi2 " << chi.statistic << " dof " << chi.dof;
    // E[weight] = integral of Sw cos = 1 (lost samples count as zero).
    const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1));
    EXPECT_NEAR(mean, 1.0, 4 * se);
  }
}

// The distance between two exit lobes as distributions of exit directions:
// integral of |Sw_a - Sw_b| cos over the hemisphere = 2 int_0^1 |Sw_a - Sw_b| pi mu dmu
// (total variation, twice), by the midpoint rule on 2^14 intervals of mu.
template <class A, class B>
double lobe_distance(const A& sw_a, const B& sw_b) {
  constexpr int n = 1 << 14;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double mu = (i + 0.5) / n;
    sum += std::abs(sw_a(float(mu)) - sw_b(float(mu))) * mu;
  }
  return 2 * kPiD * sum / n;
}

// alpha -> 0: the lobe tends to the smooth normalised-Fresnel lobe (1 - Fr) / (c pi).
// Its distance from it shrinks with alpha down to the floor of the table itself: the
// distance between the smooth lobe and its own linear interpolant on the 65 nodes
// (normalised by the table's exact rule), computed here. At the smallest rough alpha it
// is within twice that floor, and c is the smooth c = 1 - 2 FM1 within the interpolant's
// c error plus 2 int |T - (1 - Fr)| mu dmu (both c's are that rule on their nodes).
TEST(RoughExitLobe, ConvergesToTheSmoothLobeAsRoughnessVanishes) {
  const float eta = 1.4f;
  const RoughExitTable smooth = make_smooth_exit_table(eta);  // 1 - Fr on the nodes, its c by the table's rule
  const float c_smooth = subsurface_exit_normalization(eta);
  auto exact = [&](float mu) { return double(1 - fresnel_dielectric(mu, eta)) / (c_smooth * kPiD); };
  auto lobe_of = [](const RoughExitTable& t) { return [&t](float mu) { return double(t.at(mu)) / (t.norm * kPiD); }; };
  const double floor = lobe_distance(lobe_of(smooth), exact);
  double previous = 1e9;
  for (float alpha : {0.3f, 0.1f, 0.03f, 0.01f, 0.001f}) {
    const RoughExitTable t = make_rough_exit_table(eta, alpha, alpha);
    const double distance = lobe_distance(lobe_of(t), exact);
    // 2 int |T - (1 - Fr)| mu dmu between the two interpolants: bounds their c's difference.
    const double d = lobe_distance([&](float mu) { return double(t.at(mu)) / kPiD; },
                                   [&](float mu) { return double(smooth.at(mu)) / kPiD; });
    std::printf(
        "alpha %.3f: distance to the smooth lobe %.5f (floor %.5f), 2 int |T - (1 - Fr)| mu dmu %.5f, "
        "c %.5f (smooth %.5f, its interpolant %.5f)\n",
        alpha, distance, floor, d, t.norm, c_smooth, smooth.norm);
    EXPECT_LT(distance, previous) << "alpha " << alpha;
    previous = distance;
    if (alpha == 0.001f) {
      EXPECT_LT(distance, 2 * floor) << "alpha " << alpha;
      EXPECT_NEAR(t.norm, c_smooth, d + std::abs(smooth.norm - c_smooth) + kFloatSlack);
    }
  }
}

// A textured roughness's tables (RoughExitTables): node k is the material table of alpha
// (k / 16)^2 (node 0 the smooth one), the blend at a node is that node, and between
// nodes the blend is within the linear interpolation's error of the table made at that
// alpha: w (1 - w) h^2 |T''| / 2 per node mu (in t = sqrt(alpha), the variable of the
// interpolation), T'' estimated by the tables' second differences around the interval
// (the largest of the three nearest), plus that table's own quadrature error (k = 64
// against k = 128); c the same with c''. Near alpha = 0 both the smooth node and the
// quadrature floor of a nearly specular table (5e-5, the test above) take over: the
// alphas checked are those of textures that are rough. Each blend also integrates to one
// against cos (its sampler is the tables' cosine sampler, tested above with eval / pdf).
TEST(RoughExitLobe, TexturedTablesAreTheTablesAtTheirNodesAndInterpolateBetween) {
  const float eta = 1.4f;
  const RoughExitTables tables(eta);
  constexpr int K = RoughExitTables::kAlphaNodes;
  auto same = [](const RoughExitTable& a, const RoughExitTable& b) {
    for (int i = 0; i < RoughExitTable::kNodes; ++i)
      if (a.transmittance[i] != b.transmittance[i]) return false;
    return a.norm == b.norm;
  };
  EXPECT_TRUE(same(tables.node(0), make_smooth_exit_table(eta)));
  EXPECT_TRUE(same(tables.node(8), make_rough_exit_table(eta, 0.25f, 0.25f)));
  RoughExitTable blended;
  tables.at(0.25f, blended);
  EXPECT_TRUE(same(blended, tables.node(8)));
  for (float alpha : {0.09f, 0.53f, 0.97f}) {
    const float x = std::sqrt(alpha) * (K - 1);
    const int k = int(x);
    const double w = x - k;
    tables.at(alpha, blended);
    const RoughExitTable direct = make_rough_exit_table(eta, alpha, alpha);
    auto interpolation_error = [&](auto value) {
      double d2 = 0;
      for (int j = std::max(1, k - 1); j <= std::min(K - 2, k + 2); ++j)
        d2 = std::max(d2, std::abs(value(tables.node(j - 1)) - 2 * value(tables.node(j)) + value(tables.node(j + 1))));
      return w * (1 - w) * d2 / 2;
    };
    double worst = 0, c_quadrature = 0;
    for (int i = 0; i < RoughExitTable::kNodes; ++i) {
      const auto t_i = [i](const RoughExitTable& t) { return double(t.transmittance[i]); };
      const float mu = float(i) / (RoughExitTable::kNodes - 1);
      const double quadrature =
          std::abs(direct.transmittance[i] - rough_dielectric_transmittance(eta, alpha, alpha, mu, 128));
      c_quadrature = std::max(c_quadrature, quadrature);  // c's error is at most T's largest (2 int mu = 1)
      const double error = std::abs(double(blended.transmittance[i]) - direct.transmittance[i]);
      EXPECT_LE(error, interpolation_error(t_i) + quadrature + kFloatSlack) << "alpha " << alpha << " node " << i;
      worst = std::max(worst, error);
    }
    const auto c = [](const RoughExitTable& t) { return double(t.norm); };
    EXPECT_LE(std::abs(double(blended.norm) - direct.norm), interpolation_error(c) + c_quadrature + kFloatSlack)
        << "alpha " << alpha;
    // The blend is a lobe of its own: it integrates to one against cos (its c blended with T).
    const BSDF b = exit_lobe(blended, eta);
    const Frame f(kNormal);
    const auto I = integrate_with_error([&](Vec3 w) { return double(bsdf_eval(b, kNormal, f.to_world(w))[0]); },
                                        kPiD / 2, 1024, 64);
    EXPECT_NEAR(I.value, 1.0, I.error + kFloatSlack) << "alpha " << alpha;
    std::printf("alpha %.2f: max |T blended - T direct| %.2e, |c blended - c direct| %.2e\n", alpha, worst,
                std::abs(double(blended.norm) - direct.norm));
  }
}

}  // namespace
}  // namespace dermis
