// The named measured media of pbrt-v4: every name, values against the papers, use by name.
#include "dermis/scene/medium_presets.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "dermis/scene/parser.h"
#include "dermis/scene/scene_test_util.h"

namespace dermis {
namespace {

using test::parse_world;

void expect_rgb_rel(RGB a, RGB b, float rel) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], rel * b[i]) << "channel " << i;
}

// pbrt-v4's names (src/pbrt/media.cpp, GetMediumScatteringProperties), spelled as there.
constexpr const char* kPbrtNames[] = {"Apple",
                                      "Chicken1",
                                      "Chicken2",
                                      "Cream",
                                      "Ketchup",
                                      "Marble",
                                      "Potato",
                                      "Skimmilk",
                                      "Skin1",
                                      "Skin2",
                                      "Spectralon",
                                      "Wholemilk",
                                      "Lowfat Milk",
                                      "Reduced Milk",
                                      "Regular Milk",
                                      "Espresso",
                                      "Mint Mocha Coffee",
                                      "Lowfat Soy Milk",
                                      "Regular Soy Milk",
                                      "Lowfat Chocolate Milk",
                                      "Regular Chocolate Milk",
                                      "Coke",
                                      "Pepsi",
                                      "Sprite",
                                      "Gatorade",
                                      "Chardonnay",
                                      "White Zinfandel",
                                      "Merlot",
                                      "Budweiser Beer",
                                      "Coors Light Beer",
                                      "Clorox",
                                      "Apple Juice",
                                      "Cranberry Juice",
                                      "Grape Juice",
                                      "Ruby Grapefruit Juice",
                                      "White Grapefruit Juice",
                                      "Shampoo",
                                      "Strawberry Shampoo",
                                      "Head & Shoulders Shampoo",
                                      "Lemon Tea Powder",
                                      "Orange Powder",
                                      "Pink Lemonade Powder",
                                      "Cappuccino Powder",
                                      "Salt Powder",
                                      "Sugar Powder",
                                      "Suisse Mocha Powder",
                                      "Pacific Ocean Surface Water"};

TEST(MediumPresets, EveryNameOfPbrtV4IsFound) {
  EXPECT_EQ(std::size(kPbrtNames), 47u);
  EXPECT_EQ(medium_presets().size(), std::size(kPbrtNames));
  for (const char* n : kPbrtNames) {
    auto p = find_medium_preset(n);
    ASSERT_TRUE(p.has_value()) << n;
    EXPECT_EQ(std::string(p->name), n);  // the exact spelling is kept
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(p->sigma_a[c] >= 0 && p->sigma_s_prime[c] >= 0) << n;
  }
  // Lookups ignore case, spaces, '-' and '_'; no two names fold to the same key.
  for (const char* n : {"skin 2", "WHOLE_MILK", "skim-milk", "regular milk", "RegularMilk", "head & shoulders shampoo"})
    EXPECT_TRUE(find_medium_preset(n).has_value()) << n;
  std::set<std::string> folded;
  for (const MediumPreset& p : medium_presets()) {
    std::string key;
    for (char c : std::string(p.name))
      if (c != ' ' && c != '-' && c != '_') key += char(std::tolower(static_cast<unsigned char>(c)));
    EXPECT_TRUE(folded.insert(key).second) << p.name;
  }
  EXPECT_FALSE(find_medium_preset("Jelly").has_value());
}

TEST(MediumPresets, ValuesAgainstThePapers) {
  // Jensen et al. 2001, Table 2 (mm^-1): Ketchup sigma_a, Marble sigma_s', Skin1 both.
  expect_rgb_rel(find_medium_preset("Ketchup")->sigma_a, RGB(0.061f, 0.97f, 1.45f), 1e-6f);
  expect_rgb_rel(find_medium_preset("Marble")->sigma_s_prime, RGB(2.19f, 2.62f, 3.00f), 1e-6f);
  expect_rgb_rel(find_medium_preset("Skin1")->sigma_s_prime, RGB(0.74f, 0.88f, 1.01f), 1e-6f);
  // Narasimhan et al. 2006 list sigma_s, sigma_a (mm^-1) and g; pbrt keeps sigma_s' =
  // sigma_s (1 - g). Regular milk: sigma_s = (18.2052, 20.3826, 22.3698), g = (0.750, 0.714,
  // 0.681). The paper prints 5-6 digits: 1e-4 relative for the product.
  const MediumPreset milk = *find_medium_preset("Regular Milk");
  expect_rgb_rel(milk.sigma_s_prime, RGB(18.2052f * 0.250f, 20.3826f * 0.286f, 22.3698f * 0.319f), 1e-4f);
  // Espresso absorbs far more than it scatters; Coke hardly scatters at all.
  const MediumPreset espresso = *find_medium_preset("Espresso");
  for (int c = 0; c < 3; ++c) EXPECT_GT(espresso.sigma_a[c], 4 * espresso.sigma_s_prime[c]);
  EXPECT_LT(find_medium_preset("Coke")->sigma_s_prime.max(), 1e-4f);
}

TEST(MediumPresets, UsedByMediaAndSubsurfaceWithSuggestionsForNearMisses) {
  SceneDesc s = parse_world(
      "MakeNamedMedium \"milk\" \"string type\" \"homogeneous\" \"string preset\" \"Regular Milk\"\n"
      "Material \"subsurface\" \"string name\" \"Espresso\" \"float scale\" 10\nShape \"sphere\"\n");
  EXPECT_EQ(s.media[0].preset, "Regular Milk");
  expect_rgb_rel(s.media[0].sigma_s, find_medium_preset("Regular Milk")->sigma_s_prime, 1e-6f);
  const SubsurfaceParams& ss = s.materials[0].subsurface;
  expect_rgb_rel(*ss.sigma_a, find_medium_preset("Espresso")->sigma_a * 10, 1e-6f);
  expect_rgb_rel(*ss.sigma_s, find_medium_preset("Espresso")->sigma_s_prime * 10, 1e-6f);

  auto error_of = [](const std::string& body) -> std::string {
    try {
      parse_world(body);
    } catch (const SceneError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(error_of("MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"string preset\" \"Regular Mlk\"\n")
                .find("test.pbrt:2:65: error: unknown medium preset \"Regular Mlk\" (did you mean 'Regular Milk'?) "
                      "(valid: Apple, Chicken1"),
            std::string::npos);
  EXPECT_NE(error_of("Material \"subsurface\" \"string name\" \"Expresso\"\n")
                .find("unknown subsurface preset \"Expresso\" (did you mean 'Espresso'?)"),
            std::string::npos);
  EXPECT_NE(error_of("Material \"subsurface\" \"string name\" \"Jelly\"\n")
                .find("unknown subsurface preset \"Jelly\" (valid:"),
            std::string::npos);
}

}  // namespace
}  // namespace dermis
