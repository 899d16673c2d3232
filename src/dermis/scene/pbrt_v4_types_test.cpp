// Typed directives: a type name pbrt-v4 does not know is an error at the name (with a
// suggestion for a near miss); every name pbrt-v4 knows is accepted by the parser, rendered
// or warned about (docs/scene-format.md), never refused as unknown.
#include "dermis/scene/pbrt_v4_types.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "dermis/scene/parser.h"

namespace dermis {
namespace {

// A scene using `type` for `kind`, with the least the directive needs around it.
std::string scene_with(TypedDirective kind, const std::string& type) {
  const std::string q = "\"" + type + "\"";
  switch (kind) {
    case TypedDirective::Camera:
      return "Camera " + q + "\nWorldBegin\n";
    case TypedDirective::Film:
      return "Film " + q + "\nWorldBegin\n";
    case TypedDirective::PixelFilter:
      return "PixelFilter " + q + "\nWorldBegin\n";
    case TypedDirective::Material:
      return "WorldBegin\nMaterial " + q + "\n";
    case TypedDirective::LightSource:
      return "WorldBegin\nLightSource " + q + "\n";
    case TypedDirective::AreaLightSource:
      return "WorldBegin\nAreaLightSource " + q + "\n";
    case TypedDirective::Shape:
      return "WorldBegin\nShape " + q + "\n";
    case TypedDirective::Texture:
      return "WorldBegin\nTexture \"t\" \"float\" " + q + "\n";
    case TypedDirective::Medium:
      return "MakeNamedMedium \"m\" \"string type\" " + q + "\nWorldBegin\n";
  }
  return {};
}

constexpr TypedDirective kKinds[] = {
    TypedDirective::Material, TypedDirective::LightSource, TypedDirective::AreaLightSource,
    TypedDirective::Camera,   TypedDirective::Shape,       TypedDirective::Texture,
    TypedDirective::Medium,   TypedDirective::Film,        TypedDirective::PixelFilter};

// Each name pbrt-v4 knows gets past the type check: the scene parses, or fails for another
// reason (a missing filename, a spectrum-only texture declared float), never "unknown ... type".
TEST(PbrtV4Types, EveryNamePbrtV4KnowsIsAccepted) {
  int names = 0;
  for (TypedDirective kind : kKinds)
    for (const char* type : known_types(kind)) {
      ++names;
      try {
        parse_scene_string(scene_with(kind, type), "test.pbrt", ".");
      } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()).find(" type '"), std::string::npos) << type << ": " << e.what();
      }
    }
  EXPECT_GE(names, 50);
}

// The same directives with a name pbrt-v4 does not know: refused at the type name.
TEST(PbrtV4Types, AnUnknownNameIsAnErrorAtTheName) {
  for (TypedDirective kind : kKinds) {
    const std::string text = scene_with(kind, "nosuchtype");
    try {
      parse_scene_string(text, "test.pbrt", ".");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(" type 'nosuchtype' (pbrt-v4 has "), std::string::npos) << e.what();
      // The column is that of the quoted name.
      const std::size_t at = text.find("\"nosuchtype\"");
      const std::size_t newline = text.rfind('\n', at);
      const std::size_t line_start = newline == std::string::npos ? 0 : newline + 1;
      EXPECT_EQ(e.loc().column, int(at - line_start) + 1) << e.what();
    }
  }
}

// Known to pbrt-v4, not rendered by Dermis: one warning each, and the scene renders.
TEST(PbrtV4Types, KnownButUnsupportedTypesAreWarnings) {
  const SceneDesc s = parse_scene_string(
      "Camera \"realistic\"\nWorldBegin\nTexture \"t\" \"float\" \"ptex\" \"string filename\" \"x.ptx\"\n"
      "LightSource \"projection\"\nMaterial \"measured\"\n",
      "test.pbrt", ".");
  auto warned = [&](const std::string& what) {
    for (const std::string& w : s.diagnostics.warnings)
      if (w.find(what) != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(warned("test.pbrt:1:1: warning: Camera \"realistic\" is not supported"));
  // (orthographic, once the camera here, is rendered now: CameraOrthographic.*)
  // (curve, once the shape here, is rendered now: ParserCurve.*)
  EXPECT_TRUE(warned("test.pbrt:3:1: warning: ptex textures are not supported"));
  EXPECT_TRUE(warned("test.pbrt:4:1: warning: LightSource \"projection\" is not supported"));
  EXPECT_TRUE(warned("test.pbrt:5:1: warning: unsupported material \"measured\""));
}

// A 10 MB name is quoted in part and not compared for a near miss.
TEST(PbrtV4Types, AHugeNameIsQuotedInPart) {
  try {
    parse_scene_string("WorldBegin\nShape \"" + std::string(10 << 20, 's') + "\"\n", "test.pbrt", ".");
    ADD_FAILURE() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_LT(std::string(e.what()).size(), 400u) << std::string(e.what()).substr(0, 400);
    EXPECT_NE(std::string(e.what()).find("bytes in all"), std::string::npos);
  }
}

}  // namespace
}  // namespace dermis
