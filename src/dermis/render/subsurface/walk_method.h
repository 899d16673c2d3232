// A volumetric random walk under the surface (Křivánek & d'Eon 2014; sss/walk/): the
// path refracts in at the entry and walks in the medium the material describes until
// it crosses the boundary. The boundary decides how light leaves: `diffuse` through the
// exit lobe Sw at the first crossing, `matched` straight through it, `dielectric` by
// Fresnel (internal reflection continues the walk, refraction leaves specularly).
// Textured parameters: the medium of a walk is the one at its entry point (its
// coefficients from the exact albedo inversion's table: a lookup, no simulation), kept
// for the whole walk, as in Cycles: a texture varying under the surface is blurred
// over the walk's extent, not followed. A textured roughness is the boundary's at each
// point the walk meets it (entry and exits); the albedo inversion takes the entry's.
#pragma once

#include <memory>
#include <vector>

#include "dermis/scene/subsurface_params.h"
#include "dermis/render/subsurface/boundary_roughness.h"
#include "dermis/render/subsurface/coefficients.h"
#include "dermis/render/subsurface/subsurface_exit.h"
#include "dermis/sss/walk/albedo_inversion.h"
#include "dermis/sss/walk/random_walk.h"

namespace dermis {

class WalkMethod {
 public:
  // textures: the scene's (outlives the method). Builds the albedo-inversion table the
  // parameters need (seconds the first time in a process; cached on disk).
  WalkMethod(const SubsurfaceParams& params, const std::vector<Texture>* textures);

  bool sample_exit(const SubsurfaceEntry& entry, Sampler& sampler, SubsurfaceExit& out) const;

  const sss::WalkMedium& medium() const { return medium_; }

 private:
  bool walk(const SubsurfaceEntry& entry, const sss::MixtureWalkStep<3>& step, Sampler& sampler,
            SubsurfaceExit& out) const;

  SubsurfaceParams params_;
  const std::vector<Texture>* textures_;
  AlbedoInversions inversions_;  // (reflectance, mfp) -> coefficients; empty: given, or the fit
  SubsurfaceParams::Boundary boundary_;
  float eta_;
  BoundaryRoughness roughness_;  // the boundary's alphas per point (the `dielectric` boundary's exits)
  // The medium differs from one entry point to another: textured parameters, or a
  // textured roughness that the albedo inversion depends on.
  bool medium_per_entry_ = false;
  sss::WalkMedium medium_;  // the constant parameters' medium
  sss::WalkSettings settings_;
  std::unique_ptr<sss::MixtureWalkStep<3>> step_;
};

}  // namespace dermis
