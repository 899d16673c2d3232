// A small hair-like scene: vertical curves in a plane facing the camera, lit by a distant
// light from the camera's side, rendered through the parser as a pbrt-v4 user writes it
// (pbrt-v4's "hair" material: warned, diffuse). Direct light only (maxdepth 1): neighbours
// exchange no light, and the light, along the view axis, casts no shadow on a neighbour.
// A diffuse surface of reflectance rho under irradiance E at angle theta to its normal sends
// rho/pi E cos(theta), so a row's mean is rho E / pi times the integral of cos(theta) over the
// row's width in the hairs' plane, divided by that width.
// - A flat hair faces the ray: it covers w / cos(alpha) of the plane (alpha, the ray's angle
//   to the light) and its cosine is cos(alpha): the integral is exactly w.
// - A round hair is a cylinder of radius w/2 along y. The rays of a pinhole camera and the
//   normals of the cylinder all lie in planes of constant y after projection onto xz, so the
//   integral is one-dimensional: over x in the plane z = 0, the cosine at the ray's nearest
//   hit on the circle (exact ray-circle intersection, no Embree). Its value is (pi/4) w to
//   first order; the perspective makes the near side of the hair larger than its silhouette
//   (a relative 4 r / (3 pi D) = 1.1e-3 here at distance D) and the light's angle to the ray
//   adds alpha^3 / (3 pi): both are in the integral, not in a tolerance.
// The tolerance: 4 standard errors of the mean over kSeeds renders.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "dermis/render/renderer.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"

namespace dermis {
namespace {

constexpr int kHairs = 9, kSeeds = 12;
constexpr float kSpacing = 0.5f, kWidth = 0.1f, kHalfLength = 1.5f;

float hair_x(int k) { return kSpacing * float(k - kHairs / 2); }

// The integral over x, in the plane z = 0, of the cosine between a hair's normal and the
// light (which comes from -z), for the hair at x0 seen from a pinhole at (0, 0, -D).
double lit_width(double x0, double D, bool round) {
  if (!round) return kWidth;  // a flat hair: w / cos(alpha) wide, lit by cos(alpha)
  const double r = kWidth / 2;
  constexpr int kSteps = 200000;  // midpoint rule; the integrand is sqrt-like at the edges: error < 1e-7 of it
  const double a = x0 - 1.5 * r, h = 3 * r / kSteps;
  double sum = 0;
  for (int i = 0; i < kSteps; ++i) {
    const double x = a + (i + 0.5) * h;
    const double len = std::hypot(x, D), dx = x / len, dz = D / len;  // the ray through (x, 0)
    const double fx = -x0, fz = -D;                                   // its origin less the hair's centre
    const double b = fx * dx + fz * dz, disc = b * b - (fx * fx + fz * fz - r * r);
    if (disc < 0) continue;
    const double t = -b - std::sqrt(disc);  // the near hit
    const double nz = (-D + t * dz) / r;    // the normal's z
    sum += std::max(0.0, -nz) * h;
  }
  return sum;
}

std::string hair_scene(const std::string& type) {
  std::string s =
      "LookAt 0 0 -20  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n"
      "Film \"rgb\" \"integer xresolution\" 64 \"integer yresolution\" 64\nPixelFilter \"box\"\n"
      "Integrator \"volpath\" \"integer maxdepth\" 1\nWorldBegin\n"
      "LightSource \"distant\" \"point3 from\" [0 0 -1] \"point3 to\" [0 0 0] \"rgb L\" [2 2 2]\n"
      "Material \"hair\" \"rgb reflectance\" [0.5 0.5 0.5] \"float eumelanin\" 1.3\n";
  for (int k = 0; k < kHairs; ++k) {
    const float x = hair_x(k);
    s += "Shape \"curve\" \"string type\" \"" + type + "\" \"float width\" " + std::to_string(kWidth) +
         " \"point3 P\" [";
    for (int i = 0; i < 4; ++i)
      s += " " + std::to_string(x) + " " + std::to_string(-kHalfLength + 2 * kHalfLength * float(i) / 3) + " 0";
    s += " ]\n";
  }
  return s;
}

struct RowMean {
  double mean = 0, sigma = 0, expected = 0;
};

// The mean green value of the rows wholly within |y| <= 1 (clear of the hairs' ends), over
// kSeeds renders; sigma is the standard error of that mean across the seeds.
RowMean render_rows(const std::string& type) {
  SceneDesc d = parse_scene_string(hair_scene(type), "hair.pbrt");
  EXPECT_EQ(d.diagnostics.warnings.size(), 1u);
  for (const std::string& w : d.diagnostics.warnings) EXPECT_NE(w.find("material \"hair\""), std::string::npos) << w;
  Diagnostics diag;
  auto sc = build_render_scene(d, diag);
  // Where pixel centres meet the hairs' plane z = 0.
  auto on_plane = [&](float fx, float fy) {
    const Ray r = sc->camera.generate_ray({fx, fy}, {0.5f, 0.5f});
    return r.o + r.d * (-r.o.z / r.d.z);
  };
  const double W = on_plane(64, 32).x - on_plane(0, 32).x;  // the rows' width in the plane
  const double pixel = std::abs(W) / 64;
  const double E = d.lights.at(0).spectrum[1] * d.lights[0].scale, rho = 0.5;
  RowMean m;
  double lit = 0;  // the integral of cos(theta) over the hairs' width in the plane z = 0
  const double D = -sc->camera.generate_ray({32, 32}, {0.5f, 0.5f}).o.z;  // the pinhole's distance to z = 0
  for (int k = 0; k < kHairs; ++k) lit += lit_width(hair_x(k), D, type == "cylinder");
  m.expected = lit / std::abs(W) * rho * E / kPi;
  double sum = 0, sum2 = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    RenderOptions o;
    o.spp = 64;
    o.seed = uint64_t(seed + 1);
    const RenderResult r = render_image(*sc, o);
    EXPECT_EQ(r.nonfinite, 0u);
    double total = 0;
    int n = 0;
    for (int y = 0; y < r.height; ++y) {
      if (std::abs(on_plane(32, float(y) + 0.5f).y) + pixel / 2 > 1) continue;
      for (int x = 0; x < r.width; ++x, ++n) total += r.rgb[3 * (std::size_t(y) * r.width + x) + 1];
    }
    EXPECT_GT(n, 64 * 10);
    sum += total / n;
    sum2 += (total / n) * (total / n);
  }
  m.mean = sum / kSeeds;
  m.sigma = std::sqrt(std::max(0.0, (sum2 / kSeeds - m.mean * m.mean) / (kSeeds - 1)));
  return m;
}

TEST(CurveRender, RoundHairsAreLitAsCylindersSeenInPerspective) {
  const RowMean m = render_rows("cylinder");
  EXPECT_NEAR(m.mean, m.expected, 4 * m.sigma) << "sigma " << m.sigma << ", relative " << m.mean / m.expected - 1;
}

TEST(CurveRender, FlatHairsFaceTheCameraAndTheLight) {
  const RowMean m = render_rows("flat");
  EXPECT_NEAR(m.mean, m.expected, 4 * m.sigma) << "sigma " << m.sigma << ", relative " << m.mean / m.expected - 1;
}

}  // namespace
}  // namespace dermis
