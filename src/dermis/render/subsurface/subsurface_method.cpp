#include "dermis/render/subsurface/subsurface_method.h"

#include <algorithm>
#include <stdexcept>

#include "dermis/materials/bsdf.h"
#include "dermis/core/microfacet.h"

namespace dermis {

namespace {

SubsurfaceMethod make_method(const SubsurfaceParams& p, const std::vector<Texture>* textures, float sw_norm) {
  using Method = SubsurfaceParams::Method;
  switch (p.method) {
    case Method::Disk:
    case Method::DiskSingleAxis:
    case Method::SphereLines:
    case Method::SphereLinesRetry:
      return SubsurfaceMethod(std::in_place_type<ProbeMethod>, p, textures);
    case Method::RandomWalk:
      return SubsurfaceMethod(std::in_place_type<WalkMethod>, p, textures);
    case Method::PointCloud:
      return SubsurfaceMethod(std::in_place_type<PointCloudMethod>, p, sw_norm, textures);
    case Method::Volumetric:
      break;
  }
  throw std::invalid_argument("the volumetric method is a medium in a dielectric, not an exit sampler");
}

}  // namespace

SubsurfaceMaterial make_subsurface_material(const SubsurfaceParams& params, const std::vector<Texture>* textures) {
  const bool matched_walk =
      params.method == SubsurfaceParams::Method::RandomWalk && params.boundary == SubsurfaceParams::Boundary::Matched;
  const float entry_eta = matched_walk ? 1 : params.eta;
  float alpha_x = 0, alpha_y = 0;
  if (entry_eta != 1) {
    alpha_x = roughness_to_alpha(params.uroughness, params.remap_roughness);
    alpha_y = roughness_to_alpha(params.vroughness, params.remap_roughness);
  }
  // A rough boundary: light leaves through its transmittance (rough_exit_lobe.h), in the
  // lobe Sw and in the point cloud's normalisation alike.
  std::optional<RoughExitTable> exit_table;
  if (std::max(alpha_x, alpha_y) >= kSmoothAlpha) exit_table = make_rough_exit_table(params.eta, alpha_x, alpha_y);
  const float sw_norm = exit_table ? exit_table->norm : subsurface_exit_normalization(params.eta);
  return SubsurfaceMaterial{params,  entry_eta, params.eta,
                            sw_norm, alpha_x,   alpha_y,
                            make_method(params, textures, sw_norm), exit_table};
}

}  // namespace dermis
