// Exit sampling without a RenderScene: an Embree scene of spheres, an ObjectTracer,
// and the methods' sample_exit.
#include "dermis/render/subsurface/object_tracer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dermis/render/subsurface/probe_method.h"
#include "dermis/render/subsurface/profile_from_params.h"
#include "dermis/render/subsurface/subsurface_method.h"
#include "dermis/sss/profiles/quadrature.h"

namespace dermis {
namespace {

Shape sphere(Vec3 c, float r) {
  Shape s;
  s.type = Shape::Type::Sphere;
  s.center = c;
  s.radius = r;
  s.material = 0;
  return s;
}

struct Spheres {
  std::vector<Shape> shapes;
  EmbreeScene embree;
  explicit Spheres(std::vector<Shape> s) : shapes(std::move(s)) {
    std::vector<int> top;
    for (std::size_t i = 0; i < shapes.size(); ++i) top.push_back(int(i));
    embree.build(shapes, top, {}, {});
  }
};

SurfaceHit hit_from(const EmbreeScene& scene, Vec3 o, Vec3 d) {
  SurfaceHit h;
  EXPECT_TRUE(scene.intersect(Ray{o, d}, h));
  return h;
}

// What a method on its own sees around an entry (seen along +z): no light, and no other
// object inside its own.
const auto kNoIrradiance = [](Vec3, Vec3, float, Sampler&) { return RGB(0); };
const auto kBlack = [](const SurfaceHit&) { return RGB(0); };
const auto kNoLight = [](Vec3, Vec3, const BSDF&, Vec3, Sampler&) { return RGB(0); };
const auto kNoExitLight = [](const SurfaceHit&, Sampler&) { return RGB(0); };
SubsurfaceEntry bare_entry(const SurfaceHit& hit, const ObjectTracer& tracer) {
  return {hit, Vec3(0, 0, 1), tracer, kNoIrradiance, kBlack, kNoLight, kNoExitLight};
}

TEST(ObjectTracer, SeesOnlyTheShapesOfItsObject) {
  // Three spheres on the x axis; shapes 0 and 2 form object 0, shape 1 is object 1.
  Spheres s({sphere({0, 0, 0}, 1), sphere({3, 0, 0}, 1), sphere({6, 0, 0}, 1)});
  PathCounters counters;
  const SurfaceHit entry = hit_from(s.embree, {-5, 0, 0}, {1, 0, 0});
  ASSERT_EQ(entry.shape, 0);
  {
    const std::vector<int> objects{0, 1, 0};
    ObjectTracer tracer(s.embree, objects, entry, counters);
    std::vector<SurfaceHit> hits;
    tracer.collect_hits({-2, 0, 0}, {1, 0, 0}, 10, 16, hits);
    ASSERT_EQ(hits.size(), 4u);  // both walls of spheres 0 and 2, none of sphere 1
    EXPECT_EQ(hits[1].shape, 0);
    EXPECT_EQ(hits[2].shape, 2);
    EXPECT_NEAR(hits[2].t, 7.0f, 1e-3f);
    SurfaceHit first;
    ASSERT_TRUE(tracer.first_hit(Ray{{1.5f, 0, 0}, {1, 0, 0}}, first));  // starts between 0 and 1
    EXPECT_EQ(first.shape, 2);
  }
  {
    const std::vector<int> objects{0, 1, 2};  // every shape its own object
    ObjectTracer tracer(s.embree, objects, entry, counters);
    std::vector<SurfaceHit> hits;
    tracer.collect_hits({-2, 0, 0}, {1, 0, 0}, 10, 16, hits);
    EXPECT_EQ(hits.size(), 2u);
    SurfaceHit first;
    EXPECT_FALSE(tracer.first_hit(Ray{{1.5f, 0, 0}, {1, 0, 0}}, first));
  }
  EXPECT_GT(counters.rays, 0u);
}

// A walk in a medium that does not absorb always leaves the object, on its surface,
// and carries all the energy out: the mean exit weight is 1 in every channel (within 4
// standard errors), whatever the sampling strategy's per-path weights.
TEST(WalkMethodOnItsOwn, ConservesEnergyInANonAbsorbingSphere) {
  Spheres s({sphere({0, 0, 0}, 1)});
  const std::vector<int> objects{0};
  SubsurfaceParams p;
  p.method = SubsurfaceParams::Method::RandomWalk;
  p.sigma_a = RGB(0);
  p.sigma_s = RGB(2, 5, 10);
  p.g = 0.3f;
  const SubsurfaceMaterial m = make_subsurface_material(p);
  PathCounters counters;
  const SurfaceHit entry = hit_from(s.embree, {0, 0, 5}, {0, 0, -1});
  const ObjectTracer tracer(s.embree, objects, entry, counters);
  const SubsurfaceEntry e = bare_entry(entry, tracer);
  const int n = 20000;
  double sum[3] = {}, sum2[3] = {};
  for (int i = 0; i < n; ++i) {
    Sampler sampler(SamplerKind::Independent, 3, uint64_t(i), 0);
    SubsurfaceExit ex;
    ASSERT_TRUE(sample_subsurface_exit(m, e, sampler, ex));
    EXPECT_EQ(ex.kind, SubsurfaceExit::Kind::ThroughLobe);
    EXPECT_NEAR(length(ex.hit.p), 1.0f, 1e-3f);
    for (int c = 0; c < 3; ++c) {
      sum[c] += ex.weight[c];
      sum2[c] += double(ex.weight[c]) * ex.weight[c];
    }
  }
  for (int c = 0; c < 3; ++c) {
    const double mean = sum[c] / n, se = std::sqrt((sum2[c] / n - mean * mean) / n);
    EXPECT_NEAR(mean, 1.0, 4 * se + 1e-6) << "channel " << c;
  }
}

// A walk stays inside its object however grazing its entry. The tracer moves a flight
// that starts on the surface off it (offset_ray_origin: along the normal, 1e-4 of |p|).
// A walk that started its first flight from the surface point itself while its ray
// started from the point moved along the normal saw the far side where that parallel line
// does, farther than along its own line where the entry grazes (the sphere's chord grows
// as the line moves in), and a collision between the two landed outside: the walk then
// wandered outside until its step cap (bench/vs_cycles' milk configurations: a few paths
// per image). Here a matched boundary enters along the ray, (0, 0, -1), at cosines 0.03
// and 0.2 to the surface (the walk's two ways of leaving it: WalkMethod::walk, kGrazingCos
// 0.1); at 0.03 the window between the chords was about a tenth of a unit and a few per
// cent of the walks fell in it. Every flight must start inside the sphere (to float
// rounding, 1e-7 of the radius per operation) and, in a medium that does not absorb,
// every walk leaves it at its surface.
TEST(WalkMethodOnItsOwn, StaysInsideTheObjectAtAGrazingEntry) {
  const float radius = 20;
  Spheres s({sphere({0, 0, 0}, radius)});
  const std::vector<int> objects{0};
  SubsurfaceParams p;
  p.method = SubsurfaceParams::Method::RandomWalk;
  p.boundary = SubsurfaceParams::Boundary::Matched;
  p.sigma_a = RGB(0);
  p.sigma_s = RGB(0.25f);
  const SubsurfaceMaterial m = make_subsurface_material(p);
  std::vector<Ray> rays;
  PathCounters counters;
  counters.recorded_rays = &rays;
  for (const float x : {19.99f, 19.596f}) {
    const SurfaceHit entry = hit_from(s.embree, {x, 0, 50}, {0, 0, -1});
    ASSERT_LT(std::abs(entry.ng.z), 0.21f);
    const ObjectTracer tracer(s.embree, objects, entry, counters);
    const SubsurfaceEntry e = bare_entry(entry, tracer);  // wo = (0, 0, 1): the walk enters along -z
    const int n = 4000;
    int exited = 0, outside = 0;
    for (int i = 0; i < n; ++i) {
      rays.clear();
      Sampler sampler(SamplerKind::Independent, 11, uint64_t(i), 0);
      SubsurfaceExit ex;
      if (sample_subsurface_exit(m, e, sampler, ex)) {
        ++exited;
        EXPECT_NEAR(length(ex.hit.p), radius, 1e-4f * radius) << i;
      }
      for (const Ray& r : rays) outside += length(r.o) > radius * (1 + 4e-7f);
    }
    EXPECT_EQ(outside, 0) << "entry cosine " << entry.ng.z;
    EXPECT_EQ(exited, n) << "entry cosine " << entry.ng.z;
  }
}

// A random walk in a medium of extinction 2.1 per unit and single-scattering albedo 0.95.
SubsurfaceParams scattering_walk() {
  SubsurfaceParams p;
  p.method = SubsurfaceParams::Method::RandomWalk;
  p.sigma_a = RGB(0.1f);
  p.sigma_s = RGB(2);
  return p;
}

// A walk's exit is a hit of its own: its surface coordinates are those of the exit point
// (where a textured roughness is read), not the entry's: against a direct intersection
// of the sphere at the exit point.
TEST(WalkMethodOnItsOwn, ExitsCarryTheirOwnSurfaceCoordinates) {
  Spheres s({sphere({0, 0, 0}, 1)});
  const std::vector<int> objects{0};
  SubsurfaceParams p = scattering_walk();
  const SubsurfaceMaterial m = make_subsurface_material(p);
  PathCounters counters;
  const SurfaceHit entry = hit_from(s.embree, {0, 0, 5}, {0, 0, -1});
  const ObjectTracer tracer(s.embree, objects, entry, counters);
  const SubsurfaceEntry e = bare_entry(entry, tracer);
  int far = 0;
  for (int i = 0; i < 500; ++i) {
    Sampler sampler(SamplerKind::Independent, 7, uint64_t(i), 0);
    SubsurfaceExit ex;
    if (!sample_subsurface_exit(m, e, sampler, ex)) continue;
    const Vec3 n = normalize(ex.hit.p);
    const SurfaceHit direct = hit_from(s.embree, n * 1.5f, -n);
    EXPECT_NEAR(ex.hit.uv.x, direct.uv.x, 1e-3f) << i;
    EXPECT_NEAR(ex.hit.uv.y, direct.uv.y, 1e-3f) << i;
    far += length(ex.hit.p - entry.p) > 0.5f;
  }
  EXPECT_GT(far, 50);  // exits away from the entry, whose coordinates differ
}

// Backward guiding finds the object's far side below the entry point with one ray (from
// the entry point against its normal, unbounded); the entry keeps it, so that its other
// walks (three with one colour channel per walk) do not trace it again.
TEST(WalkMethodOnItsOwn, TracesTheFarSideOncePerEntry) {
  Spheres s({sphere({0, 0, 0}, 1)});
  const std::vector<int> objects{0};
  SubsurfaceParams p = scattering_walk();
  p.backward_guiding = p.backward_guiding_given = true;
  p.channel_per_walk = p.channel_per_walk_given = true;
  const SubsurfaceMaterial m = make_subsurface_material(p);
  std::vector<Ray> rays;
  PathCounters counters;
  counters.recorded_rays = &rays;
  const SurfaceHit entry = hit_from(s.embree, {0, 0, 5}, {0, 0, -1});
  const ObjectTracer tracer(s.embree, objects, entry, counters);
  SubsurfaceEntry e = bare_entry(entry, tracer);
  EXPECT_FALSE(e.far_side.has_value());
  for (int k = 0; k < 3; ++k) {
    e.exit_index = k;
    Sampler sampler(SamplerKind::Independent, 3, uint64_t(k), 0);
    SubsurfaceExit ex;
    sample_subsurface_exit(m, e, sampler, ex);
    ASSERT_TRUE(e.far_side.has_value());
    EXPECT_TRUE(e.far_side->hit);
    EXPECT_NEAR(e.far_side->p.z, -1, 1e-4f);  // the sphere's bottom, facing down
    EXPECT_NEAR(e.far_side->n.z, -1, 1e-4f);
  }
  const auto far_rays = std::count_if(rays.begin(), rays.end(), [](const Ray& r) { return std::isinf(r.tmax); });
  EXPECT_EQ(far_rays, 1);
  EXPECT_GT(rays.size(), 3u);  // and the walks' own flights
}

// A probe exit on a sphere lies on the sphere, with a finite, non-negative weight.
TEST(ProbeMethodOnItsOwn, ExitsLieOnTheObject) {
  Spheres s({sphere({0, 0, 0}, 1), sphere({0, 0, -1.5f}, 0.3f)});
  const std::vector<int> objects{0, 1};
  SubsurfaceParams p;
  p.method = SubsurfaceParams::Method::Disk;
  p.reflectance = RGB(0.8f, 0.5f, 0.3f);
  p.mfp = RGB(0.5f, 0.3f, 0.2f);
  const SubsurfaceMaterial m = make_subsurface_material(p);
  PathCounters counters;
  const SurfaceHit entry = hit_from(s.embree, {0, 0, 5}, {0, 0, -1});
  const ObjectTracer tracer(s.embree, objects, entry, counters);
  const SubsurfaceEntry e = bare_entry(entry, tracer);
  int exits = 0;
  for (int i = 0; i < 2000; ++i) {
    Sampler sampler(SamplerKind::Independent, 5, uint64_t(i), 0);
    SubsurfaceExit ex;
    if (!sample_subsurface_exit(m, e, sampler, ex)) continue;
    ++exits;
    EXPECT_EQ(ex.hit.shape, 0);
    EXPECT_NEAR(length(ex.hit.p), 1.0f, 1e-3f);
    EXPECT_TRUE(ex.weight.is_finite());
    EXPECT_GE(std::min({ex.weight[0], ex.weight[1], ex.weight[2]}), 0.0f);
  }
  EXPECT_GT(exits, 1000);
}

// A skin-like profile whose red probes reach across a unit sphere (R_max >= 2).
SubsurfaceParams long_reach_params(SubsurfaceParams::Method method) {
  SubsurfaceParams p;
  p.method = method;
  p.reflectance = RGB(0.8f, 0.5f, 0.3f);
  p.mfp = RGB(0.6f, 0.4f, 0.3f);
  return p;
}

// Probes that cross the object many times: six concentric spheres (radii 1 ... 0.5, one
// object), the entry at the top of the outer one, mfp long enough that every probe spans
// the whole object (R_max >= its diameter). A vertical probe meets up to 12 surfaces; one
// is chosen in proportion to its contribution. The mean exit weight per channel is
// sum over the spheres of int R dA (dA = 2 pi a r dr on a sphere of radius a seen from a
// point at distance 1: 2 pi a int_{1-a}^{1+a} R(r) r dr), within 4 standard errors.
TEST(ProbeMethodOnItsOwn, ManyCrossingsKeepTheMeanWeight) {
  std::vector<Shape> shells;
  for (int i = 0; i < 6; ++i) shells.push_back(sphere({0, 0, 0}, 1.0f - 0.1f * float(i)));
  Spheres s(shells);
  const std::vector<int> objects(6, 0);
  for (auto method : {SubsurfaceParams::Method::Disk, SubsurfaceParams::Method::SphereLines}) {
    SCOPED_TRACE(method == SubsurfaceParams::Method::Disk ? "disk" : "sphere lines");
    const SubsurfaceParams p = long_reach_params(method);
    const SubsurfaceMaterial m = make_subsurface_material(p);
    ASSERT_GE(std::get<ProbeMethod>(m.method).max_radius(), 2.0);
    const sss::ProfileRGB profile = make_profile(p);
    PathCounters counters;
    const SurfaceHit entry = hit_from(s.embree, {0, 0, 5}, {0, 0, -1});
    const ObjectTracer tracer(s.embree, objects, entry, counters);
    const SubsurfaceEntry e = bare_entry(entry, tracer);
    const int n = 40000;
    double sum[3] = {}, sum2[3] = {};
    for (int i = 0; i < n; ++i) {
      Sampler sampler(SamplerKind::Independent, 17, uint64_t(i), 0);
      SubsurfaceExit ex;
      if (!sample_subsurface_exit(m, e, sampler, ex)) continue;
      for (int c = 0; c < 3; ++c) {
        sum[c] += ex.weight[c];
        sum2[c] += double(ex.weight[c]) * ex.weight[c];
      }
    }
    for (int c = 0; c < 3; ++c) {
      double expected = 0;
      for (int i = 0; i < 6; ++i) {
        const double a = 1.0 - 0.1 * i;
        expected +=
            2 * kPiD * a * sss::integrate([&](double r) { return profile[c].eval(r) * r; }, 1 - a, 1 + a, 1e-10);
      }
      const double mean = sum[c] / n, se = std::sqrt(std::max(0.0, sum2[c] / n - mean * mean) / n);
      std::printf("channel %d: mean weight %.5f vs %.5f (se %.5f)\n", c, mean, expected, se);
      EXPECT_NEAR(mean, expected, 4 * se) << "channel " << c;
    }
  }
}

// The exit's direct light taken at every candidate of a probe (pick_probe_hit) against
// taking it at the chosen exit with the exit's weight, on a thin shell (the medium between
// spheres of radii 1 and 0.95, one object) lit from outside: light reaches the outer
// sphere only. Both estimates are within 4 standard errors of 2 pi int_0^2 R(r) r dr (the
// outer sphere seen from the entry at its top), and the candidates' estimate has less
// variance: a probe meets the lit outer and the dark inner surface at almost the same R,
// and no longer rests on which one it picks.
TEST(ProbeMethodOnItsOwn, ExitLightAtEveryCandidateKeepsTheMeanWithLessVariance) {
  Spheres s({sphere({0, 0, 0}, 1), sphere({0, 0, 0}, 0.95f)});
  const std::vector<int> objects{0, 0};
  const auto outside_lit = [](const SurfaceHit& h, Sampler&) { return RGB(length(h.p) > 0.975f ? 1.0f : 0.0f); };
  for (auto method : {SubsurfaceParams::Method::Disk, SubsurfaceParams::Method::SphereLines}) {
    SCOPED_TRACE(method == SubsurfaceParams::Method::Disk ? "disk" : "sphere lines");
    const SubsurfaceParams p = long_reach_params(method);
    const SubsurfaceMaterial m = make_subsurface_material(p);
    const sss::ProfileRGB profile = make_profile(p);
    PathCounters counters;
    const SurfaceHit entry = hit_from(s.embree, {0, 0, 5}, {0, 0, -1});
    const ObjectTracer tracer(s.embree, objects, entry, counters);
    const SubsurfaceEntry e{entry, Vec3(0, 0, 1), tracer, kNoIrradiance, kBlack, kNoLight, outside_lit};
    const int n = 40000;
    double sum[2][3] = {}, sum2[2][3] = {};
    for (int i = 0; i < n; ++i) {
      Sampler sampler(SamplerKind::Independent, 23, uint64_t(i), 0);
      SubsurfaceExit ex;
      if (!sample_subsurface_exit(m, e, sampler, ex)) continue;
      ASSERT_TRUE(ex.exit_light_gathered);
      const RGB at_exit = ex.weight * outside_lit(ex.hit, sampler);
      for (int c = 0; c < 3; ++c) {
        const double v[2] = {at_exit[c], ex.gathered[c]};
        for (int k = 0; k < 2; ++k) sum[k][c] += v[k], sum2[k][c] += v[k] * v[k];
      }
    }
    for (int c = 0; c < 3; ++c) {
      const double expected = 2 * kPiD * sss::integrate([&](double r) { return profile[c].eval(r) * r; }, 0, 2, 1e-10);
      double var[2];
      for (int k = 0; k < 2; ++k) {
        const double mean = sum[k][c] / n;
        var[k] = std::max(0.0, sum2[k][c] / n - mean * mean);
        const double se = std::sqrt(var[k] / n);
        std::printf("channel %d, %s: mean %.5f vs %.5f (se %.5f), variance %.5f\n", c,
                    k ? "every candidate" : "chosen exit", mean, expected, se, var[k]);
        EXPECT_NEAR(mean, expected, 4 * se) << "channel " << c << (k ? ", every candidate" : ", chosen exit");
      }
      EXPECT_LT(var[1], var[0]) << "channel " << c;
    }
  }
}

}  // namespace
}  // namespace dermis
