// The scene as the pbrt-v4 parser hands it to the renderer: typed, validated,
// with every parameter resolved to its default and every name to an index.
// Nothing here depends on Embree or the integrator.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dermis/core/float_array.h"
#include "dermis/core/rgb.h"
#include "dermis/core/sampler.h"
#include "dermis/core/transform.h"
#include "dermis/core/vec.h"
#include "dermis/scene/curve_segments.h"
#include "dermis/scene/diagnostics.h"
#include "dermis/scene/subsurface_params.h"

namespace dermis {

// One parameter as written: `"type name" [values]`. Kept on descriptions whose
// parameters are interpreted later (e.g. the subsurface material's methods).
class ParamList;

// Numbers past this count, of any type but integer, are held as floats (Param::long_numbers):
// a grid medium's millions of values exist once, at 4 bytes each, as pbrt-v4 stores them
// (Float); shorter lists (colours, spectra, small meshes) keep their exact doubles, 32 KiB at most.
inline constexpr std::size_t kLongNumberList = 4096;

struct Param {
  std::string type;  // integer, float, point2, vector2, point3, vector3, normal, normal3,
                     // rgb, spectrum, blackbody, bool, string, texture, point, vector, color
  std::string name;
  // The numbers: in `numbers`, or, for a list of non-integers longer than kLongNumberList,
  // in `long_numbers` as floats (`numbers` then empty), shared by every copy of the parameter.
  std::vector<double> numbers;
  std::shared_ptr<FloatArray> long_numbers;
  std::vector<std::string> strings;
  std::vector<bool> bools;
  SourceLoc loc;

  std::size_t number_count() const { return long_numbers ? long_numbers->size() : numbers.size(); }
  double number(std::size_t i) const { return long_numbers ? double((*long_numbers)[i]) : numbers[i]; }
  // Every number as a double: a copy (converted from floats for a long list).
  std::vector<double> numbers_as_doubles() const {
    if (!long_numbers) return numbers;
    return std::vector<double>(long_numbers->begin(), long_numbers->end());
  }
};

struct CameraDesc {
  Transform camera_to_world;  // pbrt's camera space: +z forward, +y up
  bool orthographic = false;  // pbrt-v4's "orthographic" camera; else "perspective"
  float fov = 90;             // degrees, across the shorter image axis
  float lens_radius = 0;
  float focal_distance = 1e6f;
  std::optional<std::array<float, 4>> screen_window;  // xmin xmax ymin ymax, if given
  int medium = -1;                                    // index into SceneDesc::media, -1: vacuum
  SourceLoc loc;
};

struct FilterDesc {
  enum class Type { Box, Gaussian };
  Type type = Type::Gaussian;  // pbrt-v4's default
  Vec2 radius{1.5f, 1.5f};     // box default 0.5
  float sigma = 0.5f;          // gaussian
};

struct FilmDesc {
  int xres = 1280, yres = 720;
  std::string filename = "pbrt.exr";      // as written; resolved relative to the working directory
  std::array<float, 4> crop{0, 1, 0, 1};  // cropwindow x0 x1 y0 y1 (fractions of the image)
  float exposure_scale = 1;               // iso / 100 (pbrt-v4's default sensor)
  FilterDesc filter;
};

struct RenderSettingsDesc {
  int spp = 16;
  int max_depth = 5;
  // Exits sampled at the camera's first subsurface entry, their direct light averaged
  // (Dermis' "integer subsurfacesamples" of the Integrator; render/integrator.cpp).
  int subsurface_samples = 2;
  // The render's pilot chooses each random-walk material's sampling strategy
  // (render/subsurface_pilot.h; Dermis' "bool subsurfacepilot" of the Integrator).
  bool subsurface_pilot = true;
  // Throughput above which a path is split at a subsurface exit (copies of its way on) and
  // at a later subsurface entry (exits averaged); 0: never (Dermis' "float splitthreshold"
  // of the Integrator; render/path_splitting.h).
  float split_threshold = 2;
  std::string integrator = "volpath";
  int seed = 0;                              // pbrt-v4 Sampler "integer seed"
  SamplerKind sampler = SamplerKind::Sobol;  // pbrt-v4 Sampler's name, mapped (docs/scene-format.md)
  // Adaptive sampling (render/adaptive_sampling.h): Dermis' Sampler "float noisethreshold"
  // (0: off) and "integer minpixelsamples" (0: the default).
  double noise_threshold = 0;
  int min_spp = 0;
  // Spectral transport (render/renderer.h RenderOptions::spectral): Dermis' Option "bool
  // spectral" (pbrt-v4 renders spectrally always; --spectral sets it too).
  bool spectral = false;
};

struct TextureDesc {
  enum class Type {
    Constant,
    ImageMap,
    Scale,
    Checkerboard,
    Mix,
    DirectionMix,
    Bilerp,
    Dots,
    FBm,
    Wrinkled,
    Windy,
    Marble
  };
  std::string name;
  Type type = Type::Constant;
  bool is_float = false;  // declared "float" (value holds the float in all channels), else "spectrum"
  RGB value{1, 1, 1};     // constant: "value"; scale: "tex" as a value; checkerboard: "tex1"
  std::string filename;   // imagemap: absolute path
  float scale = 1;        // imagemap: "scale"; scale: constant factor
  bool invert = false;
  std::string encoding = "sRGB";  // "sRGB", "linear" or "gamma g" for 8-bit images
  std::string wrap = "repeat";    // repeat, black, clamp
  // pbrt-v4's mapping: "uv" (uscale, vscale, udelta, vdelta), "spherical", "cylindrical",
  // "planar" (v1, v2, udelta, vdelta), or "3d" for the classes that map the point in 3D
  // (fbm, wrinkled, windy, marble). All but uv use texture_from_world: the inverse of the
  // CTM at the Texture directive.
  std::string mapping = "uv";
  float uscale = 1, vscale = 1, udelta = 0, vdelta = 0;
  Vec3 v1{1, 0, 0}, v2{0, 1, 0};
  Transform texture_from_world;
  int octaves = 8;           // fbm, wrinkled, marble
  float roughness = 0.5f;    // fbm, wrinkled, marble (pbrt-v4's omega)
  float variation = 0.2f;    // marble; marble's frequency is `scale` (1)
  Vec3 dir{0, 1, 0};         // directionmix: unit, world space
  int base = -1;             // scale: texture being scaled (index), or -1 (then `value` is scaled)
  RGB value2{0, 0, 0};       // checkerboard, mix, directionmix: tex2 (value holds tex1); dots: outside (value: inside)
  int tex1 = -1, tex2 = -1;  // the same as textures (index; dots: inside, outside), or -1 for the values
  float amount = 0.5f;       // mix: the weight of tex2
  int amount_texture = -1;   // mix: a float texture for it, or -1
  std::array<RGB, 4> corners{};  // bilerp: v00, v01, v10, v11
  SourceLoc loc;
};

// An RGB constant or a texture reference (index into SceneDesc::textures).
struct RGBTexture {
  RGB value{0.5f, 0.5f, 0.5f};
  int texture = -1;
  int data = -1;  // the value given as a spectrum (SceneDesc::spectra), for spectral rendering; -1: none
};

struct MaterialDesc {
  enum class Type {
    Diffuse,
    Dielectric,
    Conductor,
    Interface,
    Subsurface,
    CoatedDiffuse,
    CoatedConductor,
    DiffuseTransmission,
    Mix
  };
  Type type = Type::Diffuse;
  std::string name;        // MakeNamedMaterial name, or empty
  RGBTexture reflectance;  // diffuse, coateddiffuse, diffusetransmission; conductor and
                           // coatedconductor when has_reflectance
  float eta = 1.5f;        // dielectric, subsurface, coateddiffuse, coatedconductor's interface.eta
  // A dielectric's eta given as a spectrum (a named glass, a file, samples: SceneDesc::spectra),
  // positive over 360-830 nm; -1: one number (`eta` above, also what RGB rendering reads).
  int eta_data = -1;
  // eta and k as spectra (SceneDesc::spectra), where given as named spectra, files or
  // samples (pbrt-v4's default copper included); -1: RGB.
  int conductor_eta_data = -1, conductor_k_data = -1;
  RGB conductor_eta{0.2f, 0.92f, 1.1f};  // conductor, RGB approximation (default: metal-Cu-eta)
  RGB conductor_k{3.9f, 2.45f, 2.14f};   // conductor, RGB approximation (default: metal-Cu-k)
  bool has_reflectance = false;          // conductor given "reflectance" instead of eta/k
  float roughness = 0;                   // largest of roughness, uroughness, vroughness as written
  // dielectric, conductor, the coated materials' interface: pbrt-v4's Trowbridge-Reitz
  // roughness per tangent axis ("roughness" sets both, "uroughness" / "vroughness"
  // override one each) and "remaproughness" (alpha = sqrt(roughness) when true;
  // core/microfacet.h). coatedconductor: the conductor's in conductor_*roughness.
  float uroughness = 0, vroughness = 0;
  float conductor_uroughness = 0, conductor_vroughness = 0;
  bool remap_roughness = true;
  // Float textures (indices into SceneDesc::textures, -1: the constant above) for each of
  // them, as pbrt-v4 allows: u and v of the dielectric, conductor or coating interface, and
  // of coatedconductor's conductor.
  std::array<int, 2> roughness_texture{-1, -1};
  std::array<int, 2> conductor_roughness_texture{-1, -1};
  // coateddiffuse, coatedconductor: the layer between interface and base
  // (materials/layered_bsdf.h), pbrt-v4's parameters and defaults.
  float thickness = 0.01f;
  RGB albedo{0, 0, 0};
  float g = 0;
  int thickness_texture = -1, albedo_texture = -1, g_texture = -1;  // textured: float, spectrum, float
  int max_depth = 10;
  int n_samples = 1;
  // diffusetransmission: "transmittance" and "scale" (reflectance above, default 0.25).
  RGBTexture transmittance{RGB(0.25f), -1};
  float scale = 1;
  // mix: the two named materials (indices into SceneDesc::materials) and "amount", the
  // probability of the second: a value, or a float texture (index) when >= 0.
  std::array<int, 2> mix_materials{-1, -1};
  float amount = 0.5f;
  int amount_texture = -1;
  SubsurfaceParams subsurface;  // subsurface: every parameter, read once (subsurface_params.h)
  // The material as written, so that it can be re-read with some parameters changed
  // (set_material_parameters in parser.h): its type and every parameter (params.h).
  std::string type_name;
  std::shared_ptr<const ParamList> params;
  SourceLoc loc;
};

struct AreaLightDesc {
  RGB L{1, 1, 1};
  int L_data = -1;  // L as a spectrum (SceneDesc::spectra), where given as one; -1: RGB
  float scale = 1;
  bool two_sided = false;
};

struct TriangleMeshDesc {
  std::vector<Vec3> positions;    // object space
  std::vector<Vec3> normals;      // optional, per vertex
  std::vector<Vec2> uvs;          // optional, per vertex
  std::vector<uint32_t> indices;  // 3 per triangle
};

struct ShapeDesc {
  enum class Type { TriangleMesh, Sphere, Curve };
  Type type = Type::TriangleMesh;
  Transform object_to_world;  // to world for top-level shapes, to the object's space in instances
  TriangleMeshDesc mesh;      // trianglemesh, plymesh, objmesh, bilinearmesh and disk (tessellated)
  float radius = 1;           // sphere (full spheres only)
  CurveSegments curve;        // curve: cubic Bézier segments in object space
  int material = -1;          // index into SceneDesc::materials; -1: the default diffuse
  std::optional<AreaLightDesc> area_light;
  int inside_medium = -1;  // indices into SceneDesc::media, -1: vacuum
  int outside_medium = -1;
  bool has_medium_interface = false;  // false when inside == outside (no transition)
  // pbrt's ReverseOrientation XOR "object_to_world swaps handedness": when true the
  // renderer flips the geometric normal computed as cross(p1 - p0, p2 - p0) in world space
  // (and pbrt's +z disk / outward sphere normal). For instanced shapes the instance
  // transform's handedness is NOT included.
  bool reverse_orientation = false;
  // pbrt-v4 "alpha": 1 opaque, 0 cut away, between: kept with that probability per hit
  // (geometry/alpha_mask.h); or a float texture (index into textures, -1: none).
  float alpha = 1;
  int alpha_texture = -1;
  SourceLoc loc;
};

struct ObjectDesc {
  std::string name;
  std::vector<ShapeDesc> shapes;  // object_to_world here maps to the object's own space
  SourceLoc loc;
};

struct InstanceDesc {
  int object = -1;  // index into SceneDesc::objects
  Transform object_to_world;
  SourceLoc loc;
};

struct LightDesc {
  enum class Type { Point, Spot, Distant, Infinite };
  Type type = Type::Point;
  Transform light_to_world;
  RGB spectrum{1, 1, 1};   // I for point and spot, L for distant and infinite
  int spectrum_data = -1;  // the same as a spectrum (SceneDesc::spectra), where given as one; -1: RGB
  float scale = 1;
  Vec3 from{0, 0, 0};      // point, spot, distant (light space)
  Vec3 to{0, 0, 1};        // spot, distant (light space)
  float cone_angle = 30;   // spot, degrees
  float cone_delta = 5;    // spot, degrees
  std::string filename;    // infinite: absolute path of the image
  bool latlong = false;    // infinite image: equirectangular ("string mapping" "latlong"), else equal-area
  float illuminance = -1;  // infinite, distant: pbrt-v4's "illuminance" (normalises the light), -1: unset
  // infinite: pbrt-v4's "portal", a rectangle p0 p1 p2 p3 (light space): light arrives only from
  // directions w with w . normalize((p3 - p0) x (p1 - p0)) > 0. Empty: no portal.
  std::vector<Vec3> portal;
  int medium = -1;  // medium the light sits in
  SourceLoc loc;
};

struct MediumDesc {
  std::string name;
  std::string type = "homogeneous";
  RGB sigma_a{1, 1, 1};  // per scene unit, before scale (pbrt-v4 defaults)
  RGB sigma_s{1, 1, 1};
  // The same given as spectra (SceneDesc::spectra, before scale), for spectral rendering; -1: none.
  int sigma_a_data = -1, sigma_s_data = -1;
  float scale = 1;
  float g = 0;
  RGB Le{0, 0, 0};     // emission's colour (luminance 1 where given as a spectrum), before Lescale
  std::string preset;  // "name" parameter if used (Jensen et al. 2001 table)
  // The grid media (type "uniformgrid", "rgbgrid", "cloud"; materials/grid_medium.h), as
  // pbrt-v4 reads them: sigma_a and sigma_s above are per unit density (uniformgrid, cloud).
  Transform medium_to_world;      // the transformation current where the medium was made
  Vec3 p0{0, 0, 0}, p1{1, 1, 1};  // the box, in the medium's space
  int nx = 1, ny = 1, nz = 1;
  // The grids: nx * ny * nz values (rgbgrid's colours: 3 floats each), x fastest; null: not
  // given. Shared with the parameter they were read from and the renderer's grid: one copy.
  std::shared_ptr<const FloatArray> density;                     // uniformgrid
  std::shared_ptr<const FloatArray> sigma_a_grid, sigma_s_grid;  // rgbgrid (either may be null: 1)
  float cloud_density = 1, wispiness = 1, frequency = 5;         // cloud
  // Emission: homogeneous: Le above (luminance 1 where a spectrum, whose samples are
  // SceneDesc::spectra[Le_data]) times Lescale; uniformgrid: Le times the grid le_scale_grid
  // (null: none given); rgbgrid: the colours Le_grid times Lescale.
  int Le_data = -1;
  std::shared_ptr<const FloatArray> le_scale_grid;
  std::shared_ptr<const FloatArray> temperature;        // uniformgrid (null: none), emitting as a blackbody
  float temperature_offset = 0, temperature_scale = 1;  // uniformgrid, nanovdb
  // nanovdb: the .nvdb file (its float grids grid_name, the density, and temperature_name,
  // optional), read when the scene is assembled; errors point at the file name's value.
  std::string filename;
  SourceLoc filename_loc;
  std::string grid_name = "density", temperature_name = "temperature";
  std::shared_ptr<const FloatArray> Le_grid;  // rgbgrid: 3 floats per cell (null: none)
  float Lescale = 1;
  SourceLoc loc;
};

struct SceneDesc {
  // Spectra given as data (named spectra, files, samples, blackbodies) at every nanometre of
  // 360-830 nm (scene/spectra.h spectrum_param_samples), for spectral rendering; the RGB
  // stand-ins beside them are what RGB rendering reads.
  std::vector<std::vector<float>> spectra;
  CameraDesc camera;
  FilmDesc film;
  RenderSettingsDesc settings;
  std::vector<TextureDesc> textures;
  std::vector<MaterialDesc> materials;
  std::vector<MediumDesc> media;
  std::vector<ShapeDesc> shapes;    // top-level shapes
  std::vector<ObjectDesc> objects;  // ObjectBegin/End definitions
  std::vector<InstanceDesc> instances;
  std::vector<LightDesc> lights;  // non-area lights
  Diagnostics diagnostics;        // warnings collected while parsing
  std::string base_directory;     // directory of the main scene file
};

}  // namespace dermis
