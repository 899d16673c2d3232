// The `subsurface` material's parameters, read from what the user wrote: pbrt-v4's
// (reflectance + mfp, or sigma_a + sigma_s, or a preset name; scale, eta, g,
// roughness) and Dermis' own (profile, method, boundary, walksampling).
// docs/materials.md documents every parameter.
#pragma once

#include <optional>
#include <string>

#include "dermis/core/rgb.h"
#include "dermis/scene/scene_desc.h"

namespace dermis {

struct SubsurfaceParams {
  enum class Method { Volumetric, Disk, DiskSingleAxis, SphereLines, SphereLinesRetry, RandomWalk, PointCloud };
  enum class Profile { Gaussian, Skin6, Cubic, Dipole, Burley, BurleyDiffuseMfp, Tabulated };
  enum class Boundary { Diffuse, Dielectric, Matched };
  enum class WalkSampling { Classical, Dwivedi, Mis };

  // Coefficients per scene unit (scale applied) when given directly or by preset.
  std::optional<RGB> sigma_a, sigma_s;
  // Surface albedo and mean free path (scene units, scale applied) when given that way.
  std::optional<RGB> reflectance, mfp;
  float eta = 1.33f;
  float g = 0;
  float scale = 1;  // as written (already applied to the coefficients and lengths above)
  Method method = Method::RandomWalk;
  Profile profile = Profile::Burley;
  Boundary boundary = Boundary::Diffuse;
  WalkSampling walk_sampling = WalkSampling::Mis;
  // Random walk: also guide toward the object's far side (sss/walk/random_walk.h).
  bool backward_guiding = false;
  // (reflectance, mfp) -> coefficients: the exact half-space table, or the van de Hulst
  // fit (g = 0, index-matched) for comparison.
  bool albedo_inversion_fit = false;
  // Point cloud (Jensen & Buehler 2002; Langlands & Mertens): octree criterion, the
  // local disk on/off, points per mean free path squared, irradiance samples per point.
  float epsilon = 0.05f;
  bool local_disk = true;
  float point_density = 1.0f;
  int irradiance_samples = 64;
  SourceLoc loc;
};

// Throws SceneError (file:line:col) for wrong types, unknown names or invalid values;
// warns about parameters it ignores.
SubsurfaceParams read_subsurface_params(const MaterialDesc& m, Diagnostics& diag);

const char* to_string(SubsurfaceParams::Method m);
const char* to_string(SubsurfaceParams::Profile p);

}  // namespace dermis
