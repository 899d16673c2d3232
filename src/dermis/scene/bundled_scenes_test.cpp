// Every scene shipped in scenes/ (the demo and the benchmark scenes) parses without
// warnings: they cannot rot silently.
#include <gtest/gtest.h>

#include <filesystem>

#include "dermis/scene/parser.h"

namespace dermis {
namespace {

TEST(BundledScenes, AllParseWithoutWarnings) {
  namespace fs = std::filesystem;
  int count = 0;
  for (const char* dir : {"scenes", "scenes/bench"}) {
    for (const auto& e : fs::directory_iterator(fs::path(DERMIS_SOURCE_DIR) / dir)) {
      if (e.path().extension() != ".pbrt") continue;
      SCOPED_TRACE(e.path().string());
      SceneDesc d = parse_scene_file(e.path().string());
      EXPECT_TRUE(d.diagnostics.warnings.empty()) << d.diagnostics.warnings.front();
      ++count;
    }
  }
  EXPECT_GE(count, 4);
}

}  // namespace
}  // namespace dermis
