// The `subsurface` material's parameters, read once by the scene parser from what the
// user wrote: pbrt-v4's (reflectance + mfp, or sigma_a + sigma_s, or a preset name;
// scale, eta, g, roughness) and Dermis' own (profile, method, boundary, walksampling,
// ...). The table subsurface_parameters() lists every one; docs/materials.md is
// checked against it.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/scene/diagnostics.h"

namespace dermis {

class ParamList;
struct ParsedParam;

struct SubsurfaceParams {
  enum class Method { Volumetric, Disk, DiskSingleAxis, SphereLines, SphereLinesRetry, RandomWalk, PointCloud };
  enum class Profile { Gaussian, Skin6, Cubic, Dipole, Burley, BurleyDiffuseMfp, Tabulated, PhotonBeam };
  enum class Boundary { Diffuse, Dielectric, Matched };
  enum class WalkSampling { Classical, Dwivedi, Mis };

  // Coefficients per scene unit (scale applied) when given directly or by preset.
  std::optional<RGB> sigma_a, sigma_s;
  // Surface albedo and mean free path (scene units, scale applied) when given that way.
  std::optional<RGB> reflectance, mfp;
  // Spectrum textures (SceneDesc::textures) replacing the values above at each entry
  // point, -1 for none; the value above is then the texture's mean, for what needs one
  // number per material (e.g. the point spacing of a point cloud).
  int sigma_a_texture = -1, sigma_s_texture = -1, reflectance_texture = -1, mfp_texture = -1;
  // The same given as spectra (a named spectrum, a file, samples, a blackbody): their values at
  // every nanometre of 360-830 nm, before `scale`, for spectral rendering (the RGBs above are
  // their colours); null where given otherwise.
  std::shared_ptr<const std::vector<float>> sigma_a_spectrum, sigma_s_spectrum, reflectance_spectrum, mfp_spectrum;
  // A float texture for `scale` (-1: none): at each entry point it multiplies the
  // coefficients and mfp (as pbrt-v4) and divides the Skin6 profile's mm, on top of `scale`
  // below, which is then 1.
  int scale_texture = -1;
  float eta = 1.33f;
  // The boundary's microfacet roughness (pbrt-v4's parameters; alpha = sqrt(r) when
  // remapped): a rough dielectric at the entry of every method and at the exits of the
  // walk's `dielectric` boundary.
  float uroughness = 0, vroughness = 0;
  bool remap_roughness = true;
  // A float texture for "roughness" (both axes, per surface point), -1 for none; the
  // constants above are then 0. uroughness / vroughness cannot be textured.
  int roughness_texture = -1;
  float g = 0;
  float scale = 1;  // as written (already applied to the coefficients and lengths above)
  Method method = Method::RandomWalk;
  Profile profile = Profile::Burley;
  // The random walk's boundary. Unless "boundary" is given, it follows the parametrisation
  // (default_walk_boundary): a medium given by its coefficients (sigma_a + sigma_s, a
  // named medium, or pbrt-v4's default milk) gets `dielectric`, the physical object they
  // describe; reflectance + mfp, the artist's parametrisation, gets `diffuse`.
  Boundary boundary = Boundary::Diffuse;
  bool boundary_given = false;
  // Random walk, `diffuse` boundary: light that enters takes a direction from a cosine
  // lobe under the surface (a diffuse transmission, Chiang, Kutz & Burley 2016, sec. 4;
  // Cycles 3.x's Random Walk) instead of its refracted direction.
  bool lambertian_entry = false;
  WalkSampling walk_sampling = WalkSampling::Mis;
  // `walksampling` was given: the render's pilot keeps it (and the default guided share).
  bool walk_sampling_given = false;
  // Random walk: the share of guided flights (walksampling mis) and the exponent k of the
  // channel choice (sss/walk/walk_step.h); given, the render's pilot keeps them
  // (render/subsurface_pilot.h), else it chooses among the walk's strategies.
  float guided_share = 0.5f;
  bool guided_share_given = false;
  // The share is pinned (given, or `walksampling` given): every strategy of the pilot has it.
  bool guided_share_pinned() const { return walk_sampling_given || guided_share_given; }
  float channel_preference = 0.5f;
  bool channel_preference_given = false;
  // Random walk: each of the camera's first entry's walks carries one colour channel
  // (render/subsurface/walk_method.h, WalkStrategy::channel_per_walk); given, the pilot
  // keeps it.
  bool channel_per_walk = false;
  bool channel_per_walk_given = false;
  // Disk: the probability of probing along the normal, T and B sharing the rest
  // (render/subsurface/probe_method.h, kDiskNormalAxisShares); given, the render's pilot
  // keeps it, else it chooses among the disk's strategies (0.75 without the pilot).
  float normal_axis = 0.75f;
  bool normal_axis_given = false;
  // Random walk: also guide toward the object's far side (sss/walk/random_walk.h); given,
  // the render's pilot keeps it, else it measures it among the walk's strategies
  // (WalkStrategy::backward_guiding).
  bool backward_guiding = false;
  bool backward_guiding_given = false;
  // (reflectance, mfp) -> coefficients: the exact half-space table, or the van de Hulst
  // fit (g = 0, index-matched) for comparison.
  bool albedo_inversion_fit = false;
  // Point cloud (Jensen & Buehler 2002; Langlands & Mertens): octree criterion, the
  // local disk on/off, points per mean free path squared, irradiance samples per point.
  float epsilon = 0.05f;
  bool local_disk = true;
  float point_density = 1.0f;
  int irradiance_samples = 64;
  // The most points per object: the density above asks for area * density / mfp^2,
  // which grows without bound for a large object of short mfp; the local disk integral
  // keeps a sparser cloud usable (Langlands & Mertens), so the count is capped (warned).
  int max_points = 250000;
  // With the local disk the cloud only has to represent the irradiance (Langlands &
  // Mertens): its count is refined from a pilot until each point's E is predicted from its
  // neighbours within this relative RMS error (0: the density above, up to max_points).
  float illumination_error = 0.02f;
  // Materials with the same non-empty group form one subsurface object with every shape
  // that uses them; otherwise the object is the shapes sharing this material (pbrt-v4).
  std::string group;
  // "interior": a named medium (MakeNamedMedium) fills the object instead of the
  // coefficients above (docs/materials.md, "A heterogeneous interior"). The parser resolves
  // the name: a homogeneous medium's coefficients, g and spectra are copied above (and
  // interior_medium stays -1); a grid medium's index into SceneDesc::media (the renderer's
  // medium of the same index) is kept in interior_medium, and the random walk follows it by
  // null collisions (render/subsurface/heterogeneous_walk.h), the volumetric reference
  // fills the object with it. The other methods refuse a grid medium.
  std::string interior;
  SourceLoc interior_loc;
  int interior_medium = -1;
  SourceLoc loc;

  // The medium was given by its coefficients (sigma_a + sigma_s, a named medium, or none:
  // pbrt-v4's milk), not by reflectance + mfp.
  bool coefficient_given() const { return !reflectance.has_value(); }

  bool textured() const {
    return sigma_a_texture >= 0 || sigma_s_texture >= 0 || reflectance_texture >= 0 || mfp_texture >= 0 ||
           scale_texture >= 0;
  }
};

// One row of the parameter table.
struct SubsurfaceParameter {
  const char* name;
  const char* type;           // as written in a scene ("rgb", "float", "string", ...)
  const char* default_value;  // as the docs state it
  const char* meaning;
};
std::span<const SubsurfaceParameter> subsurface_parameters();

// The spectrum texture a "texture NAME" parameter names (its index in
// SceneDesc::textures); throws SceneError when there is none.
// The scene's index of the texture a parameter names: a spectrum texture, or a float
// texture when `is_float`. Throws SceneError when there is none of that kind.
using TextureIndexOf = std::function<int(const ParsedParam&, bool is_float)>;

// Reads every parameter of a `subsurface` material (marking them used). Throws
// SceneError (file:line:col) for wrong types, unknown names or invalid values; warns
// about parameters it ignores.
// The walk's boundary when "boundary" is not given: `dielectric` for a medium given by its
// coefficients, `diffuse` for reflectance + mfp (docs/materials.md, "Which boundary").
SubsurfaceParams::Boundary default_walk_boundary(const SubsurfaceParams& params);

SubsurfaceParams read_subsurface_params(const ParamList& params, const SourceLoc& loc, Diagnostics& diag,
                                        const TextureIndexOf& texture_index_of);

const char* to_string(SubsurfaceParams::Method m);
const char* to_string(SubsurfaceParams::Profile p);

}  // namespace dermis
