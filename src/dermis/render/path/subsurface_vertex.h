// A path's vertex at a subsurface material's boundary (Cycles' subsurface part of
// shade_surface and its subsurface_*.h): the entry (a smooth boundary's reflection split off
// at the camera's first hit or chosen by Fresnel, a rough one sampled), the exit or exits
// the material's method samples (render/subsurface/subsurface_method.h) with their direct
// light, and the way on from the exit: through the exit lobe (split into copies when the
// path is heavy), along a direction the method gave, or nowhere. The integrator does not
// know which method it is.
#pragma once

#include <cstdint>

#include "dermis/core/rgb.h"
#include "dermis/geometry/ray.h"
#include "dermis/render/path/path_state.h"
#include "dermis/render/subsurface/subsurface_exit.h"
#include "dermis/render/subsurface/subsurface_method.h"

namespace dermis {

class SubsurfaceVertex {
 public:
  // At `hit` on a shape of subsurface material mat, seen along wo = -st.ray.d (hit.ns
  // already facing it; depth already counted).
  SubsurfaceVertex(PathContext& ctx, PathState& st, const SurfaceHit& hit, const Material& mat, Vec3 wo);

  // kContinue: the path goes on along st.ray; kStop: it ended.
  VertexOutcome shade();

 private:
  // The entry: true when the path goes into the medium (refracted_: the direction a rough
  // boundary sampled), false when it went on (outcome_) or ended at the boundary.
  bool enter();
  // The exits the method samples, their light gathered; the way on from the first.
  VertexOutcome exit();
  // Exits 1 .. exits - 1 besides `first` (found: whether it was), their estimates averaged
  // into it; at the camera's first entry each also goes on as a nested path.
  void sample_more_exits(SubsurfaceEntry& entry, SubsurfaceExit& first, bool found, int exits, bool split_exits,
                         uint64_t exits_region);
  // The way on through the exit lobe at ex.hit (path splitting's copies nested).
  VertexOutcome leave_through_lobe(const SubsurfaceExit& ex);

  // What the method may ask (SubsurfaceEntry's callables).
  RGB irradiance(Vec3 p, Vec3 n, float eta, Sampler& smp) const;
  RGB interior_albedo(const SurfaceHit& h) const;
  // Light sampled through a rough boundary from inside (a walk's exits), on the outside,
  // in the medium the path entered from.
  RGB light_through(Vec3 p, Vec3 n, const BSDF& b, Vec3 wo_in, Sampler& smp) const;
  // Direct light leaving through the exit lobe sw at a point, from the outside's medium.
  RGB light_through_lobe(const SurfaceHit& at, const BSDF& sw, Sampler& smp) const;
  RGB exit_light(const SurfaceHit& at, Sampler& smp) const;

  // Nested ways on (a path splitting's copy, or another exit's at the camera's first entry),
  // each adding beta x weight / divisor x its radiance to st.L: from the exit point `at`
  // through its lobe (sampled from the sampler's current dimension), or along an Along
  // exit's direction; the nested path draws from first_dimension.
  void go_on_from_exit(const SurfaceHit& at, const BSDF& lobe, const RGB& weight, float divisor,
                       uint64_t first_dimension);
  void go_on_along(const SubsurfaceExit& e, float divisor, uint64_t first_dimension);

  PathContext& ctx_;
  PathState& st_;
  const SurfaceHit& hit_;
  const Material& mat_;
  const SubsurfaceMaterial& sm_;
  const Vec3 wo_;
  bool first_entry_ = false;  // the camera's first entry (PathState::camera_chain)
  std::optional<Vec3> refracted_;
  VertexOutcome outcome_ = VertexOutcome::kStop;  // when enter() is false
  int strategy_ = 0;
  SkyRule exit_sky_ = SkyRule::Sampled;
  bool exit_light_none_ = false;
  uint64_t after_exit_ = 0;  // the sampler's dimension at the exits: their regions' base
};

}  // namespace dermis
