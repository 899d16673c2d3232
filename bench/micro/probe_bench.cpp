// Probe samplers (src/dermis/sss/probe/): nanoseconds per probe sample and per area-pdf
// evaluation, disk projection (three axes, channel/lobe MIS) and sphere lines.
//   ./build/dermis_bench --benchmark_filter=Probe --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <vector>

#include "dermis/core/rng.h"
#include "dermis/sss/probe/disk_probe.h"
#include "dermis/sss/probe/sphere_lines.h"

namespace {

using namespace dermis;
using namespace dermis::sss;

enum Kind { kGaussian, kSkin, kBurley, kDipole };
const char* const kNames[] = {"Gaussian RGB", "Skin (14 lobes)", "Burley RGB", "Dipole RGB"};

ProfileRGB make(Kind kind) {
  switch (kind) {
    case kGaussian:
      return make_gaussian_rgb(RGB(0.8f, 0.6f, 0.4f), RGB(0.04f, 0.09f, 0.25f));
    case kSkin:
      return make_skin_rgb(1.0);
    case kBurley:
      return make_burley_rgb(RGB(0.8f, 0.5f, 0.3f), RGB(0.5f, 0.3f, 0.2f));
    case kDipole:
      return make_dipole_rgb(RGB(0.8f, 0.5f, 0.3f), RGB(0.3f, 0.2f, 0.1f), 1.3);
  }
  return {};
}

constexpr int kBatch = 4096;
const ProbeFrame kFrame = ProbeFrame::around(Vec3d(0, 0, 0), normalize(Vec3d(0.1, 0.2, 1)));

std::vector<double> uniforms(int n) {
  Rng rng(3, 5);
  std::vector<double> u(n);
  for (double& x : u) x = rng.uniform_double();
  return u;
}

void BM_ProbeDiskSample(benchmark::State& state) {
  const ProfileRGB profile = make(Kind(state.range(0)));
  const DiskProbeSampler sampler(profile, RGB(1.0f));
  const std::vector<double> u = uniforms(4 * kBatch);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(sampler.sample(kFrame, u[4 * i], u[4 * i + 1], u[4 * i + 2], u[4 * i + 3]));
    i = (i + 1) & (kBatch - 1);
  }
  state.SetLabel(kNames[state.range(0)]);
}

// Points on a tilted plane through P, found by the sampler itself (realistic radii).
void BM_ProbeDiskPdf(benchmark::State& state) {
  const ProfileRGB profile = make(Kind(state.range(0)));
  const DiskProbeSampler sampler(profile, RGB(1.0f));
  const std::vector<double> u = uniforms(4 * kBatch);
  std::vector<Vec3d> points(kBatch);
  for (int k = 0; k < kBatch; ++k) {
    const auto s = sampler.sample(kFrame, 0.0, u[4 * k + 1], u[4 * k + 2], u[4 * k + 3]);
    points[k] = s.segment.origin + s.segment.direction * (0.5 * s.segment.length);  // the disk point
  }
  const Vec3d n = normalize(kFrame.n + kFrame.t * 0.3);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(sampler.pdf_area(kFrame, points[i], n));
    i = (i + 1) & (kBatch - 1);
  }
  state.SetLabel(kNames[state.range(0)]);
}

void BM_ProbeSphereLineSample(benchmark::State& state) {
  const ProfileRGB profile = make(Kind(state.range(0)));
  const SphereLineTablesRGB tables(profile);
  const SphereLineSampler sampler(tables);
  const std::vector<double> u = uniforms(6 * kBatch);
  std::size_t i = 0;
  for (auto _ : state) {
    const double* v = &u[6 * i];
    benchmark::DoNotOptimize(sampler.sample(kFrame.p, v[0], v[1], Vec2d(v[2], v[3]), Vec2d(v[4], v[5])));
    i = (i + 1) & (kBatch - 1);
  }
  state.SetLabel(kNames[state.range(0)]);
}

void BM_ProbeSphereLinePdf(benchmark::State& state) {
  const ProfileRGB profile = make(Kind(state.range(0)));
  const SphereLineTablesRGB tables(profile);
  const SphereLineSampler sampler(tables);
  const std::vector<double> u = uniforms(6 * kBatch);
  std::vector<Vec3d> points(kBatch);
  for (int k = 0; k < kBatch; ++k) {
    const double* v = &u[6 * k];
    points[k] = sampler.sample(kFrame.p, v[0], v[1], Vec2d(v[2], v[3]), Vec2d(v[4], v[5])).segment.origin * 0.5;
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(sampler.pdf_area(kFrame.p, points[i]));
    i = (i + 1) & (kBatch - 1);
  }
  state.SetLabel(kNames[state.range(0)]);
}

void BM_ProbeSphereLineTableBuild(benchmark::State& state) {
  const ProfileRGB profile = make(Kind(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(SphereLineTablesRGB(profile));
  state.SetLabel(kNames[state.range(0)]);
}

BENCHMARK(BM_ProbeDiskSample)->DenseRange(0, 3);
BENCHMARK(BM_ProbeDiskPdf)->DenseRange(0, 3);
BENCHMARK(BM_ProbeSphereLineSample)->DenseRange(0, 3);
BENCHMARK(BM_ProbeSphereLinePdf)->DenseRange(0, 3);
BENCHMARK(BM_ProbeSphereLineTableBuild)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

}  // namespace
