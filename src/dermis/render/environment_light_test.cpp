// An image environment map lights the scene from the directions its mapping says: a
// diffuse sphere lit by a single bright texel is bright where its normal faces that
// texel's direction — found by the mapping's landmarks, not by the code under test —
// and black where it faces away. Equal-area is pbrt-v4's meaning; lat-long on request.
#include <gtest/gtest.h>

#include <cmath>

#include "dermis/render/image.h"
#include "dermis/render/integrator.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "dermis/scene/scene_test_util.h"

namespace dermis {
namespace {

void expect_lit_from(const std::string& map_path, const std::string& mapping, float texel_solid_angle, Vec3 w,
                     float L) {
  const std::string scene = R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" 30
Film "rgb" "integer xresolution" 24 "integer yresolution" 24
Integrator "volpath" "integer maxdepth" 1
WorldBegin
LightSource "infinite" "string filename" ")" +
                            map_path + "\"" + mapping + R"(
Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]
Shape "sphere"
)";
  Diagnostics diag;
  auto sc = build_render_scene(parse_scene_string(scene), diag);
  double rendered = 0, expected = 0, var = 0;
  int lit = 0, dark = 0;
  PathCounters counters;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x) {
      const Ray ray = sc->camera.generate_ray({x + 0.5f, y + 0.5f}, {0.5f, 0.5f});
      SurfaceHit hit;
      if (!sc->embree->intersect(ray, hit)) continue;
      const float cos_w = dot(hit.ng, w);
      if (std::abs(cos_w) < 0.2f) continue;  // away from the terminator (the texel is not a point)
      const int n = 256;
      double s = 0, s2 = 0;
      for (int i = 0; i < n; ++i) {
        Sampler sampler(SamplerKind::Independent, 1, uint64_t(y * 24 + x), uint32_t(i));
        const double v = trace_path(*sc, ray, -1, sampler, counters).average();
        s += v;
        s2 += v * v;
      }
      if (cos_w < 0) {
        EXPECT_EQ(s, 0.0) << "lit from behind at pixel " << x << ", " << y;
        ++dark;
        continue;
      }
      ++lit;
      rendered += s / n;
      var += std::max(0.0, s2 / n - (s / n) * (s / n)) / n;
      expected += 0.5 / kPiD * L * texel_solid_angle * cos_w;  // (rho / pi) L Omega cos
    }
  ASSERT_GT(lit, 20);
  ASSERT_GT(dark, 20);
  // 4 standard errors, plus 1% for cos varying across the texel (its half-width is
  // about 3.5 degrees: the mean of a linear function over it is its centre value, to
  // second order).
  EXPECT_NEAR(rendered, expected, 4 * std::sqrt(var) + 0.01 * expected);
}

// One bright texel (x, y) of a 32 x 32 equal-area map, lighting the sphere.
void expect_equal_area_texel_lights_from(int x, int y, Vec3 w) {
  test::TempDir dir;
  const int s = 32;
  Image img;
  img.width = img.height = s;
  img.pixels.assign(std::size_t(s) * s * 3, 0.0f);
  for (int c = 0; c < 3; ++c) img.pixels[3 * (y * s + x) + c] = 1000;
  const std::string path = dir.path() + "/sky_equiarea.exr";
  write_image(path, img);
  expect_lit_from(path, "", 4 * kPi / (s * s), w, 1000);
}

TEST(EnvironmentLight, EqualAreaTexelLightsFromItsDirection) {
  // The texel at the middle of the right edge, (u, v) = (31.5, 16.5) / 32: u' = 31/32,
  // v' = 1/32, r = 1 - |1 - u' - v'| = 1, so z = 0 and phi = pi/4 ((v' - u')/r + 1) =
  // 0.049: w = (cos 0.049, sin 0.049, 0), near +x (Clarberg 2008, sec. 3).
  const float phi_x = kPi / 4 * ((1.0f - 31.0f) / 32 + 1);
  expect_equal_area_texel_lights_from(31, 16, Vec3(std::cos(phi_x), std::sin(phi_x), 0));
  // The middle of the bottom edge (v grows down the image): u' = 1/32, v' = 31/32,
  // phi = pi/4 (30/32 + 1) = 1.522: near +y. A flipped or transposed image fails here.
  const float phi_y = kPi / 4 * ((31.0f - 1.0f) / 32 + 1);
  expect_equal_area_texel_lights_from(16, 31, Vec3(std::cos(phi_y), std::sin(phi_y), 0));
}

TEST(EnvironmentLight, LatLongTexelLightsFromItsDirectionWhenAsked) {
  test::TempDir dir;
  const int w = 64, h = 32;
  // Column 16 (phi = 16.5/64 2 pi), row 16 (theta = 16.5/32 pi): near +y, slightly below
  // the equator; its solid angle is 2 pi^2 sin(theta) / (w h).
  Image img;
  img.width = w;
  img.height = h;
  img.pixels.assign(std::size_t(w) * h * 3, 0.0f);
  for (int c = 0; c < 3; ++c) img.pixels[3 * (16 * w + 16) + c] = 1000;
  const std::string path = dir.path() + "/sky_latlong.exr";
  write_image(path, img);
  const float phi = 16.5f / 64 * 2 * kPi, theta = 16.5f / 32 * kPi;
  const Vec3 dir_w(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  expect_lit_from(path, " \"string mapping\" \"latlong\"", 2 * kPi * kPi * std::sin(theta) / (w * h), dir_w, 1000);
}

}  // namespace
}  // namespace dermis

namespace dermis {
namespace {

// pbrt-v4's "illuminance": a uniform sky of radiance L gives pi L on an upward surface;
// a map is scaled so that its upper hemisphere gives the illuminance asked for.
TEST(EnvironmentLight, IlluminanceNormalisesUniformAndImageSkies) {
  const std::string head = "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";
  Diagnostics diag;
  auto uniform = build_render_scene(
      parse_scene_string(head + "LightSource \"infinite\" \"rgb L\" [2 2 2] \"float illuminance\" 6.2831853\n"), diag);
  EXPECT_NEAR(uniform->lights.at(0).emission[0], 2.0f, 1e-5f);  // 2 pi = pi L
  test::TempDir dir;
  Image img;
  img.width = img.height = 16;
  img.pixels.assign(16 * 16 * 3, 0.5f);
  write_image(dir.path() + "/sky.exr", img);
  auto mapped = build_render_scene(parse_scene_string(head + "LightSource \"infinite\" \"string filename\" \"" +
                                                      dir.path() + "/sky.exr\" \"float illuminance\" 10\n"),
                                   diag);
  // A constant map of radiance c gives pi c: scaled to 10, its radiance is 10 / pi (to
  // 0.2%: the midpoint rule on 64 x 64 points, the horizon cutting the cells it crosses).
  EXPECT_NEAR(mapped->lights.at(0).environment->eval({0.3f, 0.4f, 0.866f})[0], 10 / kPi, 0.002f * 10 / kPi);
  EXPECT_NEAR(mapped->lights.at(0).environment->upper_hemisphere_illuminance(), 10.0f, 1e-3f);
}

}  // namespace
}  // namespace dermis
