// pbrt-v4's own scenes, as written (with stand-ins for assets not redistributed here:
// scenes/pbrt-v4/*/make_standins.py), parse with only the warnings Dermis owes and render.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "dermis/render/renderer.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"

namespace dermis {
namespace {

// head: textured subsurface reflectance (warm on one half of the albedo map, cool on
// the other) on the default random walk, under a grey sky: both hues reach the picture.
TEST(PbrtV4Scenes, HeadRendersWithItsTexturedReflectance) {
  SceneDesc d = parse_scene_file(std::string(DERMIS_SOURCE_DIR) + "/scenes/pbrt-v4/head/head.pbrt");
  for (const std::string& w : d.diagnostics.warnings)
    EXPECT_NE(w.find("Sampler \"halton\""), std::string::npos) << w;
  d.film.xres = 160;
  d.film.yres = 90;
  Diagnostics diag;
  auto sc = build_render_scene(d, diag);
  RenderOptions o;
  o.spp = 8;
  RenderResult r = render_image(*sc, o);
  EXPECT_EQ(r.width, 80);  // the cropwindow's half of the width
  EXPECT_EQ(r.nonfinite, 0u);
  int warm = 0, cool = 0;
  for (std::size_t i = 0; i < r.rgb.size(); i += 3) {
    const float R = r.rgb[i], B = r.rgb[i + 2];
    ASSERT_TRUE(std::isfinite(R) && std::isfinite(B));
    warm += R > 1.3f * B;
    cool += B > 1.3f * R;
  }
  EXPECT_GT(warm, 50);
  EXPECT_GT(cool, 50);
}

// sssdragon: a gzip-compressed PLY, an equal-area environment map, a Skin1 subsurface
// dragon and a checkerboard floor (reflectance 0.4 and 0.2), which once rendered white.
// The bottom rows see only the floor, lit alike: their brighter squares are about twice
// the darker ones.
TEST(PbrtV4Scenes, SssDragonRendersItsCheckerboardFloor) {
  SceneDesc d = parse_scene_file(std::string(DERMIS_SOURCE_DIR) + "/scenes/pbrt-v4/sssdragon/dragon_10.pbrt");
  for (const std::string& w : d.diagnostics.warnings) EXPECT_NE(w.find("Sampler \"halton\""), std::string::npos) << w;
  d.film.xres = 136;
  d.film.yres = 102;
  Diagnostics diag;
  auto sc = build_render_scene(d, diag);
  RenderOptions o;
  o.spp = 8;
  RenderResult r = render_image(*sc, o);
  EXPECT_EQ(r.nonfinite, 0u);
  std::vector<float> floor;
  for (int y = r.height - 10; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x) floor.push_back(r.rgb[3 * (std::size_t(y) * r.width + x) + 1]);
  std::sort(floor.begin(), floor.end());
  const float dark = floor[floor.size() / 10], bright = floor[floor.size() * 9 / 10];
  EXPECT_GT(dark, 0.0f);
  EXPECT_GT(bright / dark, 1.5f) << "dark " << dark << " bright " << bright;
  EXPECT_LT(bright / dark, 3.0f) << "dark " << dark << " bright " << bright;
}

}  // namespace
}  // namespace dermis
