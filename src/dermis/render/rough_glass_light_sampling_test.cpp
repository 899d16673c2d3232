// Light sampling at rough glass (both sides of the surface), at a rough subsurface entry
// (its reflection lobe) and at a walk's rough exits (through the boundary from inside) changes the noise, never the
// mean: each scene rendered with and without it (EstimatorSwitches::rough_glass_nee, the estimator that finds emission
// there by BSDF sampling alone), independent samples, region means within 4 standard errors of the difference. The
// variance ratio (without / with) is printed; it must exceed one.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

// Lights seen through and in rough glass: a sphere of glass (lights reach its inside
// only through its surface: the transmission side's light sampling from inside), a pane
// with a light right behind it (from the camera's side, the light is on the
// transmission side) and a wide light above (reflection side), over a diffuse floor. The lights
// and roughnesses are large enough for BSDF sampling alone to converge at this sample
// count: with small lights and narrow lobes its rare hits make its sample variance (and
// so the 4 sigma) meaningless, and the comparison could not be trusted.
const char* kHeader = R"(LookAt 0 -5 1.2  0 0 0.7  0 0 1
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 16 "integer yresolution" 12
Integrator "volpath" "integer maxdepth" 12
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [3 3 3] "bool twosided" true
  Shape "trianglemesh" "point3 P" [-1 -2 3  1 -2 3  1 0 3  -1 0 3] "integer indices" [0 1 2 0 2 3]
AttributeEnd
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [9 6 3]
  Translate 1 0.75 0.8
  Shape "sphere" "float radius" 0.3
AttributeEnd
Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]
Shape "trianglemesh" "point3 P" [-6 -6 0  6 -6 0  6 6 0  -6 6 0] "integer indices" [0 1 2 0 2 3]
)";

const char* kGlass = R"(Material "dielectric" "float eta" 1.5 "float roughness" 0.4 "bool remaproughness" false
AttributeBegin
  Translate -1 0 0.8
  Shape "sphere" "float radius" 0.75
AttributeEnd
Material "dielectric" "float eta" 1.5 "float uroughness" 0.5 "float vroughness" 0.3 "bool remaproughness" false
Shape "trianglemesh" "point3 P" [0.2 0.2 0  1.9 0.2 0  1.9 0.2 1.7  0.2 0.2 1.7] "integer indices" [0 1 2 0 2 3]
)";

// A dark (strongly absorbing) subsurface sphere: its picture is mostly the rough entry's
// reflection, whose light sampling is what this compares.
const char* kSubsurface = R"(Material "subsurface" "rgb sigma_a" [3 3 3] "rgb sigma_s" [0.3 0.5 0.8] "float g" 0.3
  "float eta" 1.4 "float roughness" 0.2 "bool remaproughness" false "string method" "randomwalk"
AttributeBegin
  Translate -0.8 0 0.8
  Shape "sphere" "float radius" 0.75
AttributeEnd
)";

// A bright, scattering walk behind a rough `dielectric` boundary: most of its picture is
// light that leaves through the boundary from inside, sampled there at every crossing.
const char* kWalkExit = R"(Material "subsurface" "rgb sigma_a" [0.05 0.1 0.2] "rgb sigma_s" [2 3 4] "float g" 0.3
  "float eta" 1.4 "float roughness" 0.3 "bool remaproughness" false "string method" "randomwalk"
  "string boundary" "dielectric"
AttributeBegin
  Translate -0.8 0 0.8
  Shape "sphere" "float radius" 0.75
AttributeEnd
)";

// Region means agree; returns the ratio of the summed per-pixel variances, without / with.
double expect_same_mean_and_variance_ratio(const std::string& scene, int spp, uint64_t seed) {
  Diagnostics diag;
  auto sc = build_render_scene(parse_scene_string(scene, "test.pbrt"), diag);
  const auto with_nee = testing::pixel_statistics(*sc, spp, seed);
  sc->switches.rough_glass_nee = false;
  const auto bsdf_only = testing::pixel_statistics(*sc, spp, seed + 1);
  testing::expect_same_region_means(with_nee, bsdf_only, 4, 4);
  double var_with = 0, var_without = 0;
  for (std::size_t p = 0; p < with_nee.mean.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      var_with += double(with_nee.stderr_[p][c]) * with_nee.stderr_[p][c];
      var_without += double(bsdf_only.stderr_[p][c]) * bsdf_only.stderr_[p][c];
    }
  return var_without / var_with;
}

TEST(RoughGlassLightSampling, BothSidesKeepTheMeanAndLowerTheVariance) {
  const double ratio = expect_same_mean_and_variance_ratio(std::string(kHeader) + kGlass, 1000, 70);
  std::printf("rough glass: variance without / with light sampling %.2f\n", ratio);
  EXPECT_GT(ratio, 1.0);
}

TEST(RoughGlassLightSampling, RoughSubsurfaceEntryKeepsTheMeanAndLowersTheVariance) {
  const double ratio = expect_same_mean_and_variance_ratio(std::string(kHeader) + kSubsurface, 400, 80);
  std::printf("rough subsurface entry: variance without / with light sampling %.2f\n", ratio);
  EXPECT_GT(ratio, 1.0);
}

TEST(RoughGlassLightSampling, RoughWalkExitKeepsTheMeanAndLowersTheVariance) {
  const double ratio = expect_same_mean_and_variance_ratio(std::string(kHeader) + kWalkExit, 400, 90);
  std::printf("rough walk exit: variance without / with light sampling %.2f\n", ratio);
  EXPECT_GT(ratio, 1.0);
}

}  // namespace
}  // namespace dermis
