// Efficiency 1/(variance x time) of the half-space albedo estimate (index-matched,
// isotropic, normal incidence) with classical, Dwivedi and MIS walk sampling
// (Krivanek & d'Eon 2014). Counters: variance per path, paths/s, and efficiency
// per second of wall time = paths/s / variance. Arguments: alpha x 1000, sampling
// (0 classical, 1 Dwivedi, 2 MIS), P_guided x 100 (MIS only).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>

#include "dermis/sss/halfspace/halfspace.h"
#include "dermis/sss/walk/analytic_boundaries.h"

namespace {

void BM_WalkEfficiency(benchmark::State& state) {
  dermis::sss::HalfspaceConfig c;
  c.albedo = double(state.range(0)) / 1000.0;
  c.sampling = dermis::sss::WalkSampling(state.range(1));
  c.p_guided = double(state.range(2)) / 100.0;
  c.paths = 100000;
  c.bins = dermis::sss::RadialBins::linear(1.0, 1);
  uint64_t seed = 1;
  double variance_sum = 0, seconds = 0;
  for (auto _ : state) {
    c.seed = seed++;
    const auto r = dermis::sss::simulate_halfspace(c);
    variance_sum += r.albedo_stderr * r.albedo_stderr * double(c.paths);
    seconds += r.seconds;
    benchmark::DoNotOptimize(r.albedo);
  }
  const double variance = variance_sum / double(state.iterations());
  const double paths_per_second = double(state.iterations()) * double(c.paths) / seconds;
  state.counters["variance"] = variance;
  state.counters["paths_per_s"] = paths_per_second;
  state.counters["efficiency"] = paths_per_second / variance;
}

void WalkArguments(benchmark::internal::Benchmark* b) {
  for (int alpha : {500, 800, 950, 990, 999}) {
    b->Args({alpha, 0, 0});
    b->Args({alpha, 1, 100});
    for (int p : {50, 75, 90}) b->Args({alpha, 2, p});
  }
}
BENCHMARK(BM_WalkEfficiency)->Apply(WalkArguments)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

// The renderer's walk (random_walk.h, three equal channels) on a slab and on a ball, entry
// at normal incidence through an index-matched boundary: efficiency of estimating what
// leaves through the entry side (reflectance R), the far side (transmittance T) and both,
// for classical sampling, the seed's guiding toward the entry plane, and guiding toward
// both sides (backward guiding). Arguments: thickness (slab) or radius (ball) x 10 in mean
// free paths, alpha x 1000, strategy (kWalkStrategies), P_guided x 100.
namespace walk_geometry {

using dermis::RGB;
using dermis::Vec3;
using namespace dermis::sss;

struct Strategy {
  WalkSampling sampling;
  bool backward;
};
constexpr Strategy kWalkStrategies[] = {{WalkSampling::Classical, false},
                                        {WalkSampling::Mis, false},
                                        {WalkSampling::Mis, true},
                                        {WalkSampling::Dwivedi, false},
                                        {WalkSampling::Dwivedi, true}};

struct Moments {
  double sum = 0, sum_sq = 0;
  void add(double x) { sum += x, sum_sq += x * x; }
  double variance(double n) const { return std::max(0.0, sum_sq / n - (sum / n) * (sum / n)); }
};

template <class Tracer>
void run(benchmark::State& state, const Tracer& tracer, Vec3 entry_p) {
  const double alpha = double(state.range(1)) / 1000.0;
  const Strategy strategy = kWalkStrategies[state.range(2)];
  WalkSettings settings;
  settings.sampling = strategy.sampling;
  settings.backward_guiding = strategy.backward;
  settings.p_guided = float(state.range(3)) / 100.0f;
  const MixtureWalkStep<3> step = make_walk_step({RGB(float(alpha)), RGB(1.0f), 0.0f}, settings);
  constexpr int kPaths = 20000;
  Moments near_side, far_side, both;
  double seconds = 0, paths = 0, steps = 0;
  uint64_t seed = 1;
  for (auto _ : state) {
    dermis::Rng rng(seed++, 3);
    WalkResult out;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < kPaths; ++i) {
      double r = 0, t = 0;
      if (random_walk(step, settings, entry_p, {0, 0, 1}, {0, 0, -1}, rng, tracer, out))
        (out.exit_n.z > 0 ? r : t) = out.weight[0];  // a ball: the lower half is the far side
      steps += out.steps;
      near_side.add(r), far_side.add(t), both.add(r + t);
    }
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    paths += kPaths;
  }
  const double rate = paths / seconds;
  state.counters["R"] = near_side.sum / paths;
  state.counters["T"] = far_side.sum / paths;
  state.counters["paths_per_s"] = rate;
  state.counters["steps"] = steps / paths;  // scattering events per path
  state.counters["eff_R"] = rate / near_side.variance(paths);
  state.counters["eff_T"] = rate / far_side.variance(paths);
  state.counters["eff_RT"] = rate / both.variance(paths);
}

void BM_SlabWalkEfficiency(benchmark::State& state) {
  run(state, SlabTracer{double(state.range(0)) / 10.0}, {0, 0, 0});
}
void BM_SphereWalkEfficiency(benchmark::State& state) {
  const double radius = double(state.range(0)) / 10.0;
  run(state, SphereTracer{radius}, {0, 0, float(radius)});
}

void GeometryArguments(benchmark::internal::Benchmark* b, std::initializer_list<int> sizes) {
  for (int size : sizes)
    for (int alpha : {500, 900, 990})
      for (int strategy = 0; strategy < 5; ++strategy) b->Args({size, alpha, strategy, 50});
}
BENCHMARK(BM_SlabWalkEfficiency)->Apply([](auto* b) {
                                  GeometryArguments(b, {5, 10, 20, 40, 80, 160});
                                }) -> Unit(benchmark::kMillisecond) -> UseRealTime();
BENCHMARK(BM_SphereWalkEfficiency)->Apply([](auto* b) {
                                    GeometryArguments(b, {5, 20, 80});
                                  }) -> Unit(benchmark::kMillisecond) -> UseRealTime();

}  // namespace walk_geometry
