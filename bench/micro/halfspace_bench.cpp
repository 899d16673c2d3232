// Paths per second of the brute-force half-space simulator (classical sampling,
// index-matched, isotropic, normal incidence) at several single-scattering albedos.
#include <benchmark/benchmark.h>

#include "dermis/sss/halfspace/halfspace.h"

namespace {

void BM_HalfspacePaths(benchmark::State& state) {
  dermis::sss::HalfspaceConfig c;
  c.albedo = double(state.range(0)) / 1000.0;
  c.paths = 20000;
  uint64_t seed = 1;
  double collisions = 0;
  for (auto _ : state) {
    c.seed = seed++;
    const auto r = dermis::sss::simulate_halfspace(c);
    benchmark::DoNotOptimize(r.albedo);
    collisions = r.mean_collisions;
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(c.paths));
  state.counters["collisions_per_path"] = collisions;
}
BENCHMARK(BM_HalfspacePaths)->Arg(500)->Arg(900)->Arg(990)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
