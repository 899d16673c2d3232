#include "dermis/scene/pbrt_v4_types.h"

#include <fmt/format.h>

#include <algorithm>

namespace dermis {

namespace {

// pbrt-v4's factories (src/pbrt/materials.cpp, lights.cpp, cameras.cpp, shapes.cpp,
// textures.cpp, media.cpp, film.cpp, filters.cpp): each ends in ErrorExit for any other name.
constexpr const char* kMaterials[] = {"diffuse",
                                      "coateddiffuse",
                                      "coatedconductor",
                                      "diffusetransmission",
                                      "dielectric",
                                      "thindielectric",
                                      "hair",
                                      "conductor",
                                      "measured",
                                      "subsurface",
                                      "mix",
                                      "interface",
                                      "none",
                                      ""};
constexpr const char* kLights[] = {"point", "spot", "goniometric", "projection", "distant", "infinite"};
constexpr const char* kAreaLights[] = {"diffuse"};
constexpr const char* kCameras[] = {"perspective", "orthographic", "realistic", "spherical"};
// "objmesh" is Dermis' own (an OBJ file through Assimp).
constexpr const char* kShapes[] = {"sphere",       "cylinder", "disk",       "bilinearmesh", "curve",
                                   "trianglemesh", "plymesh",  "loopsubdiv", "objmesh"};
// Float and spectrum textures together (which is which is checked where they are built).
constexpr const char* kTextures[] = {"bilerp", "checkerboard", "constant", "directionmix", "dots",
                                     "fbm",    "imagemap",     "marble",   "mix",          "ptex",
                                     "scale",  "windy",        "wrinkled"};
constexpr const char* kMedia[] = {"homogeneous", "uniformgrid", "rgbgrid", "cloud", "nanovdb"};
constexpr const char* kFilms[] = {"rgb", "gbuffer", "spectral"};
constexpr const char* kFilters[] = {"box", "gaussian", "mitchell", "sinc", "triangle"};

// pbrt-v3's material names, which pbrt-v4 dropped: a scene using them needs converting.
constexpr const char* kPbrtV3Materials[] = {"matte",     "plastic",     "metal",        "mirror",  "glass", "uber",
                                            "substrate", "translucent", "kdsubsurface", "fourier", "disney"};

const char* directive_name(TypedDirective kind) {
  switch (kind) {
    case TypedDirective::Material:
      return "Material";
    case TypedDirective::LightSource:
      return "LightSource";
    case TypedDirective::AreaLightSource:
      return "AreaLightSource";
    case TypedDirective::Camera:
      return "Camera";
    case TypedDirective::Shape:
      return "Shape";
    case TypedDirective::Texture:
      return "Texture";
    case TypedDirective::Medium:
      return "MakeNamedMedium";
    case TypedDirective::Film:
      return "Film";
    case TypedDirective::PixelFilter:
      return "PixelFilter";
  }
  return "?";
}

}  // namespace

std::span<const char* const> known_types(TypedDirective kind) {
  switch (kind) {
    case TypedDirective::Material:
      return kMaterials;
    case TypedDirective::LightSource:
      return kLights;
    case TypedDirective::AreaLightSource:
      return kAreaLights;
    case TypedDirective::Camera:
      return kCameras;
    case TypedDirective::Shape:
      return kShapes;
    case TypedDirective::Texture:
      return kTextures;
    case TypedDirective::Medium:
      return kMedia;
    case TypedDirective::Film:
      return kFilms;
    case TypedDirective::PixelFilter:
      return kFilters;
  }
  return {};
}

void require_known_type(TypedDirective kind, const std::string& type, const SourceLoc& at) {
  const std::span<const char* const> known = known_types(kind);
  if (std::find(known.begin(), known.end(), type) != known.end()) return;
  std::string hint;
  // The nearest name within two edits; long input is no near miss (and is not compared).
  std::size_t best = 3;
  if (type.size() <= 40)
    for (const char* name : known)
      if (*name)
        if (const std::size_t d = edit_distance(type, name); d < best) {
          best = d;
          hint = fmt::format(" (did you mean '{}'?)", name);
        }
  if (kind == TypedDirective::Material &&
      std::find(std::begin(kPbrtV3Materials), std::end(kPbrtV3Materials), type) != std::end(kPbrtV3Materials))
    hint = " (a pbrt-v3 material: `pbrt --upgrade` converts a pbrt-v3 scene to pbrt-v4)";
  if (hint.empty()) {
    std::string names;
    for (const char* name : known)
      if (*name) names += (names.empty() ? "" : ", ") + std::string(name);
    hint = fmt::format(" (pbrt-v4 has {})", names);
  }
  throw SceneError(at, fmt::format("unknown {} type '{}'{}", directive_name(kind), excerpt(type), hint));
}

}  // namespace dermis
