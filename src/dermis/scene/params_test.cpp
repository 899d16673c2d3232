// Long parameter lists: past kLongNumberList values a list of non-integers is held as floats,
// shared (never copied) by get_float_array, as_written and replace, and read back the same by
// size, get_numbers and param_text; integers and short lists keep their doubles. Read through
// a material's kept parameters (MaterialDesc::params).
#include "dermis/scene/params.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "dermis/scene/parser.h"
#include "dermis/scene/scene_test_util.h"

namespace dermis {
namespace {

using test::parse_world;

// `count` values "i.1" (not exact in binary: the float and the double differ).
std::string values_text(std::size_t count) {
  std::string text = "[";
  for (std::size_t i = 0; i < count; ++i) text += fmt::format(" {}.1", i);
  return text + " ]";
}

double value_as_written(std::size_t i) { return double(i) + 0.1; }

// The kept parameters of a diffuse material given `params`.
std::shared_ptr<const ParamList> material_params(const std::string& params) {
  SceneDesc s = parse_world("Material \"diffuse\" " + params + "\n");
  EXPECT_EQ(s.materials.size(), 1u);
  return s.materials.at(0).params;
}

TEST(ParamsLongLists, NonIntegersPastTheThresholdAreFloats) {
  constexpr std::size_t kCount = 3 * 2000;  // past kLongNumberList, a multiple of 3
  static_assert(kCount > kLongNumberList);
  std::string ids = "[";
  for (std::size_t i = 0; i < kCount; ++i) ids += fmt::format(" {}", 16777217 + i);  // not exact as floats
  const auto pl = material_params("\"float junk\" " + values_text(kCount) + " \"integer ids\" " + ids +
                                  " ] \"rgb short\" [0.1 0.2 0.3] \"float edge\" " + values_text(kLongNumberList));

  const ParsedParam& junk = *pl->find("junk");
  ASSERT_TRUE(junk.param.long_numbers);
  EXPECT_TRUE(junk.param.numbers.empty());
  EXPECT_EQ(junk.size(), kCount);
  EXPECT_EQ(junk.param.number_count(), kCount);
  const std::vector<double> doubles = pl->get_numbers("junk", {"float"}, 1);
  ASSERT_EQ(doubles.size(), kCount);
  for (std::size_t i = 0; i < kCount; ++i) ASSERT_EQ(doubles[i], double(float(value_as_written(i)))) << i;

  // Shared, not copied: the parameter's own array, each time.
  const auto floats = pl->get_float_array("junk", {"float"}, 3);
  EXPECT_EQ(floats.get(), junk.param.long_numbers.get());
  EXPECT_EQ(pl->get_float_array("junk", {"float", "rgb"}, 1).get(), floats.get());
  EXPECT_EQ(floats->size(), kCount);

  // Integers stay exact, however many; a list of exactly kLongNumberList stays doubles.
  const ParsedParam& id_list = *pl->find("ids");
  EXPECT_FALSE(id_list.param.long_numbers);
  ASSERT_EQ(id_list.param.numbers.size(), kCount);
  EXPECT_EQ(id_list.param.numbers.back(), 16777217.0 + double(kCount - 1));
  EXPECT_FALSE(pl->find("edge")->param.long_numbers);
  EXPECT_EQ(pl->find("edge")->param.numbers.at(7), 7.1);

  // A short list gives a new array of its values as floats.
  const auto rgb = pl->get_float_array("short", {"rgb"}, 3);
  ASSERT_TRUE(rgb);
  EXPECT_EQ(std::vector<float>(rgb->begin(), rgb->end()), (std::vector<float>{0.1f, 0.2f, 0.3f}));
  EXPECT_FALSE(pl->get_float_array("absent", {"float"}, 1));
}

TEST(ParamsLongLists, ChecksAsGetNumbers) {
  const auto pl = material_params("\"float junk\" " + values_text(5000) + " \"string s\" \"x\"");
  EXPECT_THROW(pl->get_float_array("junk", {"float"}, 3), SceneError);  // 5000 is no multiple of 3
  EXPECT_THROW(pl->get_numbers("junk", {"float"}, 3), SceneError);
  EXPECT_THROW(pl->get_float_array("junk", {"rgb"}, 1), SceneError);  // the type
  EXPECT_THROW(pl->get_float_array("s", {"string"}, 1), SceneError);  // not numbers
  try {
    pl->get_float_array("junk", {"float"}, 3);
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("needs a multiple of 3 values, got 5000"), std::string::npos) << e.what();
  }
}

TEST(ParamsLongLists, WrittenAndReadBackTheSame) {
  constexpr std::size_t kCount = 5000;
  const auto pl = material_params("\"spectrum junk\" " + values_text(kCount));
  const ParsedParam& junk = *pl->find("junk");
  ASSERT_TRUE(junk.param.long_numbers);

  // as_written and a copy share the floats.
  const std::vector<Param> written = pl->as_written();
  ASSERT_EQ(written.size(), 1u);
  EXPECT_EQ(written[0].long_numbers.get(), junk.param.long_numbers.get());
  ParamList merged = *pl;
  merged.replace(*material_params("\"float other\" 1"));
  ASSERT_TRUE(merged.find("junk"));
  EXPECT_EQ(merged.find("junk")->param.long_numbers.get(), junk.param.long_numbers.get());
  EXPECT_EQ(merged.find("other")->param.numbers, std::vector<double>{1});

  // The text reads back to the same floats.
  const std::string text = param_text(written[0]);
  EXPECT_EQ(text.substr(0, 30), "\"spectrum junk\" [ 0.1 1.1 2.1 ");
  const auto again = material_params(text);
  const ParsedParam& back = *again->find("junk");
  ASSERT_TRUE(back.param.long_numbers);
  EXPECT_EQ(std::vector<float>(back.param.long_numbers->begin(), back.param.long_numbers->end()),
            std::vector<float>(junk.param.long_numbers->begin(), junk.param.long_numbers->end()));
  EXPECT_EQ(back.param.number(4321), double(float(4321.1)));
}

// ParsedParam::value_at, below: a value's line and column, found by reading its list again
// from its text (plain file, gzip file, text in memory), as the errors about one value name it.

using test::TempDir;

// A grid medium whose 2000 densities run over 100 lines of 20, value `bad` negative.
std::string grid_medium(int bad) {
  std::string s = "MakeNamedMedium \"m\" \"string type\" \"uniformgrid\" \"integer nx\" 2000\n\"float density\" [";
  for (int i = 0; i < 2000; ++i) s += fmt::format("{}{}", i % 20 == 0 ? "\n  " : " ", i == bad ? "-1.5" : "0.25");
  return s + " ]\n";
}

// The error about value `i` of grid_medium(), parsed by `parse`, names file:line:column of
// that value: the list's first value is on `first_line`, each line of 20 is indented by two
// spaces and a value takes 5 bytes.
template <class Parse>
void expect_error_at_value(Parse parse, const std::string& file, int first_line, int i) {
  try {
    parse();
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().file, file) << e.what();
    EXPECT_EQ(e.loc().line, first_line + i / 20) << e.what();
    EXPECT_EQ(e.loc().column, 3 + 5 * (i % 20)) << e.what();
    EXPECT_NE(std::string(e.what()).find(fmt::format("value {} of", i)), std::string::npos) << e.what();
  }
}

TEST(ParsedParamValueAt, FoundAgainInThePlainFile) {
  TempDir dir;
  const std::string path = dir.write("s.pbrt", "WorldBegin\n" + grid_medium(1234));
  expect_error_at_value([&] { parse_scene_file(path); }, path, 4, 1234);
}

TEST(ParsedParamValueAt, FoundAgainInAGzipInclude) {
  TempDir dir;
  dir.write("grid.pbrt.gz", test::gzip(grid_medium(1999)));
  const std::string path = dir.write("s.pbrt", "WorldBegin\nInclude \"grid.pbrt.gz\"\n");
  expect_error_at_value([&] { parse_scene_file(path); }, dir.path() + "/grid.pbrt.gz", 3, 1999);
}

TEST(ParsedParamValueAt, FoundAgainInTextInMemory) {
  expect_error_at_value([] { parse_scene_string("WorldBegin\n" + grid_medium(7), "mem.pbrt"); }, "mem.pbrt", 4, 7);
}

}  // namespace
}  // namespace dermis
