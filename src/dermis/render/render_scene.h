// Everything the integrator reads: shapes in Embree, materials, textures, media,
// lights with their selection distribution, the camera, and the subsurface methods.
// Made in two steps: assembly (scene_assembly.h: from the parsed SceneDesc, no
// computation beyond building the BVH) and preparation (scene_preparation.h: albedo
// tables, profile tables, point clouds; may take a while, with progress).
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "dermis/geometry/embree_scene.h"
#include "dermis/geometry/shape.h"
#include "dermis/lights/light.h"
#include "dermis/lights/light_selection.h"
#include "dermis/materials/grid_medium.h"
#include "dermis/materials/material.h"
#include "dermis/materials/medium.h"
#include "dermis/materials/texture.h"
#include "dermis/render/camera.h"
#include "dermis/render/subsurface/coefficients.h"
#include "dermis/render/subsurface/subsurface_method.h"
#include "dermis/scene/scene_desc.h"
#include "dermis/scene/subsurface_params.h"

namespace dermis {

// Switches that turn one of the path tracer's variance reductions off, so that a test can
// compare its estimator with the one without (each is unbiased: the same mean). A render
// keeps them all on; they are the scene's, read once per use, not carried by every path.
struct EstimatorSwitches {
  // A camera path follows both reflection and transmission at its first smooth dielectric
  // or subsurface hit (path/camera_reflection.h).
  bool split_first_hit = true;
  // Next-event estimation at rough glass, on both sides of the surface, and at a rough
  // subsurface entry and a walk's rough exits; off: their emission found by BSDF sampling alone.
  bool rough_glass_nee = true;
  // At a smooth subsurface entry or smooth glass not split, in vacuum: the emission the
  // reflection meets, where brighter than twice the mean sky, added weighted F at every hit
  // (path/emission.h add_bright_emission_seen); off: found only on the paths that reflect.
  bool reflection_emission = true;
  // The camera's first smooth reflection, where it cannot see a bright emitter, rouletted on
  // its throughput (path/path_state.h reflection_survival); off: followed always.
  bool reflection_roulette = true;
  // A walk behind a smooth `dielectric` boundary samples the lights through it at its
  // scattering events (subsurface/refracted_light.h); off: found by the walks that leave
  // toward them.
  bool refracted_light = true;
};

struct RenderScene {
  std::vector<Shape> shapes;
  std::unique_ptr<EmbreeScene> embree;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  // Spectra given as data, at every nanometre of 360-830 nm (SceneDesc::spectra): spectral
  // rendering reads them where lights and conductors name them.
  std::vector<std::vector<float>> spectra;
  std::vector<HomogeneousMedium> media;
  // Per medium of the file (the first entries of `media`): its coefficients given as spectra
  // (indices into `spectra`, -1: its RGB's spectrum), and the scale they take.
  struct MediumSpectra {
    int sigma_a = -1, sigma_s = -1;
    float scale = 1;
  };
  std::vector<MediumSpectra> medium_spectra;
  // Per homogeneous medium of the file: its emission (pbrt-v4's Le x Lescale; a grid
  // medium's is its GridMedium's), and Le's spectrum where given as one (an index into
  // `spectra`, at luminance 1: times `scale`).
  struct MediumEmission {
    RGB Le;
    int data = -1;
    float scale = 1;
  };
  std::vector<MediumEmission> medium_emission;
  // The heterogeneous media of the file (uniformgrid, rgbgrid, cloud), and per medium of the
  // file its entry there (-1: homogeneous). A grid medium's entry in `media` holds its
  // coefficients per unit density (rgbgrid: the scale) and its g, which spectral rendering
  // reads at a path's wavelengths as it reads any medium's (spectral_media.h grid_medium_view).
  std::vector<GridMedium> grid_media;
  std::vector<int> grid_of_medium;
  int grid_medium_of(int m) const {
    return m >= 0 && std::size_t(m) < grid_of_medium.size() ? grid_of_medium[std::size_t(m)] : -1;
  }
  // Subsurface materials (Material::subsurface indexes both): the parameters as parsed,
  // and the methods made from them by preparation.
  std::vector<SubsurfaceParams> subsurface_params;
  std::vector<std::unique_ptr<SubsurfaceMaterial>> subsurface;
  // The `volumetric` references: a medium filled in by preparation from the parameters
  // (with textured parameters, the textures' mean; a path takes the medium of the point
  // where it entered: volumetric_texture.h).
  struct VolumetricMedium {
    SubsurfaceParams params;
    int medium = -1;
    AlbedoInversions inversions;  // the dielectric tables (empty: coefficients or the fit)
    BoundaryRoughness roughness;  // the dielectric's alphas per point (a textured roughness: the inversion's)
  };
  std::vector<VolumetricMedium> volumetric_media;
  // Per medium: its entry in volumetric_media when its parameters (or the roughness its
  // inversion depends on) are textured, else -1
  // (filled by preparation; empty when no volumetric material is textured).
  std::vector<int> textured_volumetric_of_medium;
  // The subsurface object of each shape (subsurface/object_tracer.h): walks and probes
  // stay within the shapes of the object they entered.
  std::vector<int> object_of_shape;
  std::vector<Light> lights;
  LightSelection light_selection;  // which light next-event estimation samples
  std::vector<int> infinite_lights;
  bool has_interfaces = false;        // any shape with an `interface` material
  std::vector<char> interface_shape;  // per shape: 1 when its material is `interface` (shadow rays pass)
  // Per medium: can a shadow ray from inside it reach a light? Not when the medium only
  // fills shapes with opaque or refractive boundaries and holds no light (e.g. skin
  // under a dielectric): next-event estimation there would only find the boundary.
  std::vector<char> medium_sees_lights;
  int camera_medium = -1;
  Camera camera;
  FilmDesc film;
  RenderSettingsDesc settings;
  EstimatorSwitches switches;  // all on but in tests
  bool prepared = false;       // scene_preparation.h has run
};

}  // namespace dermis
