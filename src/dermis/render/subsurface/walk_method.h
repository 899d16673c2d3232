// A volumetric random walk under the surface (Křivánek & d'Eon 2014; sss/walk/): the
// path refracts in at the entry and walks in the medium the material describes until
// it crosses the boundary. The boundary decides how light leaves: `diffuse` through the
// exit lobe Sw at the first crossing, `matched` straight through it, `dielectric` by
// Fresnel (internal reflection continues the walk, refraction leaves specularly).
#pragma once

#include <memory>

#include "dermis/scene/subsurface_params.h"
#include "dermis/render/subsurface/coefficients.h"
#include "dermis/render/subsurface/subsurface_exit.h"
#include "dermis/sss/walk/random_walk.h"

namespace dermis {

class WalkMethod {
 public:
  // `k`: the coefficients per scene unit (coefficients.h resolve_coefficients).
  WalkMethod(const SubsurfaceParams& params, const Coefficients& k);

  bool sample_exit(const SubsurfaceEntry& entry, Sampler& sampler, SubsurfaceExit& out) const;

  const sss::WalkMedium& medium() const { return medium_; }

 private:
  SubsurfaceParams::Boundary boundary_;
  float eta_;
  sss::WalkMedium medium_;
  sss::WalkSettings settings_;
  std::unique_ptr<sss::MixtureWalkStep<3>> step_;
};

}  // namespace dermis
