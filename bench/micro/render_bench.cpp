// Rays per second of the path tracer on the demo scene, against raw Embree
// rtcIntersect1 on the same rays (recorded from the same render), in one run.
// Both single-threaded so that the ratio measures the renderer's overhead over
// ray casting (shading, sampling, bookkeeping).
//
//   ./build/dermis_bench --benchmark_filter='Demo'
//   DERMIS_BENCH_SCENE=file.pbrt ./build/dermis_bench --benchmark_filter='Demo'   # another scene
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>

#include <cstdlib>
#include <memory>

#include "dermis/core/rng.h"
#include "dermis/render/integrator.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"

namespace dermis {
namespace {

constexpr int kWidth = 64, kHeight = 64, kSpp = 2;

struct DemoFixture {
  std::unique_ptr<RenderScene> scene;
  std::vector<Ray> rays;

  DemoFixture() {
    const char* file = std::getenv("DERMIS_BENCH_SCENE");
    SceneDesc desc = parse_scene_file(file ? std::string(file) : std::string(DERMIS_SOURCE_DIR) + "/scenes/demo.pbrt");
    desc.film.xres = kWidth;
    desc.film.yres = kHeight;
    Diagnostics diag;
    scene = build_render_scene(desc, diag);
    PathCounters counters;
    counters.recorded_rays = &rays;
    render_all(counters);
  }

  // One pass over the image: kSpp pixel-centre samples per pixel.
  void render_all(PathCounters& counters) const {
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        for (int s = 0; s < kSpp; ++s) {
          Sampler sampler(SamplerKind::Sobol, 7, uint64_t(y) * kWidth + x, uint32_t(s));
          Vec2 u_film = sampler.get2d();
          Ray r = scene->camera.generate_ray({x + u_film.x, y + u_film.y}, sampler.get2d());
          benchmark::DoNotOptimize(trace_path(*scene, r, scene->camera_medium, sampler, counters));
        }
  }
};

DemoFixture& fixture() {
  static DemoFixture f;
  return f;
}

void BM_DemoRendererRays(benchmark::State& state) {
  DemoFixture& f = fixture();
  uint64_t rays = 0;
  for (auto _ : state) {
    PathCounters counters;
    f.render_all(counters);
    rays += counters.rays;
  }
  state.SetItemsProcessed(int64_t(rays));
  state.counters["rays_per_s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DemoRendererRays)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_DemoRawEmbreeIntersect1(benchmark::State& state) {
  DemoFixture& f = fixture();
  RTCScene scene = f.scene->embree->handle();
  uint64_t rays = 0;
  for (auto _ : state) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (const Ray& r : f.rays) {
      RTCRayHit rh;
      rh.ray.org_x = r.o.x;
      rh.ray.org_y = r.o.y;
      rh.ray.org_z = r.o.z;
      rh.ray.dir_x = r.d.x;
      rh.ray.dir_y = r.d.y;
      rh.ray.dir_z = r.d.z;
      rh.ray.tnear = 0;
      rh.ray.tfar = r.tmax;
      rh.ray.time = 0;
      rh.ray.mask = 0xffffffffu;
      rh.ray.id = 0;
      rh.ray.flags = 0;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &ctx, &rh);
      benchmark::DoNotOptimize(rh.hit.geomID);
    }
    rays += f.rays.size();
  }
  state.SetItemsProcessed(int64_t(rays));
  state.counters["rays_per_s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DemoRawEmbreeIntersect1)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
}  // namespace dermis
