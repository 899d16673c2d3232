#include "dermis/geometry/embree_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "dermis/core/rng.h"
#include "dermis/geometry/sphere_tessellation.h"

namespace dermis {
namespace {

// The fast hit record (meshes with neither normals nor uvs: Embree's Ng, the point on the ray)
// against the one computed from the shape's own arrays, on a tessellated sphere hit by random
// rays from outside and from inside, placed at the top level, reversed, and through an instance.
void expect_hits_match_the_shape(bool flip, bool instanced) {
  Shape mesh;
  tessellate_sphere(1.5f, 12, mesh.positions, mesh.indices);
  for (Vec3& v : mesh.positions) v = v + Vec3(0.3f, -0.2f, 0.1f);
  mesh.flip_normals = flip;
  ASSERT_TRUE(mesh.normals.empty());
  ASSERT_TRUE(mesh.uvs.empty());
  std::vector<Shape> shapes{mesh};
  EmbreeScene scene;
  const Transform to_world = instanced ? Transform::translate(Vec3d(5, 0, 0)) : Transform();
  if (instanced)
    scene.build(shapes, {}, {{0}}, {Instance{0, to_world}});
  else
    scene.build(shapes, {0}, {}, {});
  Rng rng(3, 9);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 center = to_world.point(Vec3(0.3f, -0.2f, 0.1f));
    const bool inside = i % 2 == 1;
    Vec3 d = normalize(Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f));
    Vec3 o = inside ? center + Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 0.5f
                    : center - d * 10.0f + Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, 0.0f);
    SurfaceHit h;
    if (!scene.intersect(Ray{o, d}, h)) continue;
    ++hits;
    const Shape& s = shapes[h.shape];
    // The reference: the shape's triangle, its barycentric point and normal.
    const uint32_t* tri = &s.indices[3 * std::size_t(h.prim)];
    const Vec3 p0 = to_world.point(s.positions[tri[0]]), p1 = to_world.point(s.positions[tri[1]]),
               p2 = to_world.point(s.positions[tri[2]]);
    const Vec3 ng = normalize(to_world.normal(s.triangle_normal(h.prim, 0, 0)));
    EXPECT_GT(dot(h.ng, ng), 0.99999f) << "ray " << i;
    EXPECT_EQ(h.ns.x, h.ng.x);
    // On the triangle's plane to float precision (1e-5 of the scene's size), inside its edges.
    EXPECT_NEAR(dot(h.p - p0, ng), 0.0f, 1e-5f * 10);
    const float area = length(cross(p1 - p0, p2 - p0));
    const float b1 = length(cross(h.p - p0, p2 - p0)) / area, b2 = length(cross(p1 - p0, h.p - p0)) / area;
    EXPECT_NEAR(b1 + b2 + length(cross(p1 - h.p, p2 - h.p)) / area, 1.0f, 1e-3f);
    EXPECT_NEAR(h.uv.x, b1 + b2, 1e-3f);
    EXPECT_NEAR(h.uv.y, b2, 1e-3f);
  }
  EXPECT_GT(hits, 1500);
}

TEST(EmbreeScene, FastHitRecordMatchesTheShapesTriangle) { expect_hits_match_the_shape(false, false); }
TEST(EmbreeScene, FastHitRecordMatchesTheShapesTriangleReversed) { expect_hits_match_the_shape(true, false); }
TEST(EmbreeScene, FastHitRecordMatchesTheShapesTriangleInstanced) { expect_hits_match_the_shape(false, true); }

// A sphere's (u, v) is pbrt-v4's (phi / 2 pi, 1 - theta / pi) about its centre; a scene that
// says it needs no (u, v) (no textures) gets (0, 0) and the same point and normal.
TEST(EmbreeScene, SphereUvOnlyWhenNeeded) {
  Shape sphere;
  sphere.type = Shape::Type::Sphere;
  sphere.center = Vec3(1, 2, 3);
  sphere.radius = 2;
  std::vector<Shape> shapes{sphere};
  EmbreeScene with_uv, without_uv;
  with_uv.build(shapes, {0}, {}, {});
  without_uv.build(shapes, {0}, {}, {});
  without_uv.set_uv_needed(false);
  // From below-left: the hit point's direction from the centre is l = (-1, -1, -1) / sqrt 3.
  const Vec3 l = normalize(Vec3(-1, -1, -1));
  const Ray ray{sphere.center + l * 10.0f, -l};
  SurfaceHit a, b;
  ASSERT_TRUE(with_uv.intersect(ray, a));
  ASSERT_TRUE(without_uv.intersect(ray, b));
  const float phi = std::atan2(l.y, l.x) + 2 * kPi, theta = std::acos(l.z);
  EXPECT_NEAR(a.uv.x, phi / (2 * kPi), 1e-4f);
  EXPECT_NEAR(a.uv.y, 1 - theta / kPi, 1e-4f);
  EXPECT_EQ(b.uv.x, 0.0f);
  EXPECT_EQ(b.uv.y, 0.0f);
  EXPECT_EQ(a.p.x, b.p.x);
  EXPECT_EQ(a.ng.z, b.ng.z);
}

// Five concentric tessellated spheres (radii 1, 0.85, ... 0.4): a line meets up to ten surfaces.
std::vector<Shape> nested_shells() {
  std::vector<Shape> shapes;
  for (int k = 0; k < 5; ++k) {
    Shape mesh;
    tessellate_sphere(1.0f - 0.15f * float(k), 16, mesh.positions, mesh.indices);
    shapes.push_back(mesh);
  }
  return shapes;
}

// all_hits against closest-hit queries stepped past each hit: five nested tessellated
// spheres (shells, so a line meets up to ten surfaces), a sphere shape, and an instance
// of a shell, hit by random lines. Every hit is found once, in order, with the same t,
// shape and normal; a buffer too small for them is reported (-1), not filled in part.
TEST(EmbreeScene, AllHitsInOneTraversalMatchHitByHitQueries) {
  std::vector<Shape> shapes = nested_shells();
  Shape ball;
  ball.type = Shape::Type::Sphere;
  ball.center = Vec3(2.5f, 0, 0);
  ball.radius = 0.5f;
  shapes.push_back(ball);
  EmbreeScene scene;
  scene.build(shapes, {0, 1, 2, 3, 4, 5}, {{0}}, {Instance{0, Transform::translate(Vec3d(-2.5, 0, 0))}});
  Rng rng(5, 11);
  int lines_with_many = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 o(rng.uniform() * 8 - 4, rng.uniform() * 2 - 1, rng.uniform() * 2 - 1);
    const Vec3 d = normalize(Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f));
    const float length = 1 + 6 * rng.uniform();
    std::vector<SurfaceHit> stepped;
    for (float t0 = 0; t0 < length;) {
      SurfaceHit h;
      if (!scene.intersect(Ray{o + d * t0, d, length - t0}, h)) break;
      h.t += t0;
      stepped.push_back(h);
      t0 = h.t + 1e-4f * std::max(1.0f, max_component(abs(h.p)));
    }
    EmbreeScene::RawHit raw[32];
    const Ray segment{o, d, length};
    const int n = scene.all_hits(segment, raw, 32);
    ASSERT_EQ(n, int(stepped.size())) << "line " << i;
    for (int k = 0; k < n; ++k) {
      SurfaceHit h;
      scene.fill_hit(raw[k], segment, h);
      EXPECT_NEAR(h.t, stepped[std::size_t(k)].t, 1e-4f) << "line " << i << ", hit " << k;
      EXPECT_EQ(h.shape, stepped[std::size_t(k)].shape);
      EXPECT_EQ(h.instance, stepped[std::size_t(k)].instance);
      EXPECT_GT(dot(h.ng, stepped[std::size_t(k)].ng), 0.9999f);
    }
    if (n >= 4) {
      ++lines_with_many;
      EXPECT_EQ(scene.all_hits(segment, raw, n - 1), -1) << "line " << i;
    }
  }
  EXPECT_GT(lines_with_many, 200);  // enough lines that cross many surfaces to have tested them (266)
}

// pass_through_hits: on the same nested shells, shells 1 and 3 opaque, the others (and the
// instance) passed through. A line that meets an opaque shell within its length is
// blocked; any other gets exactly all_hits' hits (all of them on pass-through shapes).
TEST(EmbreeScene, PassThroughHitsStopAtTheFirstOtherShape) {
  std::vector<Shape> shapes = nested_shells();
  EmbreeScene scene;
  scene.build(shapes, {0, 1, 2, 3, 4}, {{0}}, {Instance{0, Transform::translate(Vec3d(-2.5, 0, 0))}});
  const std::vector<char> pass_through{1, 0, 1, 0, 1};
  Rng rng(7, 13);
  int blocked = 0, passed_many = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 o(rng.uniform() * 6 - 4, rng.uniform() * 2 - 1, rng.uniform() * 2 - 1);
    const Vec3 d = normalize(Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f));
    const Ray segment{o, d, 1 + 6 * rng.uniform()};
    EmbreeScene::RawHit all[32], through[32];
    const int n_all = scene.all_hits(segment, all, 32);
    ASSERT_GE(n_all, 0);
    bool opaque = false;
    for (int k = 0; k < n_all; ++k) opaque |= !pass_through[std::size_t(scene.shape_of(all[k].geom, all[k].inst))];
    const int n = scene.pass_through_hits(segment, pass_through, through, 32);
    if (opaque) {
      EXPECT_EQ(n, EmbreeScene::kBlocked) << "line " << i;
      ++blocked;
      continue;
    }
    ASSERT_EQ(n, n_all) << "line " << i;
    for (int k = 0; k < n; ++k) {
      EXPECT_EQ(through[k].t, all[k].t);
      EXPECT_EQ(through[k].prim, all[k].prim);
      EXPECT_EQ(through[k].inst, all[k].inst);
    }
    if (n >= 2) {
      ++passed_many;
      EXPECT_EQ(scene.pass_through_hits(segment, pass_through, through, n - 1), -1);
    }
  }
  EXPECT_GT(blocked, 300);
  EXPECT_GT(passed_many, 100);
  std::printf("blocked %d, passed through two or more %d\n", blocked, passed_many);
}

}  // namespace
}  // namespace dermis
