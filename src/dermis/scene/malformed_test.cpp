// Malformed scenes: each must throw SceneError at the exact line and column of the
// offending token, with a message a user can act on -- and never crash.
#include <gtest/gtest.h>

#include "dermis/scene/parser.h"
#include "dermis/scene/scene_test_util.h"

namespace dermis {
namespace {

struct Case {
  const char* text;  // with '@' just before the offending token
  const char* message;
};

// Removes the '@' marker and returns the 1-based line and column where it was.
std::string strip_marker(const std::string& marked, int& line, int& column) {
  size_t at = marked.find('@');
  EXPECT_NE(at, std::string::npos) << marked;
  line = 1;
  size_t line_start = 0;
  for (size_t i = 0; i < at; ++i)
    if (marked[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  column = int(at - line_start) + 1;
  return marked.substr(0, at) + marked.substr(at + 1);
}

void expect_scene_error(const std::string& text, int line, int column, const std::string& message,
                        const std::string& dir = ".") {
  try {
    parse_scene_string(text, "bad.pbrt", dir);
    ADD_FAILURE() << "no SceneError for:\n" << text;
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().line, line) << e.what() << "\nfor:\n" << text;
    EXPECT_EQ(e.loc().column, column) << e.what() << "\nfor:\n" << text;
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what() << "\nwanted: " << message;
    EXPECT_NE(std::string(e.what()).find(": error: "), std::string::npos) << e.what();
  }
}

// '@' marks the offending token (it is removed before parsing); the expected line and
// column are where it stood.
const Case kCases[] = {
    // Negative or overflowing light: negative or infinite pixels.
    {"WorldBegin\nLightSource \"point\" \"rgb I\" @[1 -1 1]\n", "\"I\" must be finite and >= 0"},
    {"WorldBegin\nAreaLightSource \"diffuse\" \"rgb L\" [@1e39 1 1]\nShape \"sphere\"\n",
     "beyond the range of 32-bit floats"},
    {"WorldBegin\nLightSource \"infinite\" \"float scale\" @-2\n", "\"scale\" must be finite and >= 0"},
    // Each factor in range, the product not: 1e20 x 1e20 is infinite in float.
    {"WorldBegin\nLightSource \"point\" \"rgb I\" [1e20 1 1] \"float scale\" @1e20\n",
     "a light's \"scale\" 1e+20 times its \"I\" 1e+20 is 1e+40, beyond the range of 32-bit floats"},
    {"WorldBegin\nAreaLightSource \"diffuse\" \"float scale\" @1e30 \"rgb L\" [1 1e9 1]\nShape \"sphere\"\n",
     "times its \"L\" 1e+09"},
    {"WorldBegin\nLightSource \"distant\" \"rgb L\" [3e38 3e38 3e38] \"float scale\" @2\n", "beyond the range"},
    // As in pbrt-v4, an unknown directive is an error (what follows it would be misread);
    // a near miss gets a suggestion, anything else a hint (a file that is not a scene).
    {"WorldBegin\n  @Shpae \"sphere\"\n", "unknown directive 'Shpae' (did you mean 'Shape'?)"},
    {"WorldBegin\n@Frobnicate \"x\" [1 2]\n", "unknown directive 'Frobnicate' (is this a pbrt-v4 scene file?)"},
    {"WorldBegin\n@root:x:0:0:root:/root:/bin/bash\n", "unknown directive 'root:x:0:0:root:/root:/bin/bash'"},
    {"Sampler @\"sobolish\" \"integer pixelsamples\" 4\nWorldBegin\n", "unknown Sampler \"sobolish\""},
    // As in pbrt-v4, a type name it does not know is an error (a typo would otherwise render
    // something else); a type pbrt-v4 knows but Dermis does not render is a warning.
    {"WorldBegin\nMaterial @\"difuse\"\n", "unknown Material type 'difuse' (did you mean 'diffuse'?)"},
    {"WorldBegin\nMaterial @\"plastic\"\n", "unknown Material type 'plastic' (a pbrt-v3 material"},
    {"WorldBegin\nMakeNamedMaterial \"m\" \"string type\" @\"coateddifuse\"\n", "(did you mean 'coateddiffuse'?)"},
    {"WorldBegin\nLightSource @\"laser\" \"rgb I\" [1 1 1]\n",
     "unknown LightSource type 'laser' (pbrt-v4 has point, spot"},
    {"WorldBegin\nAreaLightSource @\"difuse\"\n", "unknown AreaLightSource type 'difuse' (did you mean 'diffuse'?)"},
    {"Camera @\"fisheye\"\nWorldBegin\n", "unknown Camera type 'fisheye' (pbrt-v4 has perspective, orthographic"},
    {"Camera @\"perspectiv\"\nWorldBegin\n", "(did you mean 'perspective'?)"},
    {"WorldBegin\nShape @\"sphear\"\n", "unknown Shape type 'sphear' (did you mean 'sphere'?)"},
    {"WorldBegin\nTexture \"t\" \"spectrum\" @\"imagemapp\"\n",
     "unknown Texture type 'imagemapp' (did you mean 'imagemap'?)"},
    {"WorldBegin\nMakeNamedMedium \"f\" \"string type\" @\"plasma\"\n", "unknown MakeNamedMedium type 'plasma'"},
    {"Film @\"film\"\nWorldBegin\n", "unknown Film type 'film'"},
    {"PixelFilter @\"gauss\"\nWorldBegin\n", "unknown PixelFilter type 'gauss'"},
    {"WorldBegin\nShape \"sphere\" \"float radius\" @\"two\"\n", "expects numbers, found string 'two'"},
    {"WorldBegin\nShape \"sphere\" @\"string radius\" \"2\"\n", "has type 'string', expected float"},
    {"WorldBegin\nShape \"trianglemesh\" \"point3 P\" @[0 0 0 1 0 0 0 1]\n", "multiple of 3"},
    {"WorldBegin\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 ]\n  \"integer indices\" [0 1 @3]\n",
     "index 3 is out of range"},
    {"WorldBegin\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n  \"integer indices\" @[0 1 2 3]\n",
     "multiple of 3"},
    {"WorldBegin\n@Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n", "needs \"integer indices\""},
    {"WorldBegin\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 @-nan 0 0 1 0]\n", "not finite"},
    {"WorldBegin\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 @2.5]\n",
     "expects integers"},
    {"WorldBegin\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"normal N\" @[0 0 1]\n",
     "\"N\" has 1 normals but \"P\" has 3"},
    {"WorldBegin\nShape \"sphere\" \"float radius\" [1\n@Shape \"sphere\"\n", "missing ']'"},
    {"WorldBegin\nShape \"sphere\" \"float radius\" @[1", "missing ']'"},
    {"WorldBegin\nShape \"sphere\" \"float radius\" @[ ]\n", "has no values"},
    {"WorldBegin\nShape \"sphere\" \"float radius\" @[1 2]\n", "exactly one value"},
    {"WorldBegin\nShape \"sphere\" @\"floot radius\" 1\n", "unknown parameter type 'floot'"},
    {"WorldBegin\nShape \"sphere\" @\"radius\" 1\n", "\"type name\""},
    {"WorldBegin\nNamedMaterial @\"gold\"\n", "unknown named material \"gold\""},
    {"WorldBegin\nMaterial \"diffuse\" \"texture reflectance\" @\"wood\"\n", "unknown spectrum texture \"wood\""},
    // Resolved at use (pbrt-v4): the error is at the name once a shape needs it.
    {"MediumInterface @\"smoke\"\nWorldBegin\nShape \"sphere\"\n", "unknown medium \"smoke\""},
    {"MakeNamedMedium \"a\" \"string type\" \"homogeneous\"\nMediumInterface \"a\" @\"b\"\nWorldBegin\nShape "
     "\"sphere\"\n",
     "unknown medium \"b\""},
    {"WorldBegin\nObjectInstance @\"tree\"\n", "unknown object \"tree\""},
    {"WorldBegin\n@AttributeEnd\n", "AttributeEnd without a matching AttributeBegin"},
    {"WorldBegin\nAttributeBegin\n@TransformEnd\n", "closes the AttributeBegin"},
    {"WorldBegin\nObjectBegin \"a\"\n  @ObjectBegin \"b\"\n", "cannot be nested"},
    {"WorldBegin\n@ObjectEnd\n", "ObjectEnd without a matching ObjectBegin"},
    {"WorldBegin\n@ObjectBegin \"a\"\nShape \"sphere\"\n", "has no matching ObjectEnd"},
    {"Translate 1 @x 3\n", "Translate expects 3 numbers, found identifier 'x'"},
    {"Translate 1 2@\n", "Translate expects 3 numbers, found the end of the file"},
    {"Film \"rgb\" \"integer xresolution\" @-5\n", "xresolution must be positive"},
    {"Film \"rgb\" \"integer yresolution\" @0\n", "yresolution must be positive"},
    {"Film \"rgb\" \"integer xresolution\" @100000000 \"integer yresolution\" 10\n",
     "a film of 100000000x10 pixels is too large"},
    {"Film \"rgb\" \"integer yresolution\" 65536 \"integer xresolution\" @65536\n", "too large"},
    {"Scale 1 @0 1\n", "Scale by zero"},
    {"  @LookAt 0 0 0  0 0 0  0 1 0\n", "degenerate LookAt"},
    {"@LookAt 0 0 0  0 1 0  0 1 0\n", "parallel"},
    {"@Rotate 30 0 0 0\n", "zero length"},
    {"Transform @[1 0 0 0 0 1 0 0 0 0 0 0 0 0 0 1]\n", "singular"},
    {"Transform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n@WorldBegin\n", "missing ']'"},
    {"WorldBegin\nMakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"string preset\" @\"Jelly\"\n",
     "unknown medium preset \"Jelly\" (valid: Apple, Chicken1"},
    {"MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"float g\" @1.5\n", "g must be in (-1, 1)"},
    {"@MakeNamedMedium \"m\"\n", "needs \"string type\""},
    {"WorldBegin\n@Shape \"plymesh\" \"string filename\" \"no/such/mesh.ply\"\n", "could not read mesh file '"},
    {"WorldBegin\n@Shape \"objmesh\" \"string filename\" \"missing.obj\"\n", "missing.obj': No such file"},
    {"WorldBegin\nInclude @\"nowhere.pbrt\"\n", "could not read included file"},
    {"WorldBegin\nShape \"sphere\"\n@WorldBegin\n", "WorldBegin given twice"},
    {"WorldBegin\n@Camera \"perspective\"\n", "only allowed before WorldBegin"},
    {"@Shape \"sphere\"\n", "only allowed after WorldBegin"},
    {"Camera \"perspective\" \"float fov\" @180\n", "fov must be in (0, 180)"},
    {"WorldBegin\nLightSource \"point\" \"rgb I\" @[1 1]\n", "expects 3 values, got 2"},
    {"WorldBegin\nLightSource \"point\" \"spectrum I\" @\"metal-Unobtainium\"\n", "unknown named spectrum"},
    {"WorldBegin\nLightSource \"point\" \"spectrum I\" [400 1 @380 2]\n", "wavelengths must increase"},
    {"WorldBegin\nLightSource \"point\" \"blackbody I\" @-10\n", "temperature must be positive"},
    {"WorldBegin\nMakeNamedMaterial \"m\" \"string type\" \"diffuse\"\nMakeNamedMaterial @\"m\" \"string type\" "
     "\"diffuse\"\n",
     "defined twice"},
    {"WorldBegin\nTexture \"t\" @\"color3\" \"constant\"\n", "\"spectrum\" or \"float\""},
    {"WorldBegin\nTexture \"t\" \"spectrum\" \"imagemap\" \"string filename\" @\"absent.png\"\n", "could not read"},
    {"WorldBegin\nShape \"sphere\" \"bool x\" @1\n", "expects true or false"},
    {"WorldBegin\n@42\n", "expected a directive, found number '42'"},
    {"WorldBegin\nShape \"disk\" \"float innerradius\" @2\n", "innerradius must be in [0, radius)"},
    {"WorldBegin\nShape \"sphere\" \"float radius\" 1 @\"float radius\" 2\n", "given twice"},
};

TEST(MalformedScenes, ThrowAtTheOffendingToken) {
  for (const Case& c : kCases) {
    int line = 0, column = 0;
    std::string text = strip_marker(c.text, line, column);
    expect_scene_error(text, line, column, c.message);
  }
  EXPECT_GE(std::size(kCases), 25u);
}

TEST(MalformedScenes, IncludeCycle) {
  test::TempDir dir;
  dir.write("a.pbrt", "Include \"b.pbrt\"\n");
  dir.write("b.pbrt", "\n  Include \"a.pbrt\"\n");
  std::string main = dir.write("main.pbrt", "WorldBegin\nInclude \"a.pbrt\"\n");
  try {
    parse_scene_file(main);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().line, 2);
    EXPECT_EQ(e.loc().column, 11);
    EXPECT_NE(e.loc().file.find("b.pbrt"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("Include cycle"), std::string::npos) << e.what();
  }
}

TEST(MalformedScenes, MissingSceneFile) {
  try {
    parse_scene_file("/nonexistent/dir/scene.pbrt");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("could not read scene file '/nonexistent/dir/scene.pbrt': No such file"),
              std::string::npos)
        << e.what();
  }
}

TEST(MalformedScenes, BrokenPlyFileNamesTheFileAndTheReason) {
  test::TempDir dir;
  dir.write("bad.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  dir.write("short.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n0 0 0\n1 0\n");
  expect_scene_error("WorldBegin\nShape \"plymesh\" \"string filename\" \"bad.ply\"\n", 2, 1,
                     "references vertex 7 but the file has 3 vertices", dir.path());
  expect_scene_error("WorldBegin\nShape \"plymesh\" \"string filename\" \"short.ply\"\n", 2, 1,
                     "3 'vertex' elements of at least 6 bytes each, but only 10 bytes follow the header", dir.path());
}

TEST(MalformedScenes, BrokenGzipFilesNameTheFile) {
  test::TempDir dir;
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const std::string zply = test::gzip(ply), zpbrt = test::gzip("Shape \"sphere\"\n");
  std::string corrupt_ply = zply;
  corrupt_ply[corrupt_ply.size() - 6] ^= 0x55;  // the trailer's CRC-32
  dir.write("cut.ply.gz", zply.substr(0, zply.size() / 2));
  dir.write("bad.ply.gz", corrupt_ply);
  dir.write("cut.pbrt.gz", zpbrt.substr(0, zpbrt.size() - 3));
  const std::string d = dir.path() + "/";
  expect_scene_error("WorldBegin\nShape \"plymesh\" \"string filename\" \"cut.ply.gz\"\n", 2, 1,
                     "could not read mesh file '" + d +
                         "cut.ply.gz': gzip data is corrupt/truncated "
                         "(zlib: unexpected end of file)",
                     dir.path());
  expect_scene_error("WorldBegin\nShape \"plymesh\" \"string filename\" \"bad.ply.gz\"\n", 2, 1,
                     "could not read mesh file '" + d +
                         "bad.ply.gz': gzip data is corrupt/truncated "
                         "(zlib: incorrect data check)",
                     dir.path());
  expect_scene_error("WorldBegin\n  Include \"cut.pbrt.gz\"\n", 2, 11,
                     "could not read included file '" + d +
                         "cut.pbrt.gz': gzip data is corrupt/truncated "
                         "(zlib: unexpected end of file)",
                     dir.path());
  std::string main = dir.write("main.pbrt.gz", zpbrt.substr(0, 12));
  try {
    parse_scene_file(main);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("could not read scene file '" + main +
                                         "': gzip data is corrupt/truncated (zlib: unexpected end of file)"),
              std::string::npos)
        << e.what();
  }
}

TEST(MalformedScenes, NanInPlyFileIsRejected) {
  test::TempDir dir;
  dir.write("nan.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
  expect_scene_error("WorldBegin\n  Shape \"plymesh\" \"string filename\" \"nan.ply\"\n", 2, 3,
                     "nan.ply': vertex 1 has a non-finite coordinate", dir.path());
}

}  // namespace
}  // namespace dermis
