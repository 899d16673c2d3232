// A subsurface object with a grid interior (SubsurfaceParams::interior): the random walk by
// null collisions (subsurface/heterogeneous_walk.h) against the volumetric path tracer in the
// same grid medium inside the same boundary (the `volumetric` method, and the medium inside a
// dielectric or an interface written out), in RGB and spectrally. Region means (4 x 4 pixels)
// agree within 4 standard errors of the difference.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>

#include "dermis/core/rng.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "support/lit_sphere_scene.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

// An n^3 density grid over a box around the unit sphere: a third of the voxels nearly empty,
// the rest up to `high` (veins of dense and thin medium, on a scale of the mean free path).
std::string random_densities(int n, float high, uint64_t seed) {
  Rng rng(seed, 9);
  std::string s = fmt::format("\"integer nx\" {0} \"integer ny\" {0} \"integer nz\" {0} \"float density\" [", n);
  for (int i = 0; i < n * n * n; ++i) s += fmt::format(" {}", rng.uniform() < 0.33f ? 0.05f : high * rng.uniform());
  return s + " ]";
}

std::string grid_medium(const std::string& name) {
  return fmt::format(
      "AttributeBegin\nRotate 20 1 1 0\nMakeNamedMedium \"{}\" \"string type\" \"uniformgrid\" "
      "\"rgb sigma_a\" [0.05 0.2 0.5] \"rgb sigma_s\" [2 3 4] \"float g\" 0.3 "
      "\"point3 p0\" [-1.2 -1.2 -1.2] \"point3 p1\" [1.2 1.2 1.2] {}\nAttributeEnd\n",
      name, random_densities(6, 2, 5));
}

struct Renders {
  testing::PixelStatistics a, b;
};
Renders render_both(const std::string& a, const std::string& b, int spp, bool spectral) {
  Diagnostics diag;
  auto sa = build_render_scene(parse_scene_string(a, "a.pbrt"), diag);
  auto sb = build_render_scene(parse_scene_string(b, "b.pbrt"), diag);
  return {testing::pixel_statistics(*sa, spp, 41, {}, spectral), testing::pixel_statistics(*sb, spp, 42, {}, spectral)};
}

// The `dielectric` boundary: the walk in the grid against the volumetric method (the object
// becomes a smooth dielectric filled with the grid medium), and against that scene written
// out with a MediumInterface; spectrally, too.
TEST(HeterogeneousInterior, WalkInAGridEqualsTheVolumetricPathTracer) {
  const std::string header = testing::lit_sphere_header(16) + grid_medium("veins");
  const std::string material = "Material \"subsurface\" \"string interior\" \"veins\" \"float eta\" 1.4 ";
  const std::string walk = header + material + "\nShape \"sphere\"\n";
  const std::string volumetric = header + material + "\"string method\" \"volumetric\"\nShape \"sphere\"\n";
  const std::string written_out =
      header + "MediumInterface \"veins\" \"\"\nMaterial \"dielectric\" \"float eta\" 1.4\nShape \"sphere\"\n";
  for (const bool spectral : {false, true}) {
    SCOPED_TRACE(spectral ? "spectral" : "rgb");
    Renders r = render_both(walk, volumetric, spectral ? 48 : 64, spectral);
    testing::expect_same_region_means(r.a, r.b, 4, 4);
  }
  Renders r = render_both(volumetric, written_out, 32, false);
  testing::expect_same_region_means(r.a, r.b, 4, 4);
}

// The `matched` boundary: the walk against the grid medium inside an index-matched interface.
TEST(HeterogeneousInterior, MatchedWalkInAGridEqualsTheMediumInsideAnInterface) {
  const std::string header = testing::lit_sphere_header(16) + grid_medium("veins");
  const std::string walk = header +
                           "Material \"subsurface\" \"string interior\" \"veins\" \"string boundary\" \"matched\"\n"
                           "Shape \"sphere\"\n";
  const std::string volume = header + "MediumInterface \"veins\" \"\"\nMaterial \"interface\"\nShape \"sphere\"\n";
  Renders r = render_both(walk, volume, 64, false);
  testing::expect_same_region_means(r.a, r.b, 4, 4);
}

// A grid of constant density (its samples' centres reaching past the sphere, where pbrt-v4's
// interpolation would fade) is the homogeneous medium of the same coefficients, named as the
// interior too (its coefficients copied into the material): the walk by null collisions
// against the homogeneous walk.
TEST(HeterogeneousInterior, AConstantGridIsTheHomogeneousInterior) {
  std::string ones;
  for (int i = 0; i < 8 * 8 * 8; ++i) ones += " 1";
  const std::string coefficients = "\"rgb sigma_a\" [0.05 0.2 0.5] \"rgb sigma_s\" [2 3 4] \"float g\" 0.3";
  const std::string header =
      testing::lit_sphere_header(16) + "MakeNamedMedium \"grid\" \"string type\" \"uniformgrid\" " + coefficients +
      " \"point3 p0\" [-1.2 -1.2 -1.2] \"point3 p1\" [1.2 1.2 1.2] \"integer nx\" 8 \"integer ny\" 8 "
      "\"integer nz\" 8 \"float density\" [" +
      ones + "]\nMakeNamedMedium \"same\" \"string type\" \"homogeneous\" " + coefficients + "\n";
  auto sphere = [&](const char* interior) {
    return header + "Material \"subsurface\" \"float eta\" 1.4 \"string interior\" \"" + interior +
           "\"\nShape \"sphere\"\n";
  };
  Renders r = render_both(sphere("grid"), sphere("same"), 64, false);
  testing::expect_same_region_means(r.a, r.b, 4, 4);
}

}  // namespace
}  // namespace dermis
