#include "dermis/render/subsurface/subsurface_method.h"

#include <stdexcept>

#include "dermis/materials/bsdf.h"

namespace dermis {

namespace {

SubsurfaceMethod make_method(const SubsurfaceParams& p) {
  using Method = SubsurfaceParams::Method;
  switch (p.method) {
    case Method::Disk:
    case Method::DiskSingleAxis:
    case Method::SphereLines:
    case Method::SphereLinesRetry:
      return SubsurfaceMethod(std::in_place_type<ProbeMethod>, p);
    case Method::RandomWalk:
      return SubsurfaceMethod(std::in_place_type<WalkMethod>, p, resolve_coefficients(p));
    case Method::PointCloud:
      return SubsurfaceMethod(std::in_place_type<PointCloudMethod>, p);
    case Method::Volumetric:
      break;
  }
  throw std::invalid_argument("the volumetric method is a medium in a dielectric, not an exit sampler");
}

}  // namespace

SubsurfaceMaterial make_subsurface_material(const SubsurfaceParams& params) {
  SubsurfaceMaterial m{params, params.eta, params.eta, subsurface_exit_normalization(params.eta), make_method(params)};
  if (params.method == SubsurfaceParams::Method::RandomWalk && params.boundary == SubsurfaceParams::Boundary::Matched)
    m.entry_eta = 1;
  return m;
}

}  // namespace dermis
