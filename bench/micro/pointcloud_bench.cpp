// Point-cloud diffusion (src/dermis/sss/pointcloud): build time of the point distribution
// and of the octree, and query time of M(x) against epsilon, for 10k - 100k points on a
// plane (dipole profile, spacing ~ half the mean free path at 100k points).
//   ./build/dermis_bench --benchmark_filter=PointCloud --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <vector>

#include "dermis/core/rng.h"
#include "dermis/sss/pointcloud/point_cloud_diffusion.h"

namespace {

using namespace dermis;
using namespace dermis::sss;
using namespace dermis::sss::pointcloud;

const std::vector<Vec3> kSquare = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
const std::vector<uint32_t> kTriangles = {0, 1, 2, 0, 2, 3};

const ProfileRGB& profile() {
  static const ProfileRGB p = make_dipole_rgb(RGB(0.8f, 0.6f, 0.4f), RGB(0.02f, 0.015f, 0.01f), 1.3);
  return p;
}

struct Scene {
  std::vector<SurfacePoint> points;
  std::vector<RGB> irradiance;
};
const Scene& scene(std::size_t n) {
  static std::map<std::size_t, std::unique_ptr<Scene>> cache;
  auto& s = cache[n];
  if (!s) {
    s = std::make_unique<Scene>();
    s->points = distribute_points(kSquare, kTriangles, n, 1);
    for (const auto& p : s->points) s->irradiance.push_back(RGB(1 + p.position.x * p.position.x));
  }
  return *s;
}

void PointCloud_Distribute(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(distribute_points(kSquare, kTriangles, std::size_t(state.range(0)), 1));
}
BENCHMARK(PointCloud_Distribute)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

void PointCloud_BuildOctree(benchmark::State& state) {
  const Scene& s = scene(std::size_t(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(IrradianceOctree(s.points, s.irradiance));
  state.counters["bytes"] = double(IrradianceOctree(s.points, s.irradiance).memory_bytes());
}
BENCHMARK(PointCloud_BuildOctree)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

// range(0): points; range(1): epsilon x 1000; range(2): local disk on/off.
void PointCloud_Query(benchmark::State& state) {
  const Scene& s = scene(std::size_t(state.range(0)));
  DiffusionOptions o;
  o.epsilon = double(state.range(1)) / 1000;
  o.local_disk = state.range(2) != 0;
  const PointCloudDiffusion d(s.points, s.irradiance, profile(), o);
  Rng rng(3, 3);
  std::vector<Vec3> xs(1024);
  for (Vec3& x : xs) x = {rng.uniform() - 0.5f, rng.uniform() - 0.5f, 0};
  std::size_t i = 0;
  for (auto _ : state) {
    const Vec3 x = xs[i++ & 1023];
    benchmark::DoNotOptimize(d.radiant_exitance(x, RGB(1.0f)));
  }
}
BENCHMARK(PointCloud_Query)->ArgsProduct({{10000, 100000}, {300, 100, 30, 10}, {0, 1}})->Unit(benchmark::kMicrosecond);

}  // namespace
