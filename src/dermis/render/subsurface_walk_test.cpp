// The random-walk subsurface method against the foundation's volumetric path tracer:
// with the `dielectric` boundary it is the same physics as a homogeneous medium inside
// a dielectric, with `matched` the same as a medium inside an index-matched interface.
// Region means agree within 4 standard errors (of the difference).
#include <gtest/gtest.h>

#include <cmath>

#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "support/lit_sphere_scene.h"
#include "support/pilot_strategy_scenes.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

const std::string kHeader = testing::lit_sphere_header(16);
const char* kCoefficients = R"("rgb sigma_a" [0.05 0.15 0.3] "rgb sigma_s" [2 3 4] "float g" 0.3)";

void expect_same_picture(const std::string& a, const std::string& b, int spp) {
  testing::expect_same_picture(a, b, spp, 31);
}

TEST(SubsurfaceRandomWalk, DielectricBoundaryEqualsAMediumInsideADielectric) {
  for (const char* sampling : {"classical", "mis"}) {
    SCOPED_TRACE(sampling);
    std::string walk = kHeader + "Material \"subsurface\" " + kCoefficients +
                       " \"float eta\" 1.4 \"string method\" \"randomwalk\" \"string boundary\" \"dielectric\" "
                       "\"string walksampling\" \"" +
                       sampling + "\"\nShape \"sphere\"\n";
    std::string volume = kHeader + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" " + kCoefficients +
                         "\nMediumInterface \"m\" \"\"\nMaterial \"dielectric\" \"float eta\" 1.4\nShape \"sphere\"\n";
    expect_same_picture(walk, volume, 96);
  }
}

// The strategies the render's pilot may choose (render/subsurface_pilot.h) against the
// brute-force reference: no guided flights and the channels drawn by throughput alone
// (channel preference 0), and the larger guided share of 0.8, the walk with the
// dielectric boundary against the medium inside a dielectric, region means within 4
// standard errors (512 samples: a 5 % bias fails, which the helper asserts). Its false-failure
// rate, measured over 200 seeds with bench/statistics/: docs/testing.md.
TEST(SubsurfaceRandomWalk, ThePilotsStrategiesEqualAMediumInsideADielectric) {
  for (const char* strategy : testing::kPilotStrategies) {
    SCOPED_TRACE(strategy);
    testing::expect_same_picture(testing::pilot_strategy_walk_scene(strategy), testing::pilot_strategy_volume_scene(),
                                 512, 31, 0.05);
  }
}

// A rough boundary (Trowbridge-Reitz, pbrt-v4's roughness): the walk enters through the
// sampled rough dielectric and leaves or reflects internally at every boundary hit by
// sampling it from inside; the same physics as the medium inside a rough dielectric.
TEST(SubsurfaceRandomWalk, RoughDielectricBoundaryEqualsAMediumInsideARoughDielectric) {
  const std::string rough = " \"float eta\" 1.4 \"float roughness\" 0.3";
  std::string walk = kHeader + "Material \"subsurface\" " + kCoefficients + rough +
                     " \"string method\" \"randomwalk\" \"string boundary\" \"dielectric\"\nShape \"sphere\"\n";
  std::string volume = kHeader + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" " + kCoefficients +
                       "\nMediumInterface \"m\" \"\"\nMaterial \"dielectric\"" + rough + "\nShape \"sphere\"\n";
  expect_same_picture(walk, volume, 96);
  // And the volumetric method with the same parameters is that rough dielectric.
  std::string volumetric = kHeader + "Material \"subsurface\" " + kCoefficients + rough +
                           " \"string method\" \"volumetric\"\nShape \"sphere\"\n";
  expect_same_picture(volumetric, volume, 96);
}

// The same rough boundary lit only by delta lights (a distant and a point light): they are
// reached from inside only by sampling them through the boundary at the walk's exits, as
// the volumetric path tracer samples them through rough glass from inside.
TEST(SubsurfaceRandomWalk, RoughDielectricBoundarySeesDeltaLights) {
  const std::string header = R"(LookAt 0 -4 1.5  0 0 0  0 0 1
Camera "perspective" "float fov" 34
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
LightSource "distant" "point3 from" [1 -1 2] "point3 to" [0 0 0] "rgb L" [2 2 2]
LightSource "point" "point3 from" [-1.5 -1 -1] "rgb I" [3 3 3]
)";
  const std::string rough = " \"float eta\" 1.4 \"float roughness\" 0.3";
  std::string walk = header + "Material \"subsurface\" " + kCoefficients + rough +
                     " \"string method\" \"randomwalk\" \"string boundary\" \"dielectric\"\nShape \"sphere\"\n";
  std::string volume = header + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" " + kCoefficients +
                       "\nMediumInterface \"m\" \"\"\nMaterial \"dielectric\"" + rough + "\nShape \"sphere\"\n";
  expect_same_picture(walk, volume, 96);
}

// The default sampler (Owen-scrambled Sobol') changes the noise, never the mean: the
// walk behind a dielectric (MIS sampling, internal reflections, exit lobe, NEE at the
// exit) with 12 randomisations of 32 Sobol' samples against 256 independent samples.
TEST(SubsurfaceRandomWalk, SobolSamplerGivesTheMeanOfIndependentSampling) {
  Diagnostics diag;
  auto sc = build_render_scene(
      parse_scene_string(kHeader + "Material \"subsurface\" " + kCoefficients +
                         " \"float eta\" 1.4 \"string method\" \"randomwalk\" \"string boundary\" \"dielectric\"\n"
                         "Shape \"sphere\"\n"),
      diag);
  testing::expect_same_region_means(testing::replicated_pixel_statistics(*sc, SamplerKind::Sobol, 32, 12, 40),
                                    testing::pixel_statistics(*sc, 256, 41), 4, 4);
}

// Splitting the camera's first subsurface hit (reflection F and transmission 1 - F, both
// followed) against choosing one by Fresnel: the same mean within 4σ.
TEST(SubsurfaceRandomWalk, SplittingTheEntryKeepsTheMean) {
  Diagnostics diag;
  auto sc =
      build_render_scene(parse_scene_string(kHeader + "Material \"subsurface\" " + kCoefficients +
                                            " \"float eta\" 1.4 \"string method\" \"randomwalk\"\nShape \"sphere\"\n"),
                         diag);
  const auto split = testing::pixel_statistics(*sc, 192, 70);
  sc->switches.split_first_hit = false;
  testing::expect_same_region_means(split, testing::pixel_statistics(*sc, 192, 71), 4, 4);
}

// Several exits at the camera's first entry (Integrator "subsurfacesamples"), their direct
// light averaged and each going on with 1/n of its weight, against one: the same picture
// within 4 sigma, for the walk's exit lobe and for probes (disk, Burley).
TEST(SubsurfaceRandomWalk, SeveralExitsAtTheFirstEntryKeepTheMean) {
  for (const char* method :
       {"\"string method\" \"randomwalk\"", "\"string method\" \"disk\" \"string profile\" \"burley\""}) {
    SCOPED_TRACE(method);
    const std::string object = std::string("Material \"subsurface\" ") + kCoefficients + " \"float eta\" 1.4 " +
                               method + "\nShape \"sphere\"\n";
    const std::string one = kHeader + object;
    std::string four = kHeader + object;
    four.replace(four.find("\"integer maxdepth\""), 0, "\"integer subsurfacesamples\" 4 ");
    std::string single = one;
    single.replace(single.find("\"integer maxdepth\""), 0, "\"integer subsurfacesamples\" 1 ");
    expect_same_picture(four, single, 96);
  }
}

// On a floor: paths that leave the floor's diffuse bounce meet the sphere a second time,
// where the entry is not split and its reflection shows a light's mirror image (a caustic
// on the floor). The walk, whose entries add the emission a reflection meets at every
// entry (weight F), against the medium inside a dielectric, whose reflection is chosen by
// Fresnel: the same picture within 4 sigma. Then that emission added at every entry (and at
// every hit on smooth glass) and found only on the reflected paths: the same picture, the
// variance lower.
TEST(SubsurfaceRandomWalk, ReflectionAtALaterEntryKeepsTheMeanWithLessVariance) {
  // A small bright light beside the sphere, low: its mirror image in the sphere lights the floor.
  const std::string small_light = R"(AttributeBegin
  AreaLightSource "diffuse" "rgb L" [200 200 200]
  Translate 2.5 0.5 -0.6
  Shape "sphere" "float radius" 0.15
AttributeEnd
)";
  const std::string floor = R"(AttributeBegin
  Material "diffuse" "rgb reflectance" [0.8 0.8 0.8]
  Shape "trianglemesh" "point3 P" [-6 -6 -1  6 -6 -1  6 6 -1  -6 6 -1] "integer indices" [0 1 2  0 2 3]
AttributeEnd
)";
  const std::string walk = kHeader + small_light + floor + "Material \"subsurface\" " + kCoefficients +
                           " \"float eta\" 1.4 \"string method\" \"randomwalk\" \"string boundary\" \"dielectric\"\n"
                           "Shape \"sphere\"\n";
  const std::string volume =
      kHeader + small_light + floor + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" " + kCoefficients +
      "\nMediumInterface \"m\" \"\"\nMaterial \"dielectric\" \"float eta\" 1.4\nShape \"sphere\"\n";
  expect_same_picture(walk, volume, 128);

  // The variance: a sphere that absorbs all it lets in (no scattering, sigma_a 50 per unit)
  // on the floor, lit by a spherical light alone (no sky), its mirror image on the floor
  // frequent; the camera's entries not split either, so that every entry takes the branch.
  // The same for smooth glass around that absorbing medium (the path tracer's glass).
  const std::string absorbing = R"("rgb sigma_a" [50 50 50] "rgb sigma_s" [0 0 0])";
  for (const std::string& sphere :
       {"Material \"subsurface\" " + absorbing + " \"float eta\" 1.4 \"string method\" \"randomwalk\"\n",
        "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" " + absorbing +
            "\nMediumInterface \"m\" \"\"\nMaterial \"dielectric\" \"float eta\" 1.4\n"}) {
    SCOPED_TRACE(sphere);
    Diagnostics diag;
    auto sc = build_render_scene(parse_scene_string(R"(LookAt 0 -4 1.5  0 0 0  0 0 1
Camera "perspective" "float fov" 34
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [4 4 4]
  Translate 1 -3 3
  Shape "sphere" "float radius" 1
AttributeEnd
)" + floor + sphere + "Shape \"sphere\"\n"),
                                 diag);
    sc->switches.split_first_hit = false;
    const auto every = testing::pixel_statistics(*sc, 256, 80);
    sc->switches.reflection_emission = false;
    const auto only_reflected = testing::pixel_statistics(*sc, 256, 81);
    testing::expect_same_region_means(every, only_reflected, 4, 4);
    double v_every = 0, v_chosen = 0;
    for (std::size_t p = 0; p < every.mean.size(); ++p)
      for (int c = 0; c < 3; ++c) {
        v_every += double(every.stderr_[p][c]) * every.stderr_[p][c];
        v_chosen += double(only_reflected.stderr_[p][c]) * only_reflected.stderr_[p][c];
      }
    std::printf("variance, emission at every hit / on reflected paths only: %.3f\n", v_every / v_chosen);
    // Nothing comes out of the sphere, so every pixel's variance from the reflection's
    // choice, F (1 - F) Le^2, becomes the beyond term's alone: 0.2 of it here; at most half.
    EXPECT_LT(v_every, 0.5 * v_chosen);
  }
}

// A thin slab (0.8 to 1.7 mean free paths thick) lit from behind: most of what the camera
// sees has crossed it, the case backward guiding is for. The walk with backward guiding
// (Dwivedi-only and MIS) against the medium inside a dielectric.
TEST(SubsurfaceRandomWalk, BackwardGuidingOnABacklitThinSlabEqualsAMediumInsideADielectric) {
  const std::string header = R"(LookAt 0 -4 0.3  0 0 0  0 0 1
Camera "perspective" "float fov" 36
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
LightSource "infinite" "rgb L" [0.2 0.2 0.25]
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [8 8 8]
  Translate 0.3 2.5 0.6
  Shape "sphere" "float radius" 0.6
AttributeEnd
)";
  const std::string box = R"(Shape "trianglemesh" "point3 P" [-1 -0.2 -1  1 -0.2 -1  1 0.2 -1  -1 0.2 -1
                                  -1 -0.2 1  1 -0.2 1  1 0.2 1  -1 0.2 1]
  "integer indices" [0 2 1  0 3 2   4 5 6  4 6 7   0 1 5  0 5 4   1 2 6  1 6 5   2 3 7  2 7 6   3 0 4  3 4 7]
)";
  const std::string volume = header + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" " + kCoefficients +
                             "\nMediumInterface \"m\" \"\"\nMaterial \"dielectric\" \"float eta\" 1.4\n" + box;
  for (const char* sampling : {"dwivedi", "mis"}) {
    SCOPED_TRACE(sampling);
    const std::string walk = header + "Material \"subsurface\" " + kCoefficients +
                             " \"float eta\" 1.4 \"string method\" \"randomwalk\" \"string boundary\" \"dielectric\" "
                             "\"string walksampling\" \"" +
                             sampling + "\" \"bool backwardguiding\" true\n" + box;
    expect_same_picture(walk, volume, 1024);
  }
}

TEST(SubsurfaceRandomWalk, MatchedBoundaryEqualsAMediumInsideAnInterface) {
  std::string walk = kHeader + "Material \"subsurface\" " + kCoefficients +
                     " \"string method\" \"randomwalk\" \"string boundary\" \"matched\"\nShape \"sphere\"\n";
  std::string volume = kHeader + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" " + kCoefficients +
                       "\nMediumInterface \"m\" \"\"\nMaterial \"interface\"\nShape \"sphere\"\n";
  // The walk leaves straight through the matched boundary without next-event estimation
  // at its exit; the medium inside an interface does next-event estimation inside:
  // different estimators of the same image.
  expect_same_picture(walk, volume, 96);
}

// The same with a strongly absorbing medium (albedo 0.75 / 0.6 / 0.5, about 5 mean free
// paths across): the volumetric path tracer's throughput falls below 1/2 within a few
// collisions, where Russian roulette in a medium that sees lights begins
// (render/russian_roulette.h); the walk has its own roulette (random_walk.h).
TEST(SubsurfaceRandomWalk, MatchedBoundaryEqualsAnAbsorbingMediumInsideAnInterface) {
  const char* absorbing = R"("rgb sigma_a" [1 2 2.5] "rgb sigma_s" [3 3 2.5] "float g" 0)";
  std::string walk = kHeader + "Material \"subsurface\" " + absorbing +
                     " \"string method\" \"randomwalk\" \"string boundary\" \"matched\"\nShape \"sphere\"\n";
  std::string volume = kHeader + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" " + absorbing +
                       "\nMediumInterface \"m\" \"\"\nMaterial \"interface\"\nShape \"sphere\"\n";
  expect_same_picture(walk, volume, 96);
}

}  // namespace
}  // namespace dermis

#include <cstdio>

#include "dermis/core/frame.h"
#include "dermis/core/rng.h"
#include "dermis/core/warp.h"
#include "dermis/materials/fresnel.h"
#include "dermis/render/integrator.h"
#include "dermis/render/subsurface/coefficients.h"
#include "support/slab_albedo.h"

namespace dermis {
namespace {

// Radiance leaving the top of a thick slab, averaged over cosine-distributed
// directions at its centre: with uniform light of radiance 1 this is the slab's
// hemispherical albedo, F_avg + (1 - F_avg) A, where A is the albedo per entering light
// under diffuse incidence (the table's definition) and F_avg = 2 integral F(mu) mu dmu.
void expect_slab_albedo(const std::string& boundary, double A, double eta, double tolerance_sigmas,
                        double* measured_A = nullptr, const std::string& extra = "") {
  const std::string material = "Material \"subsurface\" \"rgb reflectance\" [" + std::to_string(A) + " " +
                               std::to_string(A) + " " + std::to_string(A) + "] \"rgb mfp\" [1 1 1] \"float eta\" " +
                               std::to_string(eta) + " \"string method\" \"randomwalk\" \"string boundary\" \"" +
                               boundary + "\" " + extra;
  double F_avg = 0;
  const int nq = 20000;
  for (int i = 0; i < nq; ++i) {
    double mu = (i + 0.5) / nq;
    F_avg += 2 * fresnel_dielectric(float(mu), float(eta)) * mu / nq;
  }
  const testing::MeanAndError slab = testing::slab_hemispherical_albedo(material, 40000);
  double expected = F_avg + (1 - F_avg) * A;
  if (measured_A) *measured_A = (slab.mean - F_avg) / (1 - F_avg);
  EXPECT_NEAR(slab.mean, expected, tolerance_sigmas * slab.stderr_) << boundary << " A " << A << " eta " << eta;
}

TEST(SubsurfaceRandomWalk, ExactAlbedoTableMakesASlabReturnTheRequestedReflectance) {
  // Each boundary has its own table (dielectric; refracting entry with exit at the first
  // crossing; index-matched): within 4 sigma.
  expect_slab_albedo("dielectric", 0.6, 1.4, 4);
  expect_slab_albedo("diffuse", 0.5, 1.4, 4);
  expect_slab_albedo("matched", 0.35, 1.0, 4);
}

// The Lambertian entry (a cosine lobe under the surface) has a table of its own: the
// slab returns the requested reflectance within 4 sigma.
TEST(SubsurfaceRandomWalk, LambertianEntrySlabReturnsTheRequestedReflectance) {
  double measured = 0;
  expect_slab_albedo("diffuse", 0.5, 1.4, 4, &measured, "\"string entry\" \"lambertian\"");
  std::printf("diffuse boundary, Lambertian entry, A = 0.5 requested: %.4f\n", measured);
}

// A non-scattering slab of optical thickness 1 under a uniform sky, eta = 1: the light
// that reaches the far face leaves through the exit lobe and sees the sky (radiance 1).
// Seen from above, the Lambertian entry's radiance is the cosine-weighted transmittance
// 2 E3(1) = integral 2 mu e^{-1/mu} dmu, whatever the view; the refracted entry's is
// e^{-1/mu_view}. Both within 4 sigma of the closed forms.
TEST(SubsurfaceRandomWalk, LambertianEntryCrossesAThinSlabWithTheCosineWeightedTransmittance) {
  const std::string scene_text = std::string(R"(LookAt 0 0 10  0 0 0  0 1 0
Camera "perspective"
Film "rgb" "integer xresolution" 2 "integer yresolution" 2
Integrator "volpath" "integer maxdepth" 100
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Material "subsurface" "rgb sigma_a" [1 1 1] "rgb sigma_s" [0 0 0] "float eta" 1 "string walksampling" "classical" )");
  const std::string slab = R"(
Shape "trianglemesh" "point3 P" [-500 -500 -1  500 -500 -1  500 500 -1  -500 500 -1
                                  -500 -500 0  500 -500 0  500 500 0  -500 500 0]
  "integer indices" [0 2 1  0 3 2   4 5 6  4 6 7   0 1 5  0 5 4   1 2 6  1 6 5   2 3 7  2 7 6   3 0 4  3 4 7]
)";
  double two_e3 = 0;  // 2 E3(1), midpoint rule (error ~1e-11)
  const int nq = 200000;
  for (int i = 0; i < nq; ++i) {
    const double mu = (i + 0.5) / nq;
    two_e3 += 2 * mu * std::exp(-1 / mu) / nq;
  }
  const float view_mu = 0.8f;
  const Vec3 view(std::sqrt(1 - view_mu * view_mu), 0, view_mu);
  for (const bool lambertian : {true, false}) {
    Diagnostics diag;
    auto sc = build_render_scene(
        parse_scene_string(scene_text + (lambertian ? "\"string entry\" \"lambertian\"" : "") + slab), diag);
    const int n = 40000;
    double sum = 0, sum2 = 0;
    PathCounters counters;
    for (int i = 0; i < n; ++i) {
      Sampler rng(SamplerKind::Independent, 91, uint64_t(i), 0);
      const double L = trace_path(*sc, Ray{view * 1.0f, -view}, -1, rng, counters).average();
      sum += L, sum2 += L * L;
    }
    const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    const double expected = lambertian ? two_e3 : std::exp(-1.0 / view_mu);
    std::printf("%s entry: %.5f +- %.5f, closed form %.5f\n", lambertian ? "Lambertian" : "refracted", mean, se,
                expected);
    EXPECT_NEAR(mean, expected, 4 * se) << (lambertian ? "lambertian" : "refracted");
  }
}

TEST(SubsurfaceRandomWalk, VanDeHulstFitMissesTheReflectanceBehindADielectric) {
  // The fit ignores the boundary: behind eta = 1.4 the coefficients it gives are far
  // too absorbing (the walk helper measured |dA| up to 0.21). Measure it on the slab.
  SubsurfaceParams exact, fit;
  exact.reflectance = fit.reflectance = RGB(0.6f);
  exact.mfp = fit.mfp = RGB(1);
  exact.eta = fit.eta = 1.4f;
  exact.boundary = fit.boundary = SubsurfaceParams::Boundary::Dielectric;
  fit.albedo_inversion_fit = true;
  const Coefficients e = resolve_coefficients(exact), f = resolve_coefficients(fit);
  double alpha_exact = e.sigma_s[0] / (e.sigma_a[0] + e.sigma_s[0]),
         alpha_fit = f.sigma_s[0] / (f.sigma_a[0] + f.sigma_s[0]);
  std::printf("A = 0.6 behind eta 1.4: alpha exact %.5f, van de Hulst %.5f\n", alpha_exact, alpha_fit);
  EXPECT_GT(alpha_exact - alpha_fit, 0.01);
}

}  // namespace
}  // namespace dermis
