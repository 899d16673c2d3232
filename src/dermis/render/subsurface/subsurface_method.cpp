#include "dermis/render/subsurface/subsurface_method.h"

#include <stdexcept>

#include "dermis/materials/bsdf.h"
#include "dermis/core/microfacet.h"

namespace dermis {

namespace {

SubsurfaceMethod make_method(const SubsurfaceParams& p, const std::vector<Texture>* textures) {
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
      return SubsurfaceMethod(std::in_place_type<PointCloudMethod>, p, textures);
    case Method::Volumetric:
      break;
  }
  throw std::invalid_argument("the volumetric method is a medium in a dielectric, not an exit sampler");
}

}  // namespace

SubsurfaceMaterial make_subsurface_material(const SubsurfaceParams& params, const std::vector<Texture>* textures) {
  SubsurfaceMaterial m{params, params.eta, params.eta, subsurface_exit_normalization(params.eta), 0, 0,
                       make_method(params, textures)};
  if (params.method == SubsurfaceParams::Method::RandomWalk && params.boundary == SubsurfaceParams::Boundary::Matched)
    m.entry_eta = 1;
  if (m.entry_eta != 1) {
    m.alpha_x = roughness_to_alpha(params.uroughness, params.remap_roughness);
    m.alpha_y = roughness_to_alpha(params.vroughness, params.remap_roughness);
  }
  return m;
}

}  // namespace dermis
