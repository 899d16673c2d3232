// LoadStage: reports start at 0, grow, end at 1 once, are thinned to 1% steps, and the
// cancel flag stops the stage (Interrupted, or false for the non-throwing form).
#include "dermis/core/load_monitor.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace dermis {
namespace {

struct Recorder {
  std::vector<std::pair<std::string, double>> calls;
  LoadMonitor monitor() {
    LoadMonitor m;
    m.progress = [this](const std::string& stage, double f) { calls.emplace_back(stage, f); };
    return m;
  }
};

TEST(LoadStage, ReportsZeroGrowingValuesAndOneOnce) {
  Recorder r;
  const LoadMonitor m = r.monitor();
  LoadStage stage(&m, "reading x");
  for (int i = 0; i <= 1000; ++i) stage.update(i / 1000.0);
  stage.update(0.5);  // late and smaller: dropped
  stage.finish();
  stage.finish();
  ASSERT_GE(r.calls.size(), 3u);
  EXPECT_EQ(r.calls.front(), std::make_pair(std::string("reading x"), 0.0));
  EXPECT_EQ(r.calls.back().second, 1.0);
  // At most one report per 1% (plus the first and the last), each larger than the one before.
  EXPECT_LE(r.calls.size(), 102u);
  for (std::size_t i = 1; i < r.calls.size(); ++i) {
    EXPECT_GT(r.calls[i].second, r.calls[i - 1].second) << i;
    EXPECT_EQ(r.calls[i].first, "reading x");
  }
}

// The tests' pause ($DERMIS_TEST_LOAD_STEP_MS): after each report, none without the variable.
// A lower bound on the stage's time (a sleep never ends early); the reports are the same.
TEST(LoadStage, TheTestPauseFollowsEachReport) {
  Recorder r;
  const LoadMonitor m = r.monitor();
  setenv("DERMIS_TEST_LOAD_STEP_MS", "20", 1);
  const auto start = std::chrono::steady_clock::now();
  {
    LoadStage stage(&m, "reading x");  // reads the variable when it starts
    unsetenv("DERMIS_TEST_LOAD_STEP_MS");
    stage.update(0.5);
    stage.update(0.501);  // not reported (under 1 % more): no pause
    stage.finish();
  }
  EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(3 * 20));
  EXPECT_EQ(r.calls.size(), 3u);
}

TEST(LoadStage, OutOfRangeFractionsAreClamped) {
  Recorder r;
  const LoadMonitor m = r.monitor();
  LoadStage stage(&m, "s");
  stage.update(-3);
  stage.update(7);
  for (const auto& [name, f] : r.calls) {
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
  }
  EXPECT_EQ(r.calls.back().second, 1.0);
}

TEST(LoadStage, TheCancelFlagStopsIt) {
  std::atomic<bool> cancel{false};
  Recorder r;
  LoadMonitor m = r.monitor();
  m.cancel = &cancel;
  LoadStage stage(&m, "s");
  stage.update(0.2);
  EXPECT_TRUE(stage.try_update(0.3));
  cancel = true;
  EXPECT_THROW(stage.update(0.4), Interrupted);
  EXPECT_FALSE(stage.try_update(0.5));
  EXPECT_THROW(stage.finish(), Interrupted);
  EXPECT_THROW(LoadStage(&m, "next"), Interrupted);
  EXPECT_LT(r.calls.back().second, 0.4);  // nothing reported once cancelled
}

TEST(LoadStage, NoMonitorIsANoOp) {
  LoadStage stage(nullptr, "s");
  stage.update(0.5);
  EXPECT_TRUE(stage.try_update(0.7));
  stage.finish();
  EXPECT_FALSE(stage.cancelled());
}

}  // namespace
}  // namespace dermis
