// What an exit sampler returns: where and how light that entered a subsurface object
// at one point leaves it. The integrator acts on the kind and never asks which method
// produced it.
#pragma once

#include <optional>

#include "dermis/core/function_ref.h"
#include "dermis/core/rgb.h"
#include "dermis/core/sampler.h"
#include "dermis/geometry/ray.h"
#include "dermis/materials/bsdf.h"
#include "dermis/render/subsurface/object_tracer.h"
#include "dermis/render/subsurface/refracted_light.h"
#include "dermis/spectral/sampled_wavelengths.h"
#include "dermis/sss/walk/boundary_hit.h"

namespace dermis {

struct GridMediumView;  // materials/grid_medium.h

struct SubsurfaceExit {
  enum class Kind {
    ThroughLobe,  // leaves at `hit` through the exit lobe Sw (bsdf.h, materials/rough_exit_lobe.h)
    Along,        // leaves at `hit` along `direction` (a walk through its boundary)
    Emitted,      // the method returns the radiance leaving the entry point itself (point cloud)
  };
  Kind kind = Kind::ThroughLobe;
  SurfaceHit hit;  // ThroughLobe, Along: the exit point; hit.ng points out of the object
  RGB weight{1};   // ThroughLobe, Along: multiplies the path throughput (estimate / pdf)
  Vec3 direction;  // Along
  // Along: the solid-angle density with which `direction` was sampled through a rough
  // boundary whose lights the method sampled (SubsurfaceEntry::light_through): light
  // found along it is weighed against those samples. 0: a delta direction (smooth or
  // matched boundary), whose light counts in full.
  float direction_pdf = 0;
  // Along: the weight of the emission met first along `direction` (a walk that left right
  // after a scattering event whose light was sampled through the smooth boundary:
  // refracted_light.h); 1: in full.
  float emission_weight = 1;
  RGB radiance{0};  // Emitted: radiance toward the viewer, per unit transmitted throughput
  // Direct light the method gathered on its way (light sampled through a rough boundary
  // wherever the path met it), per unit transmitted throughput: counts whether or not
  // the method then found an exit.
  RGB gathered{0};
  // ThroughLobe: the method has gathered the direct light leaving through the exit lobe
  // (SubsurfaceEntry::exit_light, in `gathered`, scored where the path could have left):
  // the integrator samples no light at `hit`, only the lobe for the way on.
  bool exit_light_gathered = false;
  bool truncated = false;  // no exit: the random walk hit its step cap
};

// The irradiance transmitted into the smooth dielectric surface (index eta) at p with
// outward normal n (integrator.h transmitted_irradiance): a method whose estimate needs
// the light arriving at the entry point (the point cloud's local disk) calls it.
using TransmittedIrradiance = FunctionRef<RGB(Vec3 p, Vec3 n, float eta, Sampler& sampler)>;

// The albedo of a surface of another object met inside this one (ObjectTracer::
// first_boundary): light there is reflected diffusely with it (a black surface absorbs).
using InteriorAlbedo = FunctionRef<RGB(const SurfaceHit& hit)>;

// Direct light reaching the outside of the object at p (outward normal n) and carried
// through `boundary` (a rough dielectric seen from inside) toward wo inside: one light
// sample per group, f(wo, wi)|cos wi| L / pdf over the directions wi outside, MIS-weighted
// against sampling `boundary` (integrator.h estimate_direct). Zero when the integrator does
// no light sampling there (EstimatorSwitches::rough_glass_nee off, render_scene.h).
using LightThrough = FunctionRef<RGB(Vec3 p, Vec3 n, const BSDF& boundary, Vec3 wo, Sampler& sampler)>;

// Direct light leaving the object at `exit` (hit.ng outward) through the exit lobe Sw: one
// light sample per group, MIS-weighted against sampling Sw (integrator.h estimate_direct),
// per unit throughput: what the integrator adds at a ThroughLobe exit.
using ExitLight = FunctionRef<RGB(const SurfaceHit& exit, Sampler& sampler)>;

// Everything an exit sampler may use besides its own parameters.
struct SubsurfaceEntry {
  const SurfaceHit& hit;  // where the path entered; hit.ng points out of the object
  Vec3 wo;                // toward where the path came from, on the side of hit.ng
  const ObjectTracer& tracer;
  TransmittedIrradiance irradiance;
  InteriorAlbedo interior_albedo;
  LightThrough light_through;
  ExitLight exit_light;
  // The direction the path took into the medium when the integrator sampled a rough
  // entry; unset for a smooth one (the method refracts wo itself).
  std::optional<Vec3> refracted = {};
  // The method's sampling strategy for this entry (the walk's kWalkStrategies; 0 the
  // default), chosen per material by the render's pilot (render/subsurface_pilot.h).
  int strategy = 0;
  // At the camera's first entry, which of its exits this is (0 .. first_entry_exits - 1:
  // SubsurfaceMaterial::first_entry_exits); -1 at any other entry.
  int exit_index = -1;
  // exit_light is zero wherever it is asked (no light the exits may sample: the scene's
  // lights are uniform skies that give way there): a method need not ask it.
  bool exit_light_none = false;
  // The object's far side below the entry point, where a ray from hit.p along -hit.ng
  // leaves it (the walk's backward guiding: sss/walk/random_walk.h make_walk_guide):
  // traced by the entry's first walk that asks and kept for its other exits, which would
  // trace the same ray (three per entry with one colour channel per walk).
  mutable std::optional<sss::BoundaryHit> far_side = {};
  // The lights as seen from inside, for light sampled through a smooth boundary
  // (refracted_light.h); null where the integrator does not offer it.
  const LightsFromInside* lights_from_inside = nullptr;
  // The path's wavelengths (spectral transport: each colour channel of the exit's weight
  // is the value at one of them; integrator.h PathStart::wavelengths); null: RGB. A method
  // reads its parameters at them (coefficients.h medium_at_wavelengths).
  const SampledWavelengths* wavelengths = nullptr;
  // The object's grid interior medium at the path's colours or wavelengths
  // (SubsurfaceParams::interior), which the walk follows by null collisions
  // (heterogeneous_walk.h); null: the material's own parameters.
  const GridMediumView* interior = nullptr;
};

}  // namespace dermis
