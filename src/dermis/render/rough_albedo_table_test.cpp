// The exact albedo inversion behind a rough boundary (Trowbridge-Reitz, pbrt-v4's
// roughness). Two checks on a thick slab under a uniform sky, measured with the path
// tracer (support/slab_albedo.h):
// - the half-space simulator's rough boundary against an independent reference, the
//   volumetric path tracer rendering a medium inside a rough dielectric;
// - a rough `subsurface` slab returns the reflectance asked for: its albedo is
//   R + T A, with R and T the rough dielectric's hemispherical reflectance and
//   transmittance from outside, estimated by sampling the renderer's BSDF.
// Tolerances: 4 standard errors of the difference.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "dermis/core/microfacet.h"
#include "dermis/core/rng.h"
#include "dermis/core/warp.h"
#include "dermis/materials/bsdf.h"
#include "dermis/render/subsurface/coefficients.h"
#include "dermis/sss/halfspace/halfspace.h"
#include "dermis/sss/walk/albedo_inversion.h"
#include "support/slab_albedo.h"

namespace dermis {
namespace {

constexpr double kEta = 1.4;

std::string rough_dielectric(double roughness) {
  return "\"float eta\" " + std::to_string(kEta) + " \"float roughness\" " + std::to_string(roughness);
}

float remapped_alpha(double roughness) { return roughness_to_alpha(float(roughness), true); }

// A medium of single-scattering albedo `alpha`, sigma_t = 1 and HG g inside a rough
// dielectric: the slab's albedo by the path tracer and by the half-space simulator
// (specular + albedo per unit incident power, diffuse incidence).
TEST(RoughAlbedoTable, HalfspaceEqualsAMediumInsideARoughDielectric) {
  const double alpha = 0.95, g = 0.3;
  for (double roughness : {0.1, 0.4}) {
    SCOPED_TRACE(roughness);
    const std::string a = std::to_string(1 - alpha), s = std::to_string(alpha);
    const std::string medium = "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [" + a + " " + a +
                               " " + a + "] \"rgb sigma_s\" [" + s + " " + s + " " + s + "] \"float g\" " +
                               std::to_string(g) + "\nMediumInterface \"m\" \"\"\nMaterial \"dielectric\" " +
                               rough_dielectric(roughness);
    const testing::MeanAndError slab = testing::slab_hemispherical_albedo(medium, 40000);

    sss::HalfspaceConfig c;
    c.albedo = alpha;
    c.g = g;
    c.eta = kEta;
    c.alpha_x = c.alpha_y = remapped_alpha(roughness);
    c.incidence = sss::Incidence::Diffuse;
    c.sampling = sss::WalkSampling::Dwivedi;  // as the tables
    c.paths = 200000;
    c.seed = 5;
    const sss::HalfspaceResult r = sss::simulate_halfspace(c);
    const double simulated = r.specular + r.albedo;
    // specular and albedo come from the same paths and exclude each other (negatively
    // correlated): adding their variances overstates the sum's, never understates it.
    const double sigma = std::sqrt(sqr(slab.stderr_) + sqr(r.specular_stderr) + sqr(r.albedo_stderr));
    std::printf("roughness %.2f: slab %.5f +- %.5f, half-space %.5f +- %.5f (specular %.4f, lost %.4f)\n", roughness,
                slab.mean, slab.stderr_, simulated, std::hypot(r.specular_stderr, r.albedo_stderr), r.specular, r.lost);
    EXPECT_NEAR(slab.mean, simulated, 4 * sigma);
  }
}

// R + A T per view direction, with R and T of the rough dielectric seen from outside:
// the mean over cosine-distributed directions of the sampled BSDF weight, reflected or
// transmitted (the power weight: times eta_scale). One estimator, so one standard error.
testing::MeanAndError boundary_prediction(double roughness, double A, int samples) {
  BSDF b;
  b.type = BSDF::Type::Dielectric;
  b.n = {0, 0, 1};
  b.eta = float(kEta);
  b.alpha_x = b.alpha_y = remapped_alpha(roughness);
  Rng rng(2024, 7);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < samples; ++i) {
    const Vec3 wo = sample_cosine_hemisphere({rng.uniform(), rng.uniform()});
    const float u_lobe = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    const auto s = bsdf_sample(b, wo, u_lobe, {u1, u2});
    double v = 0;
    if (s) v = s->transmission ? A * s->weight.average() * s->eta_scale : s->weight.average();
    sum += v, sum2 += v * v;
  }
  const double mean = sum / samples;
  return {mean, std::sqrt(std::max(0.0, sum2 / samples - mean * mean) / samples)};
}

// The single-scattering microfacet model loses energy at every rough boundary hit from
// inside, so behind a rough `dielectric` boundary even a medium that absorbs nothing
// returns less than everything: A_max = A(alpha = 1) < 1 (the table's node 0). A request
// above it is rendered as A_max (the inversion gives alpha = 1).
double most_returned(const std::string& boundary, double roughness, double* error) {
  SubsurfaceParams p;
  p.reflectance = RGB(0.5f);
  p.mfp = RGB(1);
  p.eta = float(kEta);
  p.uroughness = p.vroughness = float(roughness);
  p.boundary = boundary == "dielectric" ? SubsurfaceParams::Boundary::Dielectric : SubsurfaceParams::Boundary::Diffuse;
  const sss::AlbedoInversion* table = albedo_inversion_for(p);
  *error = table->node_stderrs()[0];
  return table->surface_albedo(1.0);
}

void expect_slab_returns(const std::string& boundary, double roughness, double A) {
  double max_error = 0;
  const double A_max = most_returned(boundary, roughness, &max_error);
  if (A > A_max) {
    // Not renderable: a finite slab of a medium that absorbs nothing loses light through
    // its far faces (it is no half-space). The inversion gives alpha = 1.
    std::printf("%s roughness %.2f A %.2f above A_max %.4f\n", boundary.c_str(), roughness, A, A_max);
    return;
  }
  const std::string material = "Material \"subsurface\" \"rgb reflectance\" [" + std::to_string(A) + " " +
                               std::to_string(A) + " " + std::to_string(A) + "] \"rgb mfp\" [1 1 1] " +
                               rough_dielectric(roughness) +
                               " \"string method\" \"randomwalk\" \"string boundary\" \"" + boundary + "\"";
  const testing::MeanAndError slab = testing::slab_hemispherical_albedo(material, 20000);
  const bool clamped = false;
  const double returned = clamped ? A_max : A;
  const testing::MeanAndError expected = boundary_prediction(roughness, returned, 1000000);
  const testing::MeanAndError transmitted = boundary_prediction(roughness, 1.0, 1000000);
  const testing::MeanAndError reflected = boundary_prediction(roughness, 0.0, 1000000);
  // The extrapolated A_max's own error enters through T when the request is clamped.
  const double sigma = std::sqrt(sqr(slab.stderr_) + sqr(expected.stderr_) +
                                 (clamped ? sqr((transmitted.mean - reflected.mean) * max_error) : 0.0));
  std::printf("%s roughness %.2f A %.2f (A_max %.4f +- %.4f): slab %.5f +- %.5f, expected %.5f +- %.5f\n",
              boundary.c_str(), roughness, A, A_max, max_error, slab.mean, slab.stderr_, expected.mean, sigma);
  EXPECT_NEAR(slab.mean, expected.mean, 4 * sigma) << boundary << " roughness " << roughness << " A " << A;
}

// A = 0.3, 0.6, 0.9 at roughness 0.1 and 0.4: returned exactly up to A_max (0.72 and
// 0.55 for these), A_max above it.
TEST(RoughAlbedoTable, RoughSlabReturnsTheRequestedReflectance) {
  for (double roughness : {0.1, 0.4})
    for (double A : {0.3, 0.6, 0.9}) expect_slab_returns("dielectric", roughness, A);
  // The `diffuse` boundary enters through the rough dielectric and leaves through the
  // exit lobe at the first crossing, losing nothing: its table is rough at the entry
  // only, A_max = 1.
  double error = 0;
  EXPECT_EQ(most_returned("diffuse", 0.4, &error), 1.0);
  expect_slab_returns("diffuse", 0.4, 0.9);
}

}  // namespace
}  // namespace dermis
