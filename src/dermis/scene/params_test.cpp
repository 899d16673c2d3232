// ParsedParam::value_at: a value's line and column, found by reading its list again from its
// text (plain file, gzip file, text in memory), as the errors about one value name it.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "dermis/scene/parser.h"
#include "dermis/scene/scene_test_util.h"

namespace dermis {
namespace {

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
