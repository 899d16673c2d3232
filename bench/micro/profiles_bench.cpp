// Throughput of the radial profiles through the RadialProfile variant (what the probe
// sampler calls): eval(r) and sample_radius(xi), nanoseconds per call.
//   ./build/dermis_bench --benchmark_filter=Profile --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "dermis/core/rng.h"
#include "dermis/sss/profiles/profile.h"

namespace {

using namespace dermis::sss;

enum Kind { kGaussian, kSkinRed, kCubic, kDipole, kBurley, kTabulatedDipole };
const char* const kNames[] = {"Gaussian", "SkinSumOfGaussians(red,6)", "Cubic", "Dipole", "Burley", "TabulatedDipole"};

RadialProfile make(Kind kind) {
  switch (kind) {
    case kGaussian:
      return GaussianProfile(0.25, 0.8);
    case kSkinRed:
      return skin_sum_of_gaussians(1.0, dermis::RGB(0.8f))[0];
    case kCubic:
      return CubicProfile(1.5, 0.8);
    case kDipole:
      return DipoleProfile::from_albedo(0.8, 0.5, 1.3);
    case kBurley:
      return BurleyProfile(0.8, 0.5);
    case kTabulatedDipole: {
      static const auto table = std::make_shared<const ProfileTable>(dipole_family(1.3));
      return TabulatedProfile(table, 0.8, 0.5);
    }
  }
  return {};
}

constexpr int kBatch = 4096;

std::vector<double> uniforms() {
  dermis::Rng rng(7, 11);
  std::vector<double> u(kBatch);
  for (double& x : u) x = rng.uniform_double();
  return u;
}

void BM_ProfileEval(benchmark::State& state) {
  const RadialProfile p = make(Kind(state.range(0)));
  std::vector<double> r = uniforms();
  for (double& x : r) x = p.sample_radius(x);  // radii where the profile is used
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(p.eval(r[i]));
    i = (i + 1) & (kBatch - 1);
  }
  state.SetLabel(kNames[state.range(0)]);
}

void BM_ProfileSampleRadius(benchmark::State& state) {
  const RadialProfile p = make(Kind(state.range(0)));
  const std::vector<double> xi = uniforms();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(p.sample_radius(xi[i]));
    i = (i + 1) & (kBatch - 1);
  }
  state.SetLabel(kNames[state.range(0)]);
}

void BM_ProfilePdfRadius(benchmark::State& state) {
  const RadialProfile p = make(Kind(state.range(0)));
  std::vector<double> r = uniforms();
  for (double& x : r) x = p.sample_radius(x);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(p.pdf_radius(r[i]));
    i = (i + 1) & (kBatch - 1);
  }
  state.SetLabel(kNames[state.range(0)]);
}

BENCHMARK(BM_ProfileEval)->DenseRange(0, 5);
BENCHMARK(BM_ProfileSampleRadius)->DenseRange(0, 5);
BENCHMARK(BM_ProfilePdfRadius)->DenseRange(0, 5);

}  // namespace
