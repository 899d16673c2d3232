// Tessellated quadrics and loop subdivision surfaces as closed subsurface objects: a
// cylinder capped by two disks (one subsurface material: one object) and a subdivided
// octahedron. Every ray from inside must find the object's boundary, leaving through an
// outward normal (a gap between the rims, or an inward-wound part, would fail).
#include <gtest/gtest.h>

#include <random>

#include "dermis/render/scene_assembly.h"
#include "dermis/render/subsurface/object_tracer.h"
#include "dermis/scene/parser.h"

namespace dermis {
namespace {

std::unique_ptr<RenderScene> assemble(const std::string& world) {
  SceneDesc d = parse_scene_string("WorldBegin\n" + world, "closed.pbrt");
  Diagnostics diag;
  return assemble_scene(d, diag);
}

// Rays from points drawn by `inside` in random directions: how many find no boundary or
// a boundary whose normal faces the ray (wound inward).
template <class Inside>
int escaping_rays(const RenderScene& sc, Vec3 entry_from, Vec3 entry_to, Inside inside, int n) {
  SurfaceHit entry;
  if (!sc.embree->intersect(Ray{entry_from, normalize(entry_to - entry_from)}, entry)) {
    ADD_FAILURE() << "the entry ray missed the object";
    return n;
  }
  PathCounters counters;
  ObjectTracer tracer(*sc.embree, sc.object_of_shape, entry, counters);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> U(-1, 1);
  int bad = 0;
  for (int i = 0; i < n; ++i) {
    Vec3 d;
    do d = Vec3(U(rng), U(rng), U(rng));
    while (length_squared(d) > 1 || length_squared(d) < 1e-4f);
    SurfaceHit h;
    const bool found = tracer.first_hit(Ray{inside(rng), normalize(d)}, h);
    bad += !found || dot(h.ng, d) <= 0;
  }
  return bad;
}

TEST(ClosedShapeObjects, CappedCylinderIsWatertight) {
  auto sc = assemble(
      "Material \"subsurface\"\n"
      "Shape \"cylinder\" \"float zmin\" 0 \"float zmax\" 2\n"
      "Shape \"disk\" \"float height\" 2\n"
      "ReverseOrientation\nShape \"disk\" \"float height\" 0\n");
  ASSERT_EQ(sc->shapes.size(), 3u);
  EXPECT_EQ(sc->object_of_shape[0], sc->object_of_shape[1]);
  EXPECT_EQ(sc->object_of_shape[0], sc->object_of_shape[2]);
  std::uniform_real_distribution<float> U(0, 1);
  auto inside = [&](std::mt19937& rng) {
    // Near the rims too: radius up to 0.999, z within 1e-3 of the caps.
    const float r = 0.999f * std::sqrt(U(rng)), phi = 2 * kPi * U(rng);
    return Vec3(r * std::cos(phi), r * std::sin(phi), 0.001f + 1.998f * U(rng));
  };
  EXPECT_EQ(escaping_rays(*sc, Vec3(5, 0, 1), Vec3(0, 0, 1), inside, 50000), 0);
}

TEST(ClosedShapeObjects, SubdividedOctahedronIsWatertightAndOutward) {
  auto sc = assemble(
      "Material \"subsurface\"\n"
      "Shape \"loopsubdiv\" \"integer levels\" 4 \"point3 P\" [1 0 0 -1 0 0 0 1 0 0 -1 0 0 0 1 0 0 -1] "
      "\"integer indices\" [4 0 2 4 2 1 4 1 3 4 3 0 5 2 0 5 1 2 5 3 1 5 0 3]\n");
  // Inside: the limit surface keeps at least 0.4 from the centre (checked below).
  for (const Shape& s : sc->shapes)
    for (const Vec3& p : s.positions) ASSERT_GT(length(p), 0.4f);
  std::uniform_real_distribution<float> U(-0.23f, 0.23f);
  auto inside = [&](std::mt19937& rng) { return Vec3(U(rng), U(rng), U(rng)); };
  EXPECT_EQ(escaping_rays(*sc, Vec3(5, 0, 0.5f), Vec3(0, 0, 0), inside, 50000), 0);
}

}  // namespace
}  // namespace dermis
