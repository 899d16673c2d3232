// The state one path carries from vertex to vertex (as Cycles' integrator state, or the
// locals of pbrt-v4's VolPathIntegrator::Li): the radiance gathered, the throughput, the
// last scattering event that emission met next is weighed against, and where the path is
// in its sampler. PathContext: what every vertex reads besides. The vertex units
// (volume_vertex.h, emission.h, surface_vertex.h, subsurface_vertex.h) take both;
// trace_path (integrator.cpp) is the loop over them.
#pragma once

#include <cstdint>

#include "dermis/core/rgb.h"
#include "dermis/core/sampler.h"
#include "dermis/geometry/ray.h"
#include "dermis/materials/medium.h"
#include "dermis/render/integrator.h"
#include "dermis/render/path_counters.h"
#include "dermis/render/render_scene.h"

namespace dermis {

struct PathContext {
  const RenderScene& sc;
  Sampler& sampler;
  PathCounters& counters;
  const PathStart& start;
  int& split_budget;  // the copies path splitting may still add for this camera sample (path_splitting.h)
};

// What a vertex unit tells the loop.
enum class VertexOutcome {
  kContinue,     // the path goes on along state.ray
  kStop,         // the path ends
  kPassThrough,  // (a medium segment) the path reached the surface it was traced to
};

struct PathState {
  PathState(const Ray& ray, int medium, const PathStart& start);

  Ray ray;              // the ray the path traces next
  int medium;           // the medium it starts in; -1: vacuum
  RGB L{0};             // the radiance gathered so far
  RGB beta{1};          // the throughput
  float eta_scale = 1;  // the radiance scale of the refractions taken (pbrt-v4's etaScale), for the roulette
  // The last scattering event: specular (or the camera: emission met next counts in full,
  // no MIS), else the solid-angle pdf of its sampled direction, and the next-event point,
  // normal and sky rule there that emission met next is weighed against.
  bool specular;
  float prev_pdf;
  Vec3 prev_p, prev_n;
  SkyRule prev_sky;
  // A factor on the emission met next, besides the MIS weight above (a subsurface exit's
  // SubsurfaceExit::emission_weight); 1 after every other event.
  float emission_weight = 1;
  int depth;          // scattering events taken
  int crossings = 0;  // index-matched boundaries crossed
  // Every vertex so far a smooth specular one (glass, a mirror) or none: what the camera
  // sees directly, through glass or in a mirror. Its first subsurface entry is the camera's
  // first entry, with the exits and strategies that serve it.
  bool camera_chain;
  // The emission at the next surface (or at infinity) was counted already (a smooth
  // reflection's bright emission: add_bright_emission_seen): the path goes on without it.
  bool emission_counted = false;
  bool first_vertex = true;   // PathStart::first_vertex_roulette not yet applied
  uint64_t vertex_dimension;  // this vertex's block of sampler dimensions (integrator.h)
  // A textured `volumetric` object: the path takes the medium of the point where it
  // entered and keeps it while inside (volumetric_texture.h), made at the path's
  // wavelengths when it has them; elsewhere sc.media.
  HomogeneousMedium entered;
  int entered_medium = -1;

  // The path's wavelengths (PathStart::wavelengths; null: RGB).
  const SampledWavelengths* wavelengths;

  // Medium m as the path sees it: at its wavelengths when it has them (the last one
  // converted kept: a path stays in a medium for many vertices). A `volumetric` medium's
  // parameters are read at the wavelengths and inverted per wavelength (volumetric_texture.h),
  // as its random walk twin's are.
  const HomogeneousMedium& medium_of(const RenderScene& sc, int m) const;

  // After a scattering event: the path goes on along `next`, sampled with solid-angle
  // density pdf; p and n (zero in a medium) are where the event's light sampling was done,
  // under the sky rule `sky`. counts_in_full: emission met next is not weighed (a specular
  // event, or one without light sampling).
  void after_scatter(const Ray& next, float pdf, Vec3 p, Vec3 n, SkyRule sky, bool counts_in_full) {
    ray = next;
    prev_pdf = pdf;
    prev_p = p;
    prev_n = n;
    prev_sky = sky;
    specular = counts_in_full;
    emission_weight = 1;
  }

 private:
  mutable HomogeneousMedium converted_;
  mutable int converted_index_ = -2;
};

// Russian roulette after the second bounce on max(throughput) x eta scale (pbrt-v4 sec.
// 14.1.3), below `threshold` (russian_roulette.h); reweights beta when the path survives.
bool survives_roulette(PathContext& ctx, PathState& st, float threshold);

// PathStart::first_vertex_roulette, at the path's first vertex (once): the split-off camera
// reflection's roulette where a sky shines (reflection_survival).
bool first_vertex_survives(PathContext& ctx, PathState& st);

// The camera's first smooth reflection, split off with weight `weight` (F, or F times the
// glass lobe's weight) as the path `reflected`: followed always where it may see a bright
// emitter (a small light's highlight, which it was split off for). Elsewhere Russian
// roulette (pbrt-v4's rule, russian_roulette.h) on the branch's throughput max(beta) x eta
// scale x weight: where a sky shines, at the reflected path's first vertex
// (PathStart::first_vertex_roulette), so that the sky its first ray meets counts in full
// for the price of that ray; with no sky, before the ray is traced, since nothing it meets
// directly can then be bright (rouletted before the ray, a dark object's reflection of a
// uniform sky was met by one sample in 1/F: docs/results/results-rendering.md). Returns the probability the
// reflected path is traced with, 0 when it is not; the decision's number comes from a
// region of its own.
float reflection_survival(PathContext& ctx, const PathState& st, const Ray& reflected_ray, float weight,
                          PathStart& reflected);

// The start of a path that continues this one (the split-off camera reflection, a nested
// way on from a subsurface exit): the parent's strategies and its shared split budget, at
// `depth`, drawing from `first_dimension`. The
// caller says how its last event is weighed (prev_*). Neither the pilot's record (the
// camera path's first entry is recorded once) nor a first-vertex roulette (the reflection's
// own: reflection_survival) is inherited.
PathStart continuation(const PathStart& parent, int depth, uint64_t first_dimension, int& split_budget);

}  // namespace dermis
