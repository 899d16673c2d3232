// Curves through Embree's curve primitives: the area a straight curve covers seen
// side-on, against its analytic projection (length x width, or x width cos(theta) for a
// ribbon turned by theta), by jittered parallel rays; and the normals each kind reports.
#include <gtest/gtest.h>

#include <cmath>

#include "dermis/core/rng.h"
#include "dermis/geometry/embree_scene.h"

namespace dermis {
namespace {

constexpr float kLength = 4, kWidth = 0.2f;

// A straight cubic Bézier along x from -kLength/2 to kLength/2 (control points at equal
// steps: the parameter is linear in x), of width kWidth; ribbons with normal `n`.
Shape straight_curve(Shape::CurveKind kind, Vec3 n = Vec3(0, 0, 1)) {
  Shape s;
  s.type = Shape::Type::Curve;
  s.curve_kind = kind;
  for (int i = 0; i < 4; ++i) {
    s.positions.push_back(Vec3(-kLength / 2 + kLength * float(i) / 3, 0, 0));
    s.curve_radii.push_back(kWidth / 2);
    if (kind == Shape::CurveKind::Ribbon) s.normals.push_back(normalize(n));
  }
  return s;
}

struct Coverage {
  double area = 0, sigma = 0, expected = 0;
};

// Rays along -z through one jittered point per h x h cell of the strip |x| <= kLength/2 -
// kWidth (away from the ends, whatever their caps), |y| <= kWidth: the estimate h^2 x hits
// is unbiased for the covered area. Only the cells an edge of the band (y = +-w/2) crosses
// are uncertain, each a Bernoulli of its covered fraction f: sigma = h^2 sqrt(sum f(1-f)).
Coverage side_on_coverage(const Shape& curve, float projected_width) {
  std::vector<Shape> shapes{curve};
  EmbreeScene scene;
  scene.build(shapes, {0}, {}, {});
  const float h = 0.0137f, x_half = kLength / 2 - kWidth;
  const int nx = int(2 * x_half / h), ny = int(2 * kWidth / h);
  Rng rng(11, 5);
  long hits = 0;
  double sum_var = 0;
  for (int j = 0; j < ny; ++j) {
    const float y0 = -kWidth + h * float(j);
    // The fraction of this row's cells inside |y| <= projected_width / 2.
    const double f =
        std::clamp((std::min(y0 + h, projected_width / 2) - std::max(y0, -projected_width / 2)) / h, 0.0f, 1.0f);
    sum_var += nx * f * (1 - f);
    for (int i = 0; i < nx; ++i) {
      const Vec3 o(-x_half + h * (float(i) + rng.uniform()), y0 + h * rng.uniform(), 10);
      SurfaceHit hit;
      hits += scene.intersect(Ray{o, Vec3(0, 0, -1)}, hit);
    }
  }
  Coverage c;
  c.area = double(h) * h * double(hits);
  c.sigma = double(h) * h * std::sqrt(sum_var);
  c.expected = double(nx) * h * projected_width;
  return c;
}

TEST(CurveCoverage, StraightCylinderSeenSideOnCoversLengthTimesWidth) {
  const Coverage c = side_on_coverage(straight_curve(Shape::CurveKind::Cylinder), kWidth);
  EXPECT_NEAR(c.area, c.expected, 4 * c.sigma) << "sigma " << c.sigma;
}

TEST(CurveCoverage, StraightFlatCurveSeenSideOnCoversLengthTimesWidth) {
  const Coverage c = side_on_coverage(straight_curve(Shape::CurveKind::Flat), kWidth);
  EXPECT_NEAR(c.area, c.expected, 4 * c.sigma) << "sigma " << c.sigma;
}

// A ribbon whose normal is turned 60 degrees from the view about the curve shows half its width.
TEST(CurveCoverage, RibbonTurnedBySixtyDegreesCoversHalfItsWidth) {
  const float theta = float(kPi / 3);
  const Coverage c = side_on_coverage(
      straight_curve(Shape::CurveKind::Ribbon, Vec3(0, std::sin(theta), std::cos(theta))), kWidth * std::cos(theta));
  EXPECT_NEAR(c.area, c.expected, 4 * c.sigma) << "sigma " << c.sigma;
}

// Normals: a round curve's points outward from its axis, a flat curve's faces the ray
// and a ribbon's is its given normal (on the given side); all across the tangent (x).
TEST(CurveHits, NormalsOfEachKind) {
  const Vec3 given = normalize(Vec3(0, 1, 1));
  for (Shape::CurveKind kind : {Shape::CurveKind::Cylinder, Shape::CurveKind::Flat, Shape::CurveKind::Ribbon}) {
    std::vector<Shape> shapes{straight_curve(kind, given)};
    EmbreeScene scene;
    scene.build(shapes, {0}, {}, {});
    Rng rng(7, 1);
    int hits = 0;
    for (int i = 0; i < 200; ++i) {
      const Vec3 d = normalize(Vec3(0.3f * (rng.uniform() - 0.5f), 0.4f * (rng.uniform() - 0.5f), -1));
      const Vec3 o = Vec3(2 * (rng.uniform() - 0.5f), 0.1f * (rng.uniform() - 0.5f), 0) - d * 5.0f;
      SurfaceHit h;
      if (!scene.intersect(Ray{o, d}, h)) continue;
      ++hits;
      EXPECT_NEAR(length(h.ng), 1, 1e-5f);
      EXPECT_NEAR(h.ng.x, 0, 1e-3f) << "across the tangent";
      EXPECT_GE(h.uv.y, 0);
      EXPECT_LE(h.uv.y, 1);
      EXPECT_NEAR(h.uv.x, (h.p.x + kLength / 2) / kLength, 1e-3f);
      if (kind == Shape::CurveKind::Cylinder) {
        EXPECT_NEAR(std::hypot(h.p.y, h.p.z), kWidth / 2, 1e-3f) << "on the tube";
        EXPECT_GT(dot(h.ng, normalize(Vec3(0, h.p.y, h.p.z))), 0.999f) << "outward";
      } else if (kind == Shape::CurveKind::Flat) {
        EXPECT_GT(dot(h.ng, -d), 0.0f) << "facing the ray";
        EXPECT_NEAR(dot(h.ng, normalize(Vec3(0, -d.y, -d.z))), 1, 1e-4f);
      } else {
        EXPECT_GT(dot(h.ng, given), 0.999f) << "the given normal";
      }
    }
    EXPECT_GT(hits, 20) << int(kind);
  }
}

// A ray leaving a flat curve does not find the band again (it turns to face every ray),
// at the top level and through an instance (whose filter sees the ray in object space).
void expect_rays_leaving_a_flat_curve_miss_it(bool instanced) {
  std::vector<Shape> shapes{straight_curve(Shape::CurveKind::Flat)};
  EmbreeScene scene;
  const Vec3 shift = instanced ? Vec3(5, 1, 0) : Vec3(0, 0, 0);
  if (instanced)
    scene.build(shapes, {}, {{0}}, {Instance{0, Transform::translate(Vec3d(5, 1, 0))}});
  else
    scene.build(shapes, {0}, {}, {});
  Rng rng(2, 2);
  int tested = 0;
  for (int i = 0; i < 500; ++i) {
    SurfaceHit h;
    const Vec3 o = shift + Vec3(2 * (rng.uniform() - 0.5f), 0.08f * (rng.uniform() - 0.5f), 5);
    if (!scene.intersect(Ray{o, Vec3(0, 0, -1)}, h)) continue;
    const Vec3 w = normalize(Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f));
    SurfaceHit again;
    EXPECT_FALSE(scene.intersect(Ray{offset_ray_origin(h.p, h.ng, w), w}, again)) << "at t " << again.t;
    ++tested;
  }
  EXPECT_GT(tested, 400);
}

TEST(CurveHits, RayLeavingAFlatCurveDoesNotHitItAgain) { expect_rays_leaving_a_flat_curve_miss_it(false); }
TEST(CurveHits, RayLeavingAnInstancedFlatCurveDoesNotHitItAgain) { expect_rays_leaving_a_flat_curve_miss_it(true); }

}  // namespace
}  // namespace dermis
