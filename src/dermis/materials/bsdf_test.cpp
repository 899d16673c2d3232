// Tests of the surface scattering functions: sampling against eval and pdf, and the
// normalised-Fresnel exit lobe.
#include "dermis/materials/bsdf.h"

#include <gtest/gtest.h>

#include "dermis/core/frame.h"
#include "dermis/core/fresnel.h"
#include "dermis/core/rng.h"
#include "dermis/core/warp.h"

namespace dermis {
namespace {

TEST(Bsdf, DielectricSamplingSplitsEnergyByFresnel) {
  BSDF b;
  b.type = BSDF::Type::Dielectric;
  b.n = {0, 0, 1};
  b.eta = 1.5f;
  Vec3 wo = normalize(Vec3(0.5f, 0.2f, 0.7f));
  float F = fresnel_dielectric(wo.z, 1.5f);
  Rng rng(3, 4);
  int reflected = 0, n = 200000;
  for (int i = 0; i < n; ++i) {
    auto s = bsdf_sample(b, wo, rng.uniform(), {rng.uniform(), rng.uniform()});
    ASSERT_TRUE(s);
    if (!s->transmission) {
      ++reflected;
      EXPECT_NEAR(dot(s->wi, b.n), dot(wo, b.n), 1e-5);
    } else {
      EXPECT_NEAR(s->weight[0], 1 / (1.5f * 1.5f), 1e-6);
    }
  }
  // Binomial: within 4 standard errors.
  double p = double(reflected) / n, sigma = std::sqrt(F * (1 - F) / n);
  EXPECT_NEAR(p, F, 4 * sigma);
}

TEST(Bsdf, LambertPdfMatchesSampledDirections) {
  BSDF b;
  b.n = normalize(Vec3(0.3f, -0.2f, 0.9f));
  b.albedo = RGB(0.8f);
  Vec3 wo = normalize(Vec3(0.1f, 0.4f, 0.9f));
  Rng rng(5, 6);
  for (int i = 0; i < 1000; ++i) {
    auto s = bsdf_sample(b, wo, rng.uniform(), {rng.uniform(), rng.uniform()});
    ASSERT_TRUE(s);
    EXPECT_GT(dot(s->wi, b.n), 0);
    EXPECT_NEAR(s->pdf, bsdf_pdf(b, wo, s->wi), 1e-4);
    RGB f = bsdf_eval(b, wo, s->wi);
    EXPECT_NEAR(s->weight[0], f[0] / s->pdf, 1e-4);
  }
  // Light arriving from the other side is not reflected.
  EXPECT_EQ(bsdf_eval(b, wo, -wo)[0], 0.0f);
}

TEST(SubsurfaceExitLobe, IntegratesToOneAgainstCosine) {
  for (float eta : {1.0f, 1.2f, 1.33f, 1.5f, 2.0f}) {
    BSDF b;
    b.type = BSDF::Type::SubsurfaceExit;
    b.n = normalize(Vec3(0.2f, 0.1f, 1));
    b.eta = eta;
    b.sw_norm = subsurface_exit_normalization(eta);
    // Midpoint rule in (theta, phi) over the hemisphere of n, independent of the
    // Gauss-Legendre rule inside subsurface_exit_normalization.
    Frame f(b.n);
    const int nt = 1024, np = 64;
    double sum = 0;
    for (int i = 0; i < nt; ++i)
      for (int j = 0; j < np; ++j) {
        double th = (i + 0.5) / nt * kPiD / 2, ph = (j + 0.5) / np * 2 * kPiD;
        Vec3 wi = f.to_world(
            Vec3(float(std::sin(th) * std::cos(ph)), float(std::sin(th) * std::sin(ph)), float(std::cos(th))));
        sum += bsdf_eval(b, Vec3(0, 0, 1), wi)[0] * std::sin(th) * (kPiD / 2 / nt) * (2 * kPiD / np);
      }
    EXPECT_NEAR(sum, 1.0, 2e-4) << "eta " << eta;
    if (eta == 1.0f) {
      EXPECT_NEAR(b.sw_norm, 1.0f, 1e-6);
    }
  }
}

TEST(SubsurfaceExitLobe, SampleWeightsAreFOverPdf) {
  BSDF b;
  b.type = BSDF::Type::SubsurfaceExit;
  b.n = {0, 0, 1};
  b.eta = 1.4f;
  b.sw_norm = subsurface_exit_normalization(1.4f);
  Rng rng(8, 9);
  double mean = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    auto s = bsdf_sample(b, Vec3(0, 0, 1), rng.uniform(), {rng.uniform(), rng.uniform()});
    ASSERT_TRUE(s);
    EXPECT_NEAR(s->weight[0], bsdf_eval(b, {0, 0, 1}, s->wi)[0] / s->pdf, 1e-4);
    mean += s->weight[0];
  }
  // E[weight] = integral of Sw cos = 1; the weight lies in [0, 1/c], so its standard
  // deviation is below 1/c and 4 standard errors are below 4/(c sqrt(n)).
  EXPECT_NEAR(mean / n, 1.0, 4.0 / (b.sw_norm * std::sqrt(double(n))));
}

// c = 1 - 2 FM1(eta): the one Fresnel-moment quadrature of core/fresnel.h.
TEST(SubsurfaceExitLobe, NormalizationIsOneMinusDiffuseReflectance) {
  for (float eta : {0.8f, 1.0f, 1.33f, 1.5f})
    EXPECT_EQ(subsurface_exit_normalization(eta), float(1 - fresnel_diffuse_reflectance(eta)));
}

}  // namespace
}  // namespace dermis
