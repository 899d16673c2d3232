#include "dermis/render/progress.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <string>
#include <thread>
#include <vector>

namespace dermis {
namespace {

// Everything written to a temporary FILE*.
std::string contents(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string s;
  for (int c; (c = std::fgetc(f)) != EOF;) s.push_back(char(c));
  return s;
}

int count(const std::string& s, const std::string& what) {
  int n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

TEST(FormatDuration, ReadableAtEveryScale) {
  EXPECT_EQ(format_duration(0), "0.0s");
  EXPECT_EQ(format_duration(3.26), "3.3s");
  EXPECT_EQ(format_duration(42.4), "42s");
  EXPECT_EQ(format_duration(59.6), "1m 00s");
  EXPECT_EQ(format_duration(65), "1m 05s");
  EXPECT_EQ(format_duration(3599), "59m 59s");
  EXPECT_EQ(format_duration(3600 + 2 * 60 + 5), "1h 02m 05s");
  EXPECT_EQ(format_duration(30 * 3600), "30h 00m 00s");
  EXPECT_EQ(format_duration(-1), "--");
  EXPECT_EQ(format_duration(std::numeric_limits<double>::infinity()), "--");
  EXPECT_EQ(format_duration(std::numeric_limits<double>::quiet_NaN()), "--");
}

TEST(EstimateRemaining, ExtrapolatesTheRateSoFar) {
  EXPECT_DOUBLE_EQ(estimate_remaining_seconds(10, 25, 100), 30);  // 75 more at 2.5 per second
  EXPECT_DOUBLE_EQ(estimate_remaining_seconds(10, 100, 100), 0);
  EXPECT_LT(estimate_remaining_seconds(10, 0, 100), 0);  // unknown
  EXPECT_DOUBLE_EQ(progress_fraction(1, 4), 0.25);
  EXPECT_DOUBLE_EQ(progress_fraction(5, 0), 1);  // empty job
  EXPECT_DOUBLE_EQ(progress_fraction(7, 4), 1);
}

TEST(FormatProgress, BarAndLineShowPercentElapsedAndEta) {
  EXPECT_EQ(format_progress_bar("render", 50, 100, 65, 10), "render [#####     ]  50.0%  1m 05s elapsed, ETA 1m 05s");
  EXPECT_EQ(format_progress_line("render", 500, 1000, 65), "render: 50% (500/1000), 1m 05s elapsed, ETA 1m 05s");
  EXPECT_EQ(format_progress_bar("x", 0, 10, 1, 4), "x [    ]   0.0%  1.0s elapsed, ETA --");
}

TEST(Progress, LineModePrintsEveryTenPercentThenDone) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    Progress p("job", 100, Progress::Style::kLines, f);
    for (int i = 0; i < 100; ++i) p.advance(1);
    p.finish();
    p.finish();  // idempotent
    EXPECT_EQ(p.done(), 100);
  }
  const std::string out = contents(f);
  std::fclose(f);
  // One line per 10% step (the test runs far faster than the 10 s line interval).
  EXPECT_EQ(count(out, "\n"), 11) << out;
  for (int pct = 10; pct <= 100; pct += 10)
    EXPECT_EQ(count(out, "job: " + std::to_string(pct) + "% (" + std::to_string(pct) + "/100)"), 1) << out;
  EXPECT_EQ(count(out, "job: done (100/100) in "), 1) << out;
  EXPECT_EQ(count(out, "\r"), 0);
}

TEST(Progress, BarModeRedrawsInPlaceAndEndsTheLine) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  Progress p("bar", 8, Progress::Style::kBar, f);
  for (int i = 0; i < 8; ++i) p.advance(1);
  p.finish();
  const std::string out = contents(f);
  std::fclose(f);
  EXPECT_GE(count(out, "\r"), 2) << out;  // first advance and finish at least
  EXPECT_EQ(count(out, "\n"), 1) << out;
  EXPECT_EQ(out.back(), '\n');
  EXPECT_NE(out.find("100.0%"), std::string::npos) << out;
}

TEST(Progress, QuietModeWritesNothing) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  Progress p("quiet", 10, Progress::Style::kQuiet, f);
  p.advance(10);
  p.finish();
  EXPECT_EQ(contents(f), "");
  std::fclose(f);
  EXPECT_EQ(p.done(), 10);
}

TEST(Progress, AutoStyleOnAFileIsLines) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  Progress p("auto", 10, Progress::Style::kAuto, f);
  EXPECT_EQ(p.style(), Progress::Style::kLines);
  p.finish();
  std::fclose(f);
}

TEST(Progress, ConcurrentAdvanceSumsExactly) {
  for (Progress::Style style : {Progress::Style::kQuiet, Progress::Style::kLines, Progress::Style::kBar}) {
    std::FILE* f = std::tmpfile();
    ASSERT_NE(f, nullptr);
    constexpr int kPerThread = 200'000;
    Progress p("threads", 3 * kPerThread, style, f);
    std::vector<std::thread> threads;
    for (int t = 0; t < 2; ++t)
      threads.emplace_back([&p, t] {
        for (int i = 0; i < kPerThread; ++i) p.advance(t + 1);  // 1s from one thread, 2s from the other
      });
    for (auto& t : threads) t.join();
    p.finish();
    EXPECT_EQ(p.done(), 3 * kPerThread);
    std::fclose(f);
  }
}

}  // namespace
}  // namespace dermis
