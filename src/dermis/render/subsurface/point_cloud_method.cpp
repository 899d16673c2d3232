#include "dermis/render/subsurface/point_cloud_method.h"

#include <algorithm>

#include "dermis/core/vec.h"
#include "dermis/materials/bsdf.h"
#include "dermis/render/subsurface/coefficients.h"
#include "dermis/render/subsurface/profile_from_params.h"
#include "dermis/spectral/spectrum_at.h"

namespace dermis {

PointCloudMethod::PointCloudMethod(const SubsurfaceParams& params, float sw_norm, const std::vector<Texture>* textures)
    : params_(params),
      sw_norm_(sw_norm),
      textures_(textures),
      table_(profile_table(params)),
      profile_(std::make_unique<sss::ProfileRGB>(make_profile(params, medium_at(params), table_))) {
  const RGB l = albedo_and_mfp(params).mfp;
  min_mfp_ = std::min({l[0], l[1], l[2]});
}

void PointCloudMethod::set_cloud(int object, std::shared_ptr<const sss::pointcloud::PointCloudDiffusion> cloud) {
  if (object >= int(clouds_.size())) clouds_.resize(object + 1);
  clouds_[object] = std::move(cloud);
}

bool PointCloudMethod::sample_exit(const SubsurfaceEntry& entry, Sampler& sampler, SubsurfaceExit& out) const {
  const sss::pointcloud::PointCloudDiffusion* c = cloud(entry.tracer.object());
  if (!c) return false;  // during the pre-pass: the object's own cloud does not exist yet
  // The local disk needs the irradiance at x itself: one estimate per sample.
  const RGB Ex = params_.local_disk ? entry.irradiance(entry.hit.p, entry.hit.ng, params_.eta, sampler) : RGB(0);
  out.kind = SubsurfaceExit::Kind::Emitted;
  const RGB M = textures_ && params_.textured()
                    ? c->radiant_exitance(
                          entry.hit.p, Ex,
                          make_profile(params_, medium_at(params_, textures_, texture_context(entry.hit)), table_))
                    : c->radiant_exitance(entry.hit.p, Ex);
  out.radiance = M / (sw_norm_ * kPi);  // L = Sw M (METHODS.md sec. 0)
  // A spectral path: the cloud is RGB (its pre-pass gathers RGB irradiance); the colour of
  // its light is uplifted to the path's wavelengths as an emitter's is, which the film
  // turns back into that colour (spectral_limitations, renderer.h).
  if (entry.wavelengths) out.radiance = illuminant_at(out.radiance, *entry.wavelengths);
  return true;
}

}  // namespace dermis
