// The `subsurface` material in the path tracer: one method per material, a closed
// variant of one type per family. Each family lives in its own file and has one entry
// point, sample_exit(entry, sampler, out): where light that entered at a point leaves
// the object (subsurface_exit.h). The integrator calls it through std::visit and does
// not know which paper a method came from.
//
// Adding a family: a class with that sample_exit in its own file, an entry in the
// variant below, its name in the parameter table (materials/subsurface_params.cpp)
// and a case in make_subsurface_material().
//
// The `volumetric` reference is not an exit sampler: the scene turns the material
// into a smooth dielectric filled with the medium it describes (scene_assembly.h),
// and the volumetric path tracer renders it.
#pragma once

#include <memory>
#include <optional>
#include <variant>

#include "dermis/lights/light_selection.h"
#include "dermis/materials/bsdf.h"
#include "dermis/materials/rough_exit_lobe.h"
#include "dermis/render/subsurface/boundary_roughness.h"
#include "dermis/render/subsurface/point_cloud_method.h"
#include "dermis/render/subsurface/probe_method.h"
#include "dermis/render/subsurface/walk_method.h"
#include "dermis/scene/subsurface_params.h"

namespace dermis {

using SubsurfaceMethod = std::variant<ProbeMethod, WalkMethod, PointCloudMethod>;

struct SubsurfaceMaterial {
  SubsurfaceParams params;
  float entry_eta = 1.33f;      // index the entry's Fresnel reflection sees (1 for a matched walk)
  float exit_eta = 1.33f;       // index of the exit lobe Sw
  float sw_norm = 1;            // c of the exit lobe Sw (bsdf.h); a textured roughness: the smooth lobe's
  BoundaryRoughness roughness;  // the boundary's alphas, per surface point
  SubsurfaceMethod method;
  // A rough boundary's exit lobe: its transmittance table, whose c is sw_norm
  // (materials/rough_exit_lobe.h). Unset when the boundary is smooth or textured.
  std::optional<RoughExitTable> exit_table;
  // A textured roughness: the tables at alpha nodes, blended at each exit point.
  std::shared_ptr<const RoughExitTables> exit_tables;
  // The method's sampling strategies that differ (SubsurfaceEntry::strategy: the walk's
  // kWalkStrategies, unless its parameters pin one; the disk's axis probabilities,
  // kDiskNormalAxisShares; one for the other methods).
  int strategy_count() const {
    if (const auto* probe = std::get_if<ProbeMethod>(&method)) return probe->strategy_count();
    if (!std::holds_alternative<WalkMethod>(method)) return 1;
    // A grid interior's walk samples the phase function alone (heterogeneous_walk.h): its
    // strategies would be one.
    if (params.interior_medium >= 0) return 1;
    const bool share_given = params.guided_share_pinned();
    // One channel per walk has no channel preference to choose.
    const bool channels_given =
        params.channel_preference_given || (params.channel_per_walk_given && params.channel_per_walk);
    return share_given && channels_given ? 1 : int(kWalkStrategies.size());
  }

  // The walk's strategy gives each of the camera's first entry's walks one colour channel.
  bool channel_per_walk(int strategy) const {
    const WalkMethod* walk = std::get_if<WalkMethod>(&method);
    return walk && walk->channel_per_walk(strategy);
  }

  // Whether uniform skies are light-sampled at the material's exits. A walk: per strategy
  // (WalkStrategy::exit_sky_sampled; sampled where its parameters pin its strategy,
  // whatever the pilot tries on the others). The probe methods: never (SkyRule::GivesWay;
  // the exit lobe's way on finds them at MIS weight one). Their exit is cosine-like, as a
  // uniform sky's light sample is, and leaving that sample out kept the variance for less
  // render time on every sky-lit configuration measured, where the walk's default lost
  // (docs/probe-sampling.md).
  SkyRule exit_sky_rule(int strategy) const {
    if (!std::holds_alternative<WalkMethod>(method))
      return exits_through_lobe() ? SkyRule::GivesWay : SkyRule::Outweighed;  // the point cloud: no exits
    return strategy_count() > 1 && strategy > 0 && strategy < int(kWalkStrategies.size()) &&
                   !kWalkStrategies[std::size_t(strategy)].exit_sky_sampled
               ? SkyRule::GivesWay
               : SkyRule::Outweighed;
  }

  // How many exits the camera's first entry averages (SubsurfaceEntry::exit_index), each
  // going on with its share of the path: the scene's `subsurfacesamples` where the exits
  // leave through the exit lobe, else one; a walk that gives each its own colour channel
  // takes a multiple of three (WalkStrategy::channel_per_walk).
  int first_entry_exits(int strategy, int subsurface_samples) const {
    const int requested = exits_through_lobe() ? subsurface_samples : 1;
    if (channel_per_walk(strategy)) return (requested + kChannelWalks - 1) / kChannelWalks * kChannelWalks;
    return requested;
  }

  // Whether the camera's first entry's exits are drawn as one Sobol' sequence
  // (Sampler::set_split): the probes', whose variance is much their first numbers'. Not a
  // walk's: its variance is not in its first eight numbers, and on the sky-lit fins it rose
  // (docs/probe-sampling.md, "The exits as one sequence").
  bool exits_as_one_sequence() const { return std::holds_alternative<ProbeMethod>(method); }

  // Its exits leave through the exit lobe Sw (SubsurfaceExit::Kind::ThroughLobe): the probe
  // methods, and the walk with the diffuse boundary.
  bool exits_through_lobe() const {
    using M = SubsurfaceParams::Method;
    return params.method == M::Disk || params.method == M::DiskSingleAxis || params.method == M::SphereLines ||
           params.method == M::SphereLinesRetry ||
           (params.method == M::RandomWalk && params.boundary == SubsurfaceParams::Boundary::Diffuse);
  }

  // The exit lobe Sw at an exit point, about its shading normal hit.ns (on the outward
  // side, as hit.ng; bsdf.h, geometry/shading_normal.h). A textured
  // roughness blends the table of the point's alpha into `scratch`, which the lobe
  // points to (it must outlive the lobe's use).
  BSDF exit_lobe(const SurfaceHit& hit, RoughExitTable& scratch) const {
    BSDF b;
    b.type = BSDF::Type::SubsurfaceExit;
    b.n = hit.ns;
    b.eta = exit_eta;
    b.sw_norm = sw_norm;
    b.exit_table = exit_table ? &*exit_table : nullptr;
    if (exit_tables) {
      const BoundaryAlphas a = roughness.at(hit);
      if (a.rough()) {
        exit_tables->at(a.x, scratch);
        b.exit_table = &scratch;
        b.sw_norm = scratch.norm;
      }
    }
    return b;
  }

  // The entry as a BSDF: a smooth or rough dielectric about the entry's shading normal.
  BSDF entry_boundary(const SurfaceHit& hit) const {
    BSDF b;
    b.type = BSDF::Type::Dielectric;
    b.n = hit.ns;
    b.eta = entry_eta;
    const BoundaryAlphas a = roughness.at(hit);
    b.alpha_x = a.x;
    b.alpha_y = a.y;
    return b;
  }
};

// Builds the method of a material (profiles, probe tables, a rough boundary's exit
// table; for the walk, the albedo
// inversion when the user gave reflectance + mfp, which may take seconds the first
// time). Throws std::invalid_argument for parameters a method cannot use.
// textures: the scene's, which textured parameters read (must outlive the material).
// object_chord: the mean chord length of the object it fills (geometry/mean_chord.h; 0:
// unknown), which the walk's guiding takes (walk_method.h, short_walk_guided_shares).
SubsurfaceMaterial make_subsurface_material(const SubsurfaceParams& params,
                                            const std::vector<Texture>* textures = nullptr, double object_chord = 0);

inline bool sample_subsurface_exit(const SubsurfaceMaterial& m, const SubsurfaceEntry& entry, Sampler& sampler,
                                   SubsurfaceExit& out) {
  return std::visit([&](const auto& method) { return method.sample_exit(entry, sampler, out); }, m.method);
}

}  // namespace dermis
