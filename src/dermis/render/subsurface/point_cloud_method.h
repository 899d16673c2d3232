// Point-cloud diffusion (Jensen & Buehler 2002; the local disk integral of Langlands &
// Mertens, seed 001): the light leaving a point is Sw-weighted radiant exitance M(x)
// from a cloud of surface points holding the irradiance that entered there. The cloud
// of each object is computed while the scene is prepared (render/point_cloud_prepass.h);
// until then the method finds no exit.
#pragma once

#include <memory>
#include <vector>

#include "dermis/materials/texture.h"
#include "dermis/render/subsurface/subsurface_exit.h"
#include "dermis/scene/subsurface_params.h"
#include "dermis/sss/pointcloud/point_cloud_diffusion.h"
#include "dermis/sss/profiles/profile.h"
#include "dermis/sss/profiles/tabulated.h"

namespace dermis {

// Textured parameters: the cloud holds irradiance and area only; the exitance at a
// shading point spreads every point's E_p A_p with the profile of the parameters at the
// shading point (as the probes weight every exit with the entry point's profile).
// Spectral transport: the cloud stays RGB, and its light's colour is uplifted to the path's
// wavelengths (a documented limitation: the colour is the RGB method's, not the spectrum's).
class PointCloudMethod {
 public:
  // sw_norm: c of the exit lobe Sw (bsdf.h; the rough table's when the boundary is rough).
  // textures: the scene's (outlives the method); null when the parameters are constant.
  PointCloudMethod(const SubsurfaceParams& params, float sw_norm, const std::vector<Texture>* textures = nullptr);

  bool sample_exit(const SubsurfaceEntry& entry, Sampler& sampler, SubsurfaceExit& out) const;

  const sss::ProfileRGB& profile() const { return *profile_; }
  const SubsurfaceParams& params() const { return params_; }
  // The smallest mean free path of the three channels: the cloud's point spacing.
  float min_mean_free_path() const { return min_mfp_; }

  // The cloud of object `object` (ObjectTracer::object()).
  void set_cloud(int object, std::shared_ptr<const sss::pointcloud::PointCloudDiffusion> cloud);
  const sss::pointcloud::PointCloudDiffusion* cloud(int object) const {
    return object < int(clouds_.size()) ? clouds_[object].get() : nullptr;
  }

 private:
  SubsurfaceParams params_;
  float sw_norm_;
  float min_mfp_;
  const std::vector<Texture>* textures_;
  std::shared_ptr<const sss::ProfileTable> table_;  // the tabulated profile's
  std::unique_ptr<sss::ProfileRGB> profile_;        // the constants' (or the textures' mean)
  std::vector<std::shared_ptr<const sss::pointcloud::PointCloudDiffusion>> clouds_;  // per object
};

}  // namespace dermis
