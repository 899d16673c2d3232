// Unidirectional volumetric path tracing (Veach 1997; pbrt-v4 ch. 14) through
// homogeneous media bounded by dielectric or index-matched surfaces: next-event
// estimation with multiple importance sampling (power heuristic) at surfaces and
// in media, Russian roulette, and chromatic media sampled with one channel per
// step and one-sample MIS over the channels (METHODS.md sec. 5).
#pragma once

#include <cstdint>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/core/sampler.h"
#include "dermis/geometry/ray.h"
#include "dermis/render/path_counters.h"
#include "dermis/render/render_scene.h"
#include "dermis/spectral/sampled_wavelengths.h"

namespace dermis {

// How a path begins: from the camera (emission seen at full weight), or as the
// continuation of a scattering at `prev_p` sampled with solid-angle density `prev_pdf`
// (emission found by the ray is MIS-weighted against next-event estimation there).
// Dimensions of a pixel sample (core/sampler.h): the camera takes the first four (film
// position 2D, lens 2D); path vertex v (the v-th ray the path casts) takes the block of
// kVertexDimensions from first_dimension + v kVertexDimensions, in the order its
// decisions are made, so that the same decision of every sample of a pixel reads the
// same stratified dimension. A subsurface exit and a nested path draw from their own
// regions (Sampler::region) of the block they start in.
inline constexpr uint64_t kCameraDimensions = 4;
inline constexpr uint64_t kVertexDimensions = 32;
// A subsurface exit sampler takes its first 8 numbers (a probe, or the first flight and
// scattering of a walk) stratified, the rest from the sample's PCG32 stream: stratifying
// every step of the walk left the variance unchanged and cost render time in hashing
// (docs/rendering.md, "Sampler").
inline constexpr uint32_t kStratifiedExitDimensions = 8;
// Vertices past the first 6 of a path take the sample's PCG32 stream: deep in a medium
// the hashing of Sobol' dimensions cost much of the render time for no measurable gain
// (docs/rendering.md, "Sampler").
inline constexpr uint64_t kStratifiedVertices = 6;

// What a camera path's first subsurface entry was, for the render's pilot
// (render/subsurface_pilot.h): filled by trace_path where PathStart::subsurface_record
// points.
struct SubsurfaceEntryRecord {
  int material = -1;  // RenderScene::subsurface index; -1: the path entered no subsurface object
  // The radiance of the reflection split off at the camera's first hit (a subsurface entry
  // or smooth glass), included in the path's: the same for every strategy (with the same
  // numbers; but where it meets a subsurface object again), so the pilot leaves it out of
  // what it measures.
  RGB camera_reflection{0};
};

struct PathStart {
  bool from_camera = true;
  float prev_pdf = 0;
  Vec3 prev_p;  // the next-event point there (offset off the surface)
  Vec3 prev_n;  // and the normal of the hemisphere its light selection saw (zero in a medium)
  // The rule by which uniform skies were light-sampled there (LightSelection's SkyRule: at
  // subsurface exits, SubsurfaceMaterial::exit_sky_rule).
  SkyRule prev_sky = SkyRule::Sampled;
  // The path starts after a specular event (not from the camera: a smooth boundary's
  // exit, the camera's split-off reflection): the emission it meets first counts in full,
  // as after the camera.
  bool prev_specular = false;
  // The weight of the emission met first (SubsurfaceExit::emission_weight); 1: in full.
  float prev_emission_weight = 1;
  int depth = 0;                                 // scattering events already taken
  uint64_t first_dimension = kCameraDimensions;  // of vertex 0's block
  // Russian roulette at the path's first vertex (its first surface hit, once that
  // surface's emission is counted, or its first scattering event in a medium) on this
  // throughput (roulette_survival's argument; 0: none): the camera's split-off reflection,
  // where a sky can be seen, so that the sky met by its first ray counts in full
  // (path/path_state.h reflection_survival).
  float first_vertex_roulette = 0;
  // The sampling strategy of each subsurface material (SubsurfaceEntry::strategy, by
  // RenderScene::subsurface index; null: every material's default, 0): the render's pilot
  // chooses them (render/subsurface_pilot.h) and tries each. Where the pilot records the
  // camera path's first entry (null: nowhere).
  const std::vector<int>* subsurface_strategies = nullptr;
  SubsurfaceEntryRecord* subsurface_record = nullptr;
  // The copies that path splitting may still add for this camera sample
  // (render/path_splitting.h), shared by the paths nested in it; null: a budget of its own.
  int* split_budget = nullptr;
  // The wavelengths the path carries (--spectral: each RGB channel of its values is the
  // value at one of them); null: the channels are red, green and blue.
  // Not const: a dispersive dielectric keeps one of them (SampledWavelengths::
  // terminate_secondary), for the whole camera sample.
  SampledWavelengths* wavelengths = nullptr;
};

// Radiance arriving along `ray` (from the camera), starting in `medium`: the loop over the
// path's vertices, each a unit of render/path/ (docs/ARCHITECTURE.md).
RGB trace_path(const RenderScene& scene, Ray ray, int medium, Sampler& sampler, PathCounters& counters,
               const PathStart& start = {});

// One-sample estimate of the irradiance transmitted into a smooth dielectric surface
// (index eta) at p with outward normal n: E = integral of L (1 - Fr(cos, eta)) cos dw over
// the outside hemisphere, by next-event estimation and cosine sampling combined with
// the power heuristic. The point cloud's pre-pass and its local term use it. Through a
// rough boundary (rough: its table, materials/rough_exit_lobe.h) T(cos) replaces 1 - Fr.
// split_budget: that of the path it is nested in (PathStart::split_budget), if any.
RGB transmitted_irradiance(const RenderScene& scene, Vec3 p, Vec3 n, float eta, int medium, Sampler& sampler,
                           PathCounters& counters, const RoughExitTable* rough = nullptr, int* split_budget = nullptr);

// Transmittance from `origin` along unit `dir` over `distance` (infinity allowed),
// starting in `medium`: zero if an opaque or refractive surface is in the way,
// otherwise the product of the media's transmittances across index-matched boundaries,
// at the path's wavelengths when it has them (null: RGB).
RGB shadow_transmittance(const RenderScene& scene, Vec3 origin, Vec3 dir, float distance, int medium,
                         PathCounters& counters, const SampledWavelengths* wavelengths);

}  // namespace dermis
