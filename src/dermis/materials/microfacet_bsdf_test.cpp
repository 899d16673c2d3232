// Tests of the rough dielectric and rough conductor through the world-space BSDF (a
// tilted normal, so that the shading frame is exercised): pdf normalisation, sampler
// against pdf (chi-square), weights against eval / pdf, reciprocity, energy. Monte Carlo
// tolerances are 4 standard errors; quadratures carry their own error estimate
// (support/direction_grid.h). Fixed seeds.
#include "dermis/materials/microfacet_bsdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dermis/core/frame.h"
#include "dermis/core/fresnel.h"
#include "dermis/core/rng.h"
#include "dermis/materials/bsdf.h"
#include "support/direction_grid.h"

namespace dermis {
namespace {

using testing::direction_at;
using testing::DirectionHistogram;
using testing::integrate_with_error;
using testing::kChiSquareAlpha;

const Vec3 kNormal = normalize(Vec3(0.2f, -0.3f, 1.0f));
const RGB kGoldEta(0.2f, 0.92f, 1.1f), kGoldK(3.9f, 2.45f, 2.14f);

BSDF rough(BSDF::Type type, float ax, float ay) {
  BSDF b;
  b.type = type;
  b.n = kNormal;
  b.eta = 1.5f;
  b.cond_eta = kGoldEta;
  b.cond_k = kGoldK;
  b.alpha_x = ax;
  b.alpha_y = ay;
  return b;
}

// A direction at polar angle theta to the BSDF's normal (theta > pi/2: below).
Vec3 about_normal(double theta, double phi) { return Frame(kNormal).to_world(direction_at(theta, phi)); }

struct Case {
  BSDF b;
  Vec3 wo;
  const char* what;
};

// Dielectric from outside (near normal, oblique), from inside below and beyond the
// critical angle (41.8 degrees for eta 1.5); conductor from either side; isotropic and
// anisotropic roughness.
std::vector<Case> cases() {
  std::vector<Case> c;
  for (auto [ax, ay] : {std::pair{0.3f, 0.3f}, std::pair{0.15f, 0.5f}}) {
    const BSDF d = rough(BSDF::Type::Dielectric, ax, ay), m = rough(BSDF::Type::Conductor, ax, ay);
    c.push_back({d, about_normal(0.3, 0.4), "dielectric, outside, 17 deg"});
    c.push_back({d, about_normal(1.2, 2.0), "dielectric, outside, 69 deg"});
    c.push_back({d, about_normal(kPiD - 0.4, 1.0), "dielectric, inside, 23 deg"});
    c.push_back({d, about_normal(kPiD - 0.9, 4.0), "dielectric, inside, 52 deg (beyond critical)"});
    c.push_back({m, about_normal(0.3, 0.4), "conductor, 17 deg"});
    c.push_back({m, about_normal(1.3, 5.0), "conductor, 74 deg"});
    c.push_back({m, about_normal(kPiD - 0.5, 1.0), "conductor, from below, 29 deg"});
  }
  return c;
}

std::string describe(const Case& c) {
  return std::string(c.what) + ", alpha " + std::to_string(c.b.alpha_x) + " x " + std::to_string(c.b.alpha_y);
}

constexpr int kSamples = 200'000;
// Full sphere: the peaks (alpha >= 0.15, lobes ~0.3 rad wide) span > 100 theta steps.
constexpr int kThetaSteps = 1024, kPhiSteps = 512;
constexpr double kFloatSlack = 1e-5;

TEST(RoughBsdf, SpecularOnlyWhenEffectivelySmooth) {
  for (auto type : {BSDF::Type::Dielectric, BSDF::Type::Conductor}) {
    const BSDF smooth = rough(type, 0, 0), nearly = rough(type, 9e-4f, 5e-4f), r = rough(type, 1e-3f, 0);
    EXPECT_TRUE(smooth.is_specular());
    EXPECT_TRUE(nearly.is_specular());
    EXPECT_FALSE(r.is_specular());
    EXPECT_TRUE(r.is_rough());
    // Below the threshold: today's smooth code path, bit for bit.
    const Vec3 wo = about_normal(0.7, 1.0);
    for (float u_lobe : {0.01f, 0.5f, 0.99f}) {
      const auto a = bsdf_sample(smooth, wo, u_lobe, {0.3f, 0.6f}), b = bsdf_sample(nearly, wo, u_lobe, {0.3f, 0.6f});
      ASSERT_TRUE(a && b);
      EXPECT_TRUE(a->wi == b->wi);
      EXPECT_EQ(a->weight, b->weight);
      EXPECT_EQ(a->pdf, b->pdf);
      EXPECT_TRUE(b->specular);
    }
    EXPECT_EQ(bsdf_pdf(nearly, wo, reflect(wo, kNormal)), 0.0f);
    EXPECT_TRUE(bsdf_eval(nearly, wo, reflect(wo, kNormal)).is_black());
  }
}

// The pdf integrates to 1 - P(lost), P(lost) the probability that bsdf_sample returns
// nothing (a microfacet reflection below the surface, a refraction back to wo's side),
// estimated by sampling (binomial standard error); and the sampled directions follow the
// pdf (chi-square, with the lost samples as one more cell).
TEST(RoughBsdf, PdfIntegratesToOneMinusLostAndSamplerMatchesIt) {
  uint64_t seed = 100;
  for (const Case& c : cases()) {
    SCOPED_TRACE(describe(c));
    auto pdf = [&](Vec3 wi) { return double(bsdf_pdf(c.b, c.wo, wi)); };
    const auto I = integrate_with_error(pdf, kPiD, kThetaSteps, kPhiSteps);
    DirectionHistogram h(kPiD, 24, 48);
    Rng rng(seed++, 0);
    for (int i = 0; i < kSamples; ++i) {
      const auto s = bsdf_sample(c.b, c.wo, rng.uniform(), {rng.uniform(), rng.uniform()});
      if (s) {
        h.add(s->wi);
      } else {
        h.add_lost();
      }
    }
    const double lost = h.lost_fraction(), sigma = std::sqrt(std::max(lost * (1 - lost), 1.0 / kSamples) / kSamples);
    EXPECT_LE(I.value, 1.0 + I.error + kFloatSlack);
    EXPECT_NEAR(I.value, 1.0 - lost, 4 * sigma + I.error + kFloatSlack) << "lost " << lost;
    const auto r = h.test(pdf);
    EXPECT_GT(r.p_value, kChiSquareAlpha) << "chi2 " << r.statistic << " dof " << r.dof;
  }
}

TEST(RoughBsdf, SampleWeightIsEvalOverPdf) {
  uint64_t seed = 200;
  for (const Case& c : cases()) {
    SCOPED_TRACE(describe(c));
    Rng rng(seed++, 0);
    int returned = 0;
    for (int i = 0; i < 2000; ++i) {
      const auto s = bsdf_sample(c.b, c.wo, rng.uniform(), {rng.uniform(), rng.uniform()});
      if (!s) continue;
      ++returned;
      EXPECT_FALSE(s->specular);
      EXPECT_NEAR(length(s->wi), 1.0f, 1e-5f);
      const float pdf = bsdf_pdf(c.b, c.wo, s->wi);
      EXPECT_NEAR(s->pdf, pdf, 1e-5f * pdf);
      const RGB f = bsdf_eval(c.b, c.wo, s->wi);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(s->weight[k], f[k] / pdf, 1e-4f * f[k] / pdf);
      const bool crossed = dot(s->wi, kNormal) * dot(c.wo, kNormal) < 0;
      EXPECT_EQ(s->transmission, crossed);
      const float etap = dot(c.wo, kNormal) > 0 ? c.b.eta : 1 / c.b.eta;
      EXPECT_FLOAT_EQ(s->eta_scale, crossed ? etap * etap : 1.0f);
      if (c.b.type == BSDF::Type::Conductor) {
        EXPECT_FALSE(crossed);
      }
    }
    EXPECT_GT(returned, 1000);
  }
}

// f(wo, wi) = f(wi, wo) for reflection (bsdf_eval returns f |cos wi|); across the
// dielectric, radiance scaling makes f(wo, wi) / eta_o^2 = f(wi, wo) / eta_i^2
// (Veach 1997, eq. 5.14), eta_o and eta_i the indices on the sides of wo and wi.
// The two orders compute F from wo.m and from wi.m. In float, F's cos_t = sqrt(1 - sin_t^2)
// loses ~eps / cos_t^2 relative accuracy near the critical angle, and 1 - F ~ |w.m| near a
// grazing microfacet ~eps / (w.m)^2 (eps = 6e-8): the tolerance is 1e-5 + 16 eps / c^2
// relative, c the smaller of |wo.m| and the cosine on the far side of the microfacet.
TEST(RoughBsdf, Reciprocity) {
  const Frame frame(kNormal);
  for (auto [ax, ay] : {std::pair{0.3f, 0.3f}, std::pair{0.15f, 0.5f}})
    for (auto type : {BSDF::Type::Dielectric, BSDF::Type::Conductor}) {
      const BSDF b = rough(type, ax, ay);
      Rng rng(7, 0);
      int transmissions = 0, nonzero = 0;
      for (int i = 0; i < 2000; ++i) {
        const Vec3 wo = about_normal(std::acos(1 - 2 * double(rng.uniform())), 2 * kPiD * rng.uniform());
        const Vec3 wi = about_normal(std::acos(1 - 2 * double(rng.uniform())), 2 * kPiD * rng.uniform());
        const float co = dot(wo, kNormal), ci = dot(wi, kNormal);
        const bool crossed = co * ci < 0;
        if (crossed && type == BSDF::Type::Conductor) continue;
        const float eta_o = co > 0 ? 1 : b.eta, eta_i = ci > 0 ? 1 : b.eta;
        const auto m = crossed ? refraction_half_vector(frame.to_local(wo), frame.to_local(wi), eta_i / eta_o)
                               : reflection_half_vector(frame.to_local(wo), frame.to_local(wi));
        if (!m) continue;
        const double c_o = dot(frame.to_local(wo), *m);
        const double eta_m = type == BSDF::Type::Conductor ? 1.0 : (c_o > 0 ? b.eta : 1 / b.eta);
        const double cos_t2 = 1 - (1 - c_o * c_o) / (eta_m * eta_m);  // Snell across the microfacet
        const double c2 = std::min(c_o * c_o, cos_t2);
        const double tolerance = c2 > 0 ? 1e-5 + 16 * 6e-8 / c2 : 1.0;
        const double f_oi = bsdf_eval(b, wo, wi)[0] / std::abs(ci) / (eta_o * eta_o);
        const double f_io = bsdf_eval(b, wi, wo)[0] / std::abs(co) / (eta_i * eta_i);
        EXPECT_NEAR(f_oi, f_io, tolerance * std::max(f_oi, f_io)) << "c^2 " << c2;
        transmissions += crossed && f_oi > 0;
        nonzero += f_oi > 0;
      }
      EXPECT_GT(nonzero, 500);
      if (type == BSDF::Type::Dielectric) {
        EXPECT_GT(transmissions, 200);
      }
    }
}

// The directional albedo int f |cos wi| dwi by quadrature of bsdf_eval against the mean
// of the sampler's weights (which estimate the same integral: lost samples weigh 0).
// Conductor: no more than the largest Fresnel reflectance of any microfacet.
TEST(RoughBsdf, AlbedoOfSamplerMatchesQuadratureOfEval) {
  uint64_t seed = 300;
  for (const Case& c : cases()) {
    SCOPED_TRACE(describe(c));
    Rng rng(seed++, 0);
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (int i = 0; i < kSamples; ++i) {
      const auto s = bsdf_sample(c.b, c.wo, rng.uniform(), {rng.uniform(), rng.uniform()});
      if (!s) continue;
      for (int k = 0; k < 3; ++k) sum[k] += s->weight[k], sum2[k] += double(s->weight[k]) * s->weight[k];
    }
    for (int k = 0; k < 3; ++k) {
      auto f = [&](Vec3 wi) { return double(bsdf_eval(c.b, c.wo, wi)[k]); };
      const auto I = integrate_with_error(f, kPiD, kThetaSteps, kPhiSteps);
      const double mean = sum[k] / kSamples, sigma = std::sqrt((sum2[k] / kSamples - mean * mean) / kSamples);
      EXPECT_NEAR(mean, I.value, 4 * sigma + I.error + kFloatSlack) << "channel " << k;
      if (c.b.type == BSDF::Type::Conductor) {
        double f_max = 0;
        for (int j = 0; j <= 1000; ++j)
          f_max = std::max(f_max, double(fresnel_conductor(j / 1000.0f, c.b.cond_eta[k], c.b.cond_k[k])));
        EXPECT_LE(mean, f_max + 4 * sigma) << "channel " << k;
      }
      if (c.b.type == BSDF::Type::Dielectric) break;  // grey
    }
  }
}

// White furnace: undoing the radiance scaling 1/etap^2 of transmitted samples, the
// energy that leaves, R + T, is at most 1 (each such weight is G / G1(wo) <= 1). As
// alpha -> 0 it approaches the smooth dielectric's R + T = 1: the deficit shrinks with
// alpha, and at alpha = 0.01 it is below alpha (it is O(alpha^2) at these angles: masking
// 1 - G / G1 ~ Lambda ~ alpha^2 tan^2 theta / 4, and reflections below the horizon need
// microfacets in the GGX tail, probability ~ alpha^2 / tilt^2). The probability of
// reflection approaches F(cos theta_o): it is the mean of F(wo.m) over visible normals m,
// which stray from n by ~alpha on average, so it differs from F(cos theta_o) by at most
// alpha max |dF/dtheta| (over +-0.2 rad) besides the binomial error.
TEST(RoughBsdf, DielectricFurnace) {
  constexpr int n = 400'000;
  for (double theta_o : {0.5, kPiD - 0.3}) {  // from outside; from inside (below the critical angle)
    SCOPED_TRACE(theta_o);
    const Vec3 wo = about_normal(theta_o, 0.8);
    double previous_deficit = -1, previous_sigma = 0;
    for (float alpha : {1.0f, 0.5f, 0.2f, 0.05f, 0.01f}) {
      SCOPED_TRACE(alpha);
      const BSDF b = rough(BSDF::Type::Dielectric, alpha, alpha);
      Rng rng(17, uint64_t(alpha * 1000));
      double sum = 0, sum2 = 0;
      int reflected = 0;
      for (int i = 0; i < n; ++i) {
        const auto s = bsdf_sample(b, wo, rng.uniform(), {rng.uniform(), rng.uniform()});
        if (!s) continue;
        const double w = s->weight[0] * (s->transmission ? s->eta_scale : 1.0f);
        sum += w, sum2 += w * w;
        reflected += !s->transmission;
      }
      const double mean = sum / n, sigma = std::sqrt(std::max(sum2 / n - mean * mean, 0.0) / n);
      EXPECT_LE(mean, 1.0 + 4 * sigma);
      const double deficit = 1 - mean;
      if (previous_deficit >= 0) {
        EXPECT_LT(deficit, previous_deficit + 4 * std::hypot(sigma, previous_sigma));
      }
      previous_deficit = deficit, previous_sigma = sigma;
      if (alpha == 0.01f) {
        const float co = float(std::cos(theta_o));
        const double F = fresnel_dielectric(co, b.eta);
        double slope = 0;  // max |dF/dtheta| within 0.2 rad of theta_o
        for (double t = theta_o - 0.2; t <= theta_o + 0.2; t += 1e-3)
          slope = std::max(slope, std::abs(fresnel_dielectric(std::cos(t + 1e-4), double(b.eta)) -
                                           fresnel_dielectric(std::cos(t - 1e-4), double(b.eta))) /
                                      2e-4);
        const double p = double(reflected) / n, binomial = std::sqrt(F * (1 - F) / n);
        EXPECT_NEAR(p, F, 4 * binomial + alpha * slope);
        EXPECT_LT(deficit, alpha);
      }
    }
  }
}

}  // namespace
}  // namespace dermis
