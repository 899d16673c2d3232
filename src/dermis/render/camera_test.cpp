// pbrt-v4's cameras: where each raster position's ray starts and where it goes.
#include "dermis/render/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"

namespace dermis {
namespace {

void expect_near(Vec3 a, Vec3 b, float tol, const std::string& what) {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

// The screen window [-aspect, aspect] x [-1, 1] (200 x 100 pixels), in camera-space units on
// the plane z = 0: raster (0, 0) is its top-left corner, raster (200, 100) its bottom-right.
TEST(CameraOrthographic, RaysLeaveTheScreenWindowAlongTheViewAxis) {
  const Camera c(Transform(), 90, 0, 1e6f, 200, 100, nullptr, Camera::Projection::Orthographic);
  const struct {
    Vec2 film;
    Vec3 origin;
  } cases[] = {{{0, 0}, {-2, 1, 0}}, {{200, 100}, {2, -1, 0}}, {{100, 50}, {0, 0, 0}}, {{150, 25}, {1, 0.5f, 0}}};
  for (const auto& k : cases) {
    const Ray r = c.generate_ray(k.film, {0.5f, 0.5f});
    expect_near(r.o, k.origin, 1e-6f, "origin");
    expect_near(r.d, Vec3(0, 0, 1), 1e-6f, "direction");
  }
  // A given screen window is used as written, in camera-space units.
  const std::array<float, 4> window{-3, 1, -0.5f, 0.5f};
  const Camera w(Transform(), 90, 0, 1e6f, 200, 100, &window, Camera::Projection::Orthographic);
  expect_near(w.generate_ray({0, 0}, {0.5f, 0.5f}).o, Vec3(-3, 0.5f, 0), 1e-6f, "window corner");
  expect_near(w.generate_ray({200, 100}, {0.5f, 0.5f}).o, Vec3(1, -0.5f, 0), 1e-6f, "window corner");
}

// The pinhole perspective camera: raster (x, y) is the screen point (sx, sy) = (w0 + x (w1 -
// w0) / xres, w3 - y (w3 - w2) / yres) on the plane z = 1 / tan(fov / 2), seen from the
// origin; under a placed and mirrored camera (as bench/vs_cycles' scenes: Scale -1 1 1 and a
// LookAt), computed here in double from the transform.
TEST(CameraPerspective, PinholeRaysFollowTheProjectionUnderAnyTransform) {
  const Transform place =
      Transform::scale({-1, 1, 1}) * Transform::look_at({-850, -1000, 150}, {0, 0, 10}, {0, 0, 1}).inverse();
  const int xres = 128, yres = 96;
  const double t = std::tan(36.0 * 3.14159265358979323846 / 360.0), aspect = double(xres) / yres;
  const Camera c(place, 36, 0, 1e6f, xres, yres);
  for (const Vec2 film : {Vec2(0, 0), Vec2(128, 96), Vec2(64, 48), Vec2(13.25f, 90.5f), Vec2(127.9f, 0.1f)}) {
    const double sx = -aspect + film.x * 2 * aspect / xres, sy = 1 - film.y * 2.0 / yres;
    const Vec3d d = normalize(place.vector(Vec3d(sx * t, sy * t, 1)));
    const Ray r = c.generate_ray(film, {0.5f, 0.5f});
    expect_near(r.o, Vec3(place.point(Vec3d(0, 0, 0))), 1e-3f, "origin (world units of 1000)");
    expect_near(r.d, Vec3(d), 2e-6f, "direction");
  }
}

// A thin lens: every lens sample's ray for one raster position passes through the pinhole
// ray's point on the plane of focus, for both projections.
TEST(CameraThinLens, RaysOfAPixelMeetOnThePlaneOfFocus) {
  for (const Camera::Projection p : {Camera::Projection::Perspective, Camera::Projection::Orthographic}) {
    const Camera pinhole(Transform(), 40, 0, 5, 64, 48, nullptr, p);
    const Camera lens(Transform(), 40, 0.3f, 5, 64, 48, nullptr, p);
    const Vec2 film(13.5f, 30.25f);
    const Ray r0 = pinhole.generate_ray(film, {0.5f, 0.5f});
    const Vec3 focus = r0.o + r0.d * (5 / r0.d.z);
    for (const Vec2 u : {Vec2(0.1f, 0.2f), Vec2(0.9f, 0.4f), Vec2(0.3f, 0.95f)}) {
      const Ray r = lens.generate_ray(film, u);
      EXPECT_GT(length(r.o - r0.o), 1e-3f);  // the lens moved the origin
      expect_near(r.o + r.d * ((5 - r.o.z) / r.d.z), focus, 1e-4f, "on the plane of focus");
    }
  }
}

// The parser: "orthographic" is read (no warning), its "fov" is an unused parameter, and the
// camera's transform places it as pbrt-v4 does.
TEST(CameraOrthographic, ParsedAndPlacedByLookAt) {
  const SceneDesc d = parse_scene_string(
      "LookAt 0 0 -10  0 0 0  0 1 0\nCamera \"orthographic\" \"float screenwindow\" [-2 2 -1 1]\n"
      "Film \"rgb\" \"integer xresolution\" 40 \"integer yresolution\" 20\nWorldBegin\n"
      "LightSource \"distant\" \"point3 from\" [0 0 -1] \"point3 to\" [0 0 0]\nShape \"sphere\"\n",
      "test.pbrt");
  EXPECT_TRUE(d.camera.orthographic);
  EXPECT_TRUE(d.diagnostics.warnings.empty()) << d.diagnostics.warnings.at(0);
  Diagnostics diag;
  auto sc = build_render_scene(d, diag);
  // pbrt's LookAt: camera +x is up x view = world +x here. Raster (10, 5) of 40 x 20 is the
  // window's point (-2 + 4 * 10/40, 1 - 2 * 5/20) = (-1, 0.5).
  const Ray r = sc->camera.generate_ray({10, 5}, {0.5f, 0.5f});
  expect_near(r.o, Vec3(-1, 0.5f, -10), 1e-5f, "origin");
  expect_near(r.d, Vec3(0, 0, 1), 1e-6f, "direction");
  const SceneDesc f = parse_scene_string("Camera \"orthographic\" \"float fov\" 30\nWorldBegin\n", "test.pbrt");
  bool unused = false;
  for (const std::string& w : f.diagnostics.warnings) unused |= w.find("fov") != std::string::npos;
  EXPECT_TRUE(unused);
}

}  // namespace
}  // namespace dermis
