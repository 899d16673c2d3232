// --confine (scene/file_access.h): every kind of file a scene names is refused outside the
// scene's directory and the allowed ones, at the file name, after `..` and symbolic links;
// inside, and in the default (pbrt-v4) mode, the same scenes parse.
#include <gtest/gtest.h>

#include <filesystem>

#include "dermis/scene/parser.h"
#include "dermis/scene/scene_test_util.h"

namespace dermis {
namespace {

namespace fs = std::filesystem;

// A mesh, an image, a spectrum file and an included scene, outside `scene/`.
struct Layout {
  test::TempDir dir;
  std::string scene_dir;
  Layout() {
    dir.write("assets/tri.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
              "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    dir.write("assets/tex.png", "the parser does not read images");
    dir.write("assets/flat.spd", "400 1\n700 1\n");
    dir.write("assets/part.pbrt", "Shape \"sphere\"\n");
    dir.write("scene/keep", "");
    scene_dir = dir.path() + "/scene";
    fs::create_directory_symlink(dir.path() + "/assets", scene_dir + "/link");
  }
};

// Each line names one file through `prefix` ("../assets/", an absolute path, "link/").
std::string world_naming(const std::string& prefix) {
  return "WorldBegin\n"
         "Shape \"plymesh\" \"string filename\" \"" +
         prefix +
         "tri.ply\"\n"
         "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"" +
         prefix +
         "tex.png\"\n"
         "Material \"diffuse\" \"spectrum reflectance\" \"" +
         prefix +
         "flat.spd\"\n"
         "Include \"" +
         prefix + "part.pbrt\"\n";
}

// The line of the first refused file, with the others commented out in turn.
TEST(FileAccess, ConfinedRefusesEveryKindOfFileOutsideAtItsName) {
  Layout l;
  const FileAccessOptions confined{true, {}};
  for (const std::string& prefix : {std::string("../assets/"), l.dir.path() + "/assets/", std::string("link/")}) {
    const std::string world = world_naming(prefix);
    // Parsed whole in the default mode.
    EXPECT_NO_THROW(parse_scene_string(world, "s.pbrt", l.scene_dir)) << prefix;
    // Confined: each of the four lines is refused, at its file name.
    std::vector<std::string> lines;
    for (std::size_t at = 0, next; at < world.size(); at = next + 1) {
      next = world.find('\n', at);
      lines.push_back(world.substr(at, next - at + 1));
    }
    const char* kinds[] = {"mesh '", "image '", "spectrum file '", "Include '"};
    for (int refused = 1; refused <= 4; ++refused) {
      std::string text = lines[0];
      for (int i = 1; i <= 4; ++i) text += (i == refused ? "" : "# ") + lines[std::size_t(i)];
      try {
        parse_scene_string(text, "s.pbrt", l.scene_dir, confined);
        ADD_FAILURE() << "accepted: " << text;
      } catch (const SceneError& e) {
        EXPECT_EQ(e.loc().line, refused + 1) << e.what();
        EXPECT_EQ(e.loc().column, int(lines[std::size_t(refused)].find("\"" + prefix)) + 1) << e.what();
        // The name as written (cut to 64 bytes in the message: the absolute one is long).
        EXPECT_NE(std::string(e.what()).find(std::string(kinds[refused - 1]) + prefix.substr(0, 40)), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("is outside the directories this scene may read"), std::string::npos);
      }
    }
    // Allowing the assets' directory (by its real path) lets the same scene through.
    EXPECT_NO_THROW(parse_scene_string(world, "s.pbrt", l.scene_dir, {true, {l.dir.path() + "/assets"}})) << prefix;
  }
}

TEST(FileAccess, ConfinedAcceptsFilesInsideTheSceneDirectory) {
  Layout l;
  l.dir.write("scene/sub/tri.ply", "");
  fs::copy_file(l.dir.path() + "/assets/tri.ply", l.scene_dir + "/tri.ply");
  // "sub/../tri.ply" stays inside.
  EXPECT_NO_THROW(parse_scene_string("WorldBegin\nShape \"plymesh\" \"string filename\" \"sub/../tri.ply\"\n", "s.pbrt",
                                     l.scene_dir, {true, {}}));
}

// The scene's output name is written relative to the working directory: confined, it must
// stay there (or in an allowed directory).
TEST(FileAccess, ConfinedRefusesAFilmFilenameOutside) {
  Layout l;
  const FileAccessOptions confined{true, {}};
  EXPECT_NO_THROW(parse_scene_string("Film \"rgb\" \"string filename\" \"out.exr\"\nWorldBegin\n", "s.pbrt",
                                     l.scene_dir, confined));
  try {
    parse_scene_string("Film \"rgb\" \"string filename\" \"/tmp/../etc/x.png\"\nWorldBegin\n", "s.pbrt", l.scene_dir,
                       confined);
    ADD_FAILURE() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().column, 30) << e.what();
    EXPECT_NE(std::string(e.what()).find("outside the directories this scene may write"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace dermis
