// The `subsurface` material in the path tracer: one SubsurfaceMethod per material,
// built once, and the sampling of where light that entered at a point leaves the
// object. The integrator does not know which paper a method came from.
#pragma once

#include <memory>

#include "dermis/core/rgb.h"
#include "dermis/core/sampler.h"
#include "dermis/geometry/ray.h"
#include "dermis/materials/subsurface_params.h"
#include "dermis/sss/probe/disk_probe.h"
#include "dermis/sss/probe/sphere_lines.h"
#include "dermis/sss/profiles/profile.h"
#include "dermis/sss/walk/random_walk.h"

namespace dermis {

struct RenderScene;
struct PathCounters;

struct SubsurfaceMethod {
  SubsurfaceParams params;
  float sw_norm = 1;                       // c of the exit lobe Sw (bsdf.h)
  float entry_eta = 1.33f;                 // index seen at entry (1 for a matched walk)
  RGB albedo;                              // surface albedo per channel (profiles)
  RGB mean_free_path;                      // per channel (point density of the point cloud)
  // Profile methods (disk, sphere lines).
  std::unique_ptr<sss::ProfileRGB> profile;
  std::unique_ptr<sss::DiskProbeSampler> disk;
  std::unique_ptr<sss::SphereLineTablesRGB> line_tables;
  std::unique_ptr<sss::SphereLineSampler> lines;
  // Random walk: coefficients per scene unit and the prepared step (sss/walk/).
  sss::WalkMedium walk_medium;
  sss::WalkSettings walk_settings;
  std::unique_ptr<sss::MixtureWalkStep<3>> walk_step;

  bool is_volumetric() const { return params.method == SubsurfaceParams::Method::Volumetric; }
};

// Builds the method of a material; `sigma_a`/`sigma_s` are resolved already when the
// user gave reflectance + mfp (the random walk's exact albedo inversion).
std::unique_ptr<SubsurfaceMethod> make_subsurface_method(const SubsurfaceParams& params);

// Scattering coefficients per scene unit: as given, or from (reflectance, mfp) through
// the random walk's exact albedo inversion (a half-space table for the boundary's eta and g).
void resolve_coefficients(const SubsurfaceParams& params, RGB& sigma_a, RGB& sigma_s);

// Where light entering at `entry` (travelling against wo) leaves the object.
struct SubsurfaceExit {
  SurfaceHit hit;         // the exit point; hit.ng points out of the object
  RGB weight;             // multiplies the path throughput (estimate / pdf)
  bool diffuse_exit = true;  // continue with the Sw lobe at hit; otherwise leave along `direction`
  Vec3 direction;
  bool truncated = false;    // the random walk hit its step cap
};

// Returns false when the estimate is zero (no exit found, or the path was absorbed).
bool sample_subsurface_exit(const RenderScene& scene, const SubsurfaceMethod& method, const SurfaceHit& entry, Vec3 wo,
                            Sampler& sampler, PathCounters& counters, SubsurfaceExit& out);

}  // namespace dermis
