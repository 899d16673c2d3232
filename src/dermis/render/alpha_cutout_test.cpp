// Alpha cut-outs (geometry/alpha_mask.h) through the whole pipeline: parsed "alpha"
// (constant or float texture), the Embree filters on closest-hit and any-hit queries,
// and a render of a light seen through a cut-out screen. References: the area fraction
// of a checkerboard, 1 - alpha for constant alpha, (1 - a)^2 for two screens; binomial
// standard errors, 4 sigma.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dermis/render/renderer.h"
#include "dermis/render/scene_assembly.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"

namespace dermis {
namespace {

std::unique_ptr<RenderScene> assemble(const std::string& world) {
  // A light, so that the scene is not warned as unlit; the tests trace rays only.
  SceneDesc d = parse_scene_string("WorldBegin\nLightSource \"point\"\n" + world, "alpha.pbrt");
  EXPECT_TRUE(d.diagnostics.warnings.empty()) << d.diagnostics.warnings.front();
  Diagnostics diag;
  return assemble_scene(d, diag);
}

// The unit square at height z, uv = xy, with the given extra parameters.
std::string square(float z, const std::string& params) {
  return "Shape \"trianglemesh\" \"point3 P\" [0 0 " + std::to_string(z) + " 1 0 " + std::to_string(z) + " 1 1 " +
         std::to_string(z) + " 0 1 " + std::to_string(z) +
         "] \"integer indices\" [0 1 2 0 2 3] \"point2 uv\" [0 0 1 0 1 1 0 1] " + params + "\n";
}

double four_sigma(double p, int n) { return 4 * std::sqrt(p * (1 - p) / n); }

TEST(AlphaCutout, CheckerboardCutsExactlyItsSquares) {
  auto sc = assemble(
      "Texture \"checks\" \"float\" \"checkerboard\" \"float uscale\" 4 \"float vscale\" 4 \"float tex1\" 1 "
      "\"float tex2\" 0\n" +
      square(0, "\"texture alpha\" \"checks\""));
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(0, 1);
  const int n = 40000;
  int blocked = 0, occluded = 0, wrong = 0;
  for (int i = 0; i < n; ++i) {
    const float x = U(rng), y = U(rng);
    // From below, in a random direction towards (x, y, 0).
    const Vec3 o(x + 0.5f * (U(rng) - 0.5f), y + 0.5f * (U(rng) - 0.5f), -1);
    const Ray r{o, normalize(Vec3(x, y, 0) - o), 10};
    SurfaceHit h;
    const bool hit = sc->embree->intersect(r, h);
    blocked += hit;
    occluded += sc->embree->occluded(r);
    const float fx = 4 * x - std::floor(4 * x), fy = 4 * y - std::floor(4 * y);
    const bool near_edge = std::min({fx, 1 - fx, fy, 1 - fy}) < 1e-3f;
    const bool solid = (int(std::floor(4 * x)) + int(std::floor(4 * y))) % 2 == 0;  // tex1 = 1
    wrong += !near_edge && hit != solid;
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(occluded, blocked);
  EXPECT_NEAR(double(blocked) / n, 0.5, four_sigma(0.5, n));
}

TEST(AlphaCutout, FractionalAlphaKeepsThatFractionOfHitsDeterministically) {
  auto one = assemble(square(0, "\"float alpha\" 0.3"));
  auto two = assemble(square(0, "\"float alpha\" 0.5") + square(0.5f, "\"float alpha\" 0.5"));
  auto none = assemble(square(0, "\"float alpha\" 0"));
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> U(0, 1);
  const int n = 40000;
  int hit_one = 0, occ_one = 0, repeat_differs = 0, through_two = 0, hit_none = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 target(0.1f + 0.8f * U(rng), 0.1f + 0.8f * U(rng), 0);
    // Steep enough (slope <= 0.05) to cross both screens inside the unit square.
    const Vec3 o = target + Vec3(0.2f * (U(rng) - 0.5f), 0.2f * (U(rng) - 0.5f), -2);
    const Ray r{o, normalize(target - o), 10};
    SurfaceHit h;
    const bool a = one->embree->intersect(r, h);
    hit_one += a;
    occ_one += one->embree->occluded(r);
    repeat_differs += one->embree->intersect(r, h) != a;
    through_two += !two->embree->occluded(r);
    hit_none += none->embree->intersect(r, h) || none->embree->occluded(r);
  }
  EXPECT_EQ(repeat_differs, 0);  // the same ray, the same answer
  EXPECT_EQ(hit_none, 0);
  EXPECT_NEAR(double(hit_one) / n, 0.3, four_sigma(0.3, n));
  EXPECT_NEAR(double(occ_one) / n, 0.3, four_sigma(0.3, n));
  // Two independent screens of alpha 0.5 let (1 - 0.5)^2 through (one number per ray, as
  // pbrt-v4 draws, would let 0.5 through).
  EXPECT_NEAR(double(through_two) / n, 0.25, four_sigma(0.25, n));
}

// An exact sphere whose alpha texture cuts away u < 1/2 (phi < pi: y > 0): a ray along
// -y passes the near side and stops on the far one; along +y it stops on the near side.
TEST(AlphaCutout, TexturedAlphaOnAnExactSphereUsesItsUv) {
  auto sc = assemble(
      "Texture \"half\" \"float\" \"checkerboard\" \"float uscale\" 2 \"float vscale\" 1 \"float tex1\" 0 "
      "\"float tex2\" 1\n"
      "Shape \"sphere\" \"texture alpha\" \"half\"\n");
  ASSERT_EQ(sc->shapes[0].type, Shape::Type::Sphere);
  SurfaceHit h;
  ASSERT_TRUE(sc->embree->intersect(Ray{{0.1f, 5, 0.2f}, {0, -1, 0}}, h));
  EXPECT_LT(h.p.y, -0.9f);
  ASSERT_TRUE(sc->embree->intersect(Ray{{0.1f, -5, 0.2f}, {0, 1, 0}}, h));
  EXPECT_LT(h.p.y, -0.9f);
  EXPECT_FALSE(sc->embree->occluded(Ray{{0.1f, 5, 0.2f}, {0, -1, 0}, 5}));  // reaches y = 0 only
  EXPECT_TRUE(sc->embree->occluded(Ray{{0.1f, 5, 0.2f}, {0, -1, 0}, 7}));
}

// An emitter (L = 1) behind a black screen of alpha 0.3, filling the view: the image is
// 0.7 on average. Standard error from the spread of the pixels.
TEST(AlphaCutout, LightSeenThroughAScreenIsDimmedByAlpha) {
  SceneDesc d = parse_scene_string(
      "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 10\n"
      "Film \"rgb\" \"integer xresolution\" 48 \"integer yresolution\" 48\n"
      "WorldBegin\n"
      "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [0 0 0]\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 "
      "1]\n"
      "Shape \"trianglemesh\" \"point3 P\" [-10 -10 1  -10 10 1  10 10 1  10 -10 1] \"integer indices\" [0 1 2 0 2 3]\n"
      "AttributeEnd\n"
      "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\n"
      "Shape \"trianglemesh\" \"point3 P\" [-10 -10 0  10 -10 0  10 10 0  -10 10 0] \"integer indices\" [0 1 2 0 2 3] "
      "\"float alpha\" 0.3\n",
      "alpha.pbrt");
  Diagnostics diag;
  auto sc = build_render_scene(d, diag);
  RenderOptions o;
  o.spp = 4;
  RenderResult r = render_image(*sc, o);
  double sum = 0, sum2 = 0;
  const int npix = r.width * r.height;
  for (int i = 0; i < npix; ++i) {
    const double v = r.rgb[3 * std::size_t(i) + 1];
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / npix, var = sum2 / npix - mean * mean;
  EXPECT_NEAR(mean, 0.7, 4 * std::sqrt(var / npix) + 1e-6) << "spread " << std::sqrt(var);
  EXPECT_GT(var, 0);  // pixels do differ: the test measures something
}

}  // namespace
}  // namespace dermis
