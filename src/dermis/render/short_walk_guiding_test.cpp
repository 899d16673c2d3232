// Guiding where the walks are short against the object (render/subsurface/walk_method.h,
// short_walk_guided_shares): the default's guided share raised to kShortWalkGuidedShare
// where every channel's importance length is below kShortWalkChordFraction of the
// object's mean chord length, and only there.
#include <gtest/gtest.h>

#include <string>

#include "dermis/render/object_chords.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/render/subsurface/subsurface_method.h"
#include "dermis/render/subsurface_pilot.h"
#include "dermis/scene/parser.h"

namespace dermis {
namespace {

// A sphere of radius `radius` filled with a subsurface medium under a sky.
std::string sphere(float radius, const std::string& material) {
  return R"(LookAt 0 -4 0  0 0 0  0 0 1
Camera "perspective" "float fov" 30
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Material "subsurface" )" +
         material + R"(
Shape "sphere" "float radius" )" +
         std::to_string(radius) + "\n";
}

const WalkMethod& walk_of(const RenderScene& sc) { return std::get<WalkMethod>(sc.subsurface[0]->method); }

TEST(ShortWalkGuiding, TheObjectsMeanChordIsItsThickness) {
  Diagnostics diag;
  auto sc =
      build_render_scene(parse_scene_string(sphere(3, R"("rgb reflectance" [0.3 0.3 0.3] "rgb mfp" [1 1 1])")), diag);
  const std::vector<double> chords = subsurface_object_chords(*sc);
  ASSERT_EQ(chords.size(), 1u);
  EXPECT_NEAR(chords[0], 4.0 * 3 / 3, 1e-5);  // 2D/3 of a sphere
}

TEST(ShortWalkGuiding, RaisesTheDefaultsShareOnlyWhereEveryChannelsWalksAreShort) {
  Diagnostics diag;
  const std::string dark = R"("rgb reflectance" [0.3 0.28 0.32] "rgb mfp" [0.01 0.01 0.01])";
  // A dark, dense medium in a sphere of radius 1: the walks' reach is about 1/100 of it.
  auto thick = build_render_scene(parse_scene_string(sphere(1, dark)), diag);
  const WalkMethod& w = walk_of(*thick);
  const double chord = subsurface_object_chords(*thick)[0];
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(w.step(0).importance_length(c), kShortWalkChordFraction * chord);
    EXPECT_EQ(w.step(0).p_guided(c), kShortWalkGuidedShare) << "channel " << c;
  }
  for (std::size_t v = 0; v < kWalkStrategies.size(); ++v) {
    const double expected = kWalkStrategies[v].p_guided == kWalkStrategies[0].p_guided ? kShortWalkGuidedShare
                                                                                       : kWalkStrategies[v].p_guided;
    EXPECT_NEAR(w.step(int(v)).p_guided(1), expected, 1e-6) << "strategy " << v;  // 0 stays 0, 0.8 stays 0.8
  }
  // The pilot's report says which share the default took, and why.
  SubsurfaceChoice choice;
  choice.material = 0;
  EXPECT_NE(describe_subsurface_choice(*thick, choice).find("guided share 0.8 (not 0.5: the walks are short"),
            std::string::npos)
      << describe_subsurface_choice(*thick, choice);
  // The same medium in a sphere 100x smaller: the walks reach across it.
  auto thin = build_render_scene(parse_scene_string(sphere(0.01f, dark)), diag);
  EXPECT_EQ(walk_of(*thin).step(0).p_guided(0), double(kWalkStrategies[0].p_guided));
  // One channel's walks long (a bright red): the shared walk keeps the default share.
  auto red = build_render_scene(
      parse_scene_string(sphere(1, R"("rgb reflectance" [0.95 0.28 0.32] "rgb mfp" [0.5 0.01 0.01])")), diag);
  EXPECT_GT(walk_of(*red).step(0).importance_length(0), kShortWalkChordFraction * 4.0 / 3);
  EXPECT_EQ(walk_of(*red).step(0).p_guided(1), double(kWalkStrategies[0].p_guided));
  // The same sphere seen through an instance (in its own space; an instance may scale it):
  // no thickness known, no rule.
  auto instanced = build_render_scene(parse_scene_string(R"(LookAt 0 -4 0  0 0 0  0 0 1
Camera "perspective" "float fov" 30
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
ObjectBegin "ball"
Material "subsurface" )" + dark + R"(
Shape "sphere" "float radius" 1
ObjectEnd
ObjectInstance "ball"
)"),
                                      diag);
  EXPECT_EQ(subsurface_object_chords(*instanced)[0], 0.0);
  EXPECT_EQ(walk_of(*instanced).step(0).p_guided(0), double(kWalkStrategies[0].p_guided));
  // A share the material gives is kept.
  auto given = build_render_scene(parse_scene_string(sphere(1, dark + R"( "float guidedshare" 0.3)")), diag);
  EXPECT_NEAR(walk_of(*given).step(0).p_guided(2), 0.3, 1e-6);
}

// The pilot's strategies that guide backward too (WalkStrategy::backward_guiding) are
// measured only where they change the walks: where the far side is within the walks'
// reach (by the same test as above), and the material leaves backward guiding to the
// pilot; `backwardguiding` given, every strategy has it (or none does).
TEST(ShortWalkGuiding, OffersBackwardGuidingOnlyWhereTheFarSideIsInReach) {
  std::vector<int> backward, not_backward;
  for (std::size_t v = 0; v < kWalkStrategies.size(); ++v)
    (kWalkStrategies[v].backward_guiding ? backward : not_backward).push_back(int(v));
  ASSERT_FALSE(backward.empty());
  const int all = int(kWalkStrategies.size());
  Diagnostics diag;
  auto offered = [&](const std::string& material, float radius) {
    auto sc = build_render_scene(parse_scene_string(sphere(radius, material)), diag);
    return std::pair{walk_of(*sc).backward_strategies_differ(), offered_strategies(*sc, all)};
  };
  // Dark and dense in a sphere of radius 1: the walks stay near their entry.
  const std::string dark = R"("rgb reflectance" [0.3 0.28 0.32] "rgb mfp" [0.01 0.01 0.01])";
  const auto [dark_differs, dark_offered] = offered(dark, 1);
  EXPECT_FALSE(dark_differs);
  EXPECT_EQ(dark_offered, not_backward);
  // The same medium 100x smaller, and a milk-like one: the far side is in reach.
  const std::string milk = R"("rgb reflectance" [0.95 0.9 0.75] "rgb mfp" [0.6 0.4 0.2])";
  for (const auto& [material, radius] : {std::pair{dark, 0.01f}, std::pair{milk, 1.0f}}) {
    const auto [differs, list] = offered(material, radius);
    EXPECT_TRUE(differs) << material;
    EXPECT_EQ(int(list.size()), all) << material;
  }
  // Given either way: every strategy as given, none offered for it.
  for (const char* given : {"true", "false"}) {
    auto sc = build_render_scene(parse_scene_string(sphere(1, milk + " \"bool backwardguiding\" " + given)), diag);
    EXPECT_FALSE(walk_of(*sc).backward_strategies_differ()) << given;
    EXPECT_EQ(offered_strategies(*sc, all), not_backward) << given;
    for (int v = 0; v < all; ++v) EXPECT_EQ(walk_of(*sc).backward_guiding(v), std::string(given) == "true") << v;
  }
  // Left to the pilot: the backward strategies alone guide backward.
  auto free = build_render_scene(parse_scene_string(sphere(1, milk)), diag);
  for (int v = 0; v < all; ++v)
    EXPECT_EQ(walk_of(*free).backward_guiding(v), kWalkStrategies[std::size_t(v)].backward_guiding) << v;
}

}  // namespace
}  // namespace dermis
