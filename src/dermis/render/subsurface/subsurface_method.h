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

#include <optional>
#include <variant>

#include "dermis/materials/bsdf.h"
#include "dermis/materials/rough_exit_lobe.h"

#include "dermis/scene/subsurface_params.h"
#include "dermis/render/subsurface/point_cloud_method.h"
#include "dermis/render/subsurface/probe_method.h"
#include "dermis/render/subsurface/walk_method.h"

namespace dermis {

using SubsurfaceMethod = std::variant<ProbeMethod, WalkMethod, PointCloudMethod>;

struct SubsurfaceMaterial {
  SubsurfaceParams params;
  float entry_eta = 1.33f;  // index the entry's Fresnel reflection sees (1 for a matched walk)
  float exit_eta = 1.33f;   // index of the exit lobe Sw
  float sw_norm = 1;        // c of the exit lobe Sw (bsdf.h)
  float alpha_x = 0, alpha_y = 0;  // the boundary's Trowbridge-Reitz alphas (0: smooth)
  SubsurfaceMethod method;
  // A rough boundary's exit lobe: its transmittance table, whose c is sw_norm
  // (materials/rough_exit_lobe.h). Unset when the boundary is smooth.
  std::optional<RoughExitTable> exit_table;

  // The exit lobe Sw at an exit point with outward normal n (bsdf.h).
  BSDF exit_lobe(Vec3 n) const {
    BSDF b;
    b.type = BSDF::Type::SubsurfaceExit;
    b.n = n;
    b.eta = exit_eta;
    b.sw_norm = sw_norm;
    b.exit_table = exit_table ? &*exit_table : nullptr;
    return b;
  }

  // The entry as a BSDF: a smooth or rough dielectric about the entry's normal n.
  BSDF entry_boundary(Vec3 n) const {
    BSDF b;
    b.type = BSDF::Type::Dielectric;
    b.n = n;
    b.eta = entry_eta;
    b.alpha_x = alpha_x;
    b.alpha_y = alpha_y;
    return b;
  }
};

// Builds the method of a material (profiles, probe tables, a rough boundary's exit
// table; for the walk, the albedo
// inversion when the user gave reflectance + mfp, which may take seconds the first
// time). Throws std::invalid_argument for parameters a method cannot use.
// textures: the scene's, which textured parameters read (must outlive the material).
SubsurfaceMaterial make_subsurface_material(const SubsurfaceParams& params,
                                            const std::vector<Texture>* textures = nullptr);

inline bool sample_subsurface_exit(const SubsurfaceMaterial& m, const SubsurfaceEntry& entry, Sampler& sampler,
                                   SubsurfaceExit& out) {
  return std::visit([&](const auto& method) { return method.sample_exit(entry, sampler, out); }, m.method);
}

}  // namespace dermis
