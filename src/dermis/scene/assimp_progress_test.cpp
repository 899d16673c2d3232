#include "dermis/scene/assimp_progress.h"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace dermis {
namespace {

// Reports pass through while the stage runs; once cancelled, every call throws (an
// exception Assimp's importers catch): returning false would be ignored while it reads
// (SceneLoading.ObjThroughAssimpStopsWhileReadingALargeFile is the same through Assimp).
TEST(AssimpStageProgress, ReportsAndThrowsOnceCancelled) {
  std::atomic<bool> cancel{false};
  std::vector<std::pair<std::string, double>> calls;
  LoadMonitor m;
  m.cancel = &cancel;
  m.progress = [&](const std::string& stage, double f) { calls.emplace_back(stage, f); };
  LoadStage stage(&m, "reading m.obj");
  AssimpStageProgress handler(stage);
  EXPECT_TRUE(handler.Update(0.25f));
  EXPECT_TRUE(handler.Update(-1.0f));  // "go on?": yes
  ASSERT_EQ(calls.size(), 2u);
  EXPECT_EQ(calls[1].second, 0.25);
  cancel = true;
  EXPECT_THROW(handler.Update(0.4f), StopReading);
  EXPECT_THROW(handler.Update(-1.0f), StopReading);
  EXPECT_EQ(calls.size(), 2u);
  static_assert(std::is_base_of_v<std::exception, StopReading>, "Assimp catches std::exception");
}

}  // namespace
}  // namespace dermis
