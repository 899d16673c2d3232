// Efficiency 1/(variance x time) of the half-space albedo estimate (index-matched,
// isotropic, normal incidence) with classical, Dwivedi and MIS walk sampling
// (Krivanek & d'Eon 2014). Counters: variance per path, paths/s, and efficiency
// per second of wall time = paths/s / variance. Arguments: alpha x 1000, sampling
// (0 classical, 1 Dwivedi, 2 MIS), P_guided x 100 (MIS only).
#include <benchmark/benchmark.h>

#include "dermis/sss/halfspace/halfspace.h"

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
