#include "dermis/render/subsurface/subsurface_method.h"

#include <algorithm>
#include <stdexcept>

#include "dermis/core/microfacet.h"
#include "dermis/materials/bsdf.h"

namespace dermis {

namespace {

SubsurfaceMethod make_method(const SubsurfaceParams& p, const std::vector<Texture>* textures, float sw_norm,
                             double object_chord) {
  using Method = SubsurfaceParams::Method;
  switch (p.method) {
    case Method::Disk:
    case Method::DiskSingleAxis:
    case Method::SphereLines:
    case Method::SphereLinesRetry:
      return SubsurfaceMethod(std::in_place_type<ProbeMethod>, p, textures);
    case Method::RandomWalk:
      return SubsurfaceMethod(std::in_place_type<WalkMethod>, p, textures, object_chord);
    case Method::PointCloud:
      return SubsurfaceMethod(std::in_place_type<PointCloudMethod>, p, sw_norm, textures);
    case Method::Volumetric:
      break;
  }
  throw std::invalid_argument("the volumetric method is a medium in a dielectric, not an exit sampler");
}

}  // namespace

SubsurfaceMaterial make_subsurface_material(const SubsurfaceParams& params, const std::vector<Texture>* textures,
                                            double object_chord) {
  const bool matched_walk =
      params.method == SubsurfaceParams::Method::RandomWalk && params.boundary == SubsurfaceParams::Boundary::Matched;
  const float entry_eta = matched_walk ? 1 : params.eta;
  const BoundaryRoughness roughness(params, entry_eta == 1, textures);
  // A rough boundary: light leaves through its transmittance (rough_exit_lobe.h), in the
  // lobe Sw and in the point cloud's normalisation alike; a textured one through the
  // table of each exit point's alpha.
  std::optional<RoughExitTable> exit_table;
  std::shared_ptr<const RoughExitTables> exit_tables;
  const BoundaryAlphas a = roughness.constant();
  if (a.rough()) exit_table = make_rough_exit_table(params.eta, a.x, a.y);
  if (roughness.textured()) exit_tables = std::make_shared<const RoughExitTables>(params.eta);
  const float sw_norm = exit_table ? exit_table->norm : subsurface_exit_normalization(params.eta);
  return SubsurfaceMaterial{params,     entry_eta,  params.eta,
                            sw_norm,    roughness,  make_method(params, textures, sw_norm, object_chord),
                            exit_table, exit_tables};
}

}  // namespace dermis
