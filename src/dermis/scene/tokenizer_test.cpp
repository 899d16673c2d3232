#include "dermis/scene/tokenizer.h"

#include <gtest/gtest.h>

#include <atomic>

namespace dermis {
namespace {

TEST(Tokenizer, KindsTextAndExactPositions) {
  auto t = tokenize("Shape \"sphere\"  # comment [ \"x\"\n  \"float radius\" [ -2.5e1 ]\n", "f");
  ASSERT_EQ(t.size(), 6u);
  EXPECT_EQ(t[0].kind, Token::Kind::Identifier);
  EXPECT_EQ(t[0].text, "Shape");
  EXPECT_EQ(t[0].line, 1);
  EXPECT_EQ(t[0].column, 1);
  EXPECT_EQ(t[1].kind, Token::Kind::String);
  EXPECT_EQ(t[1].text, "sphere");
  EXPECT_EQ(t[1].column, 7);
  EXPECT_EQ(t[2].text, "float radius");
  EXPECT_EQ(t[2].line, 2);
  EXPECT_EQ(t[2].column, 3);
  EXPECT_EQ(t[3].kind, Token::Kind::LBracket);
  EXPECT_EQ(t[3].column, 18);
  EXPECT_EQ(t[4].kind, Token::Kind::Number);
  EXPECT_DOUBLE_EQ(t[4].number, -25.0);
  EXPECT_EQ(t[4].column, 20);
  EXPECT_EQ(t[5].kind, Token::Kind::RBracket);
  EXPECT_EQ(t[5].column, 27);
}

TEST(Tokenizer, BracketsNeedNoSpaces) {
  auto t = tokenize("[1 2.5 .5 +3]", "f");
  ASSERT_EQ(t.size(), 6u);
  EXPECT_DOUBLE_EQ(t[1].number, 1);
  EXPECT_DOUBLE_EQ(t[2].number, 2.5);
  EXPECT_DOUBLE_EQ(t[3].number, 0.5);
  EXPECT_DOUBLE_EQ(t[4].number, 3);
  EXPECT_EQ(t[5].column, 13);
}

TEST(Tokenizer, StringEscapesAndHashInsideString) {
  auto t = tokenize(R"("a\"b\\c\n#not a comment")", "f");
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].text, "a\"b\\c\n#not a comment");
}

TEST(Tokenizer, CommentRunsToEndOfLineOnly) {
  auto t = tokenize("# all of this\nWorldBegin # and this\n", "f");
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].line, 2);
}

TEST(Tokenizer, CrLfLineEndings) {
  auto t = tokenize("A\r\nB", "f");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[1].line, 2);
  EXPECT_EQ(t[1].column, 1);
}

void expect_error(const std::string& text, int line, int col, const std::string& what) {
  try {
    tokenize(text, "f.pbrt");
    FAIL() << "no error for: " << text;
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().line, line) << e.what();
    EXPECT_EQ(e.loc().column, col) << e.what();
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("f.pbrt:", 0), 0u) << e.what();
  }
}

TEST(Tokenizer, Errors) {
  expect_error("Shape \"sphere", 1, 7, "unterminated string");
  expect_error("A\n  \"abc\ndef\"", 2, 3, "unterminated string");
  expect_error("\"a\\qb\"", 1, 3, "unknown escape");
  expect_error("Translate 1 2x 3", 1, 13, "invalid number '2x'");
  expect_error("Scale 1 -nan 1", 1, 9, "not finite");
  expect_error("Scale 1 1e999 1", 1, 9, "not finite");
  expect_error("Scale 1 1e39 1", 1, 9, "beyond the range of 32-bit floats");
  expect_error("Translate 0 -3.5e38 0", 1, 13, "beyond the range of 32-bit floats");
  expect_error("Shape @", 1, 7, "unexpected character '@'");
}

// A long text (a grid medium's values) reports its progress as it goes and stops, throwing
// Interrupted, once the monitor's cancel flag is set.
TEST(Tokenizer, LongTextShowsProgressAndStopsOnCancel) {
  std::string text = "MakeNamedMedium \"m\" \"float density\" [";
  for (int i = 0; i < 400000; ++i) text += " 0.5";
  text += " ]";
  std::vector<double> fractions;
  std::atomic<bool> cancel = false;
  LoadMonitor monitor;
  monitor.progress = [&](const std::string&, double f) { fractions.push_back(f); };
  monitor.cancel = &cancel;
  {
    LoadStage stage(&monitor, "parsing");
    EXPECT_EQ(tokenize(text, "f.pbrt", &stage).size(), 400005u);  // 5 besides the values
  }
  ASSERT_GE(fractions.size(), 5u);  // 0, then every 64 Ki tokens
  for (std::size_t i = 1; i < fractions.size(); ++i) EXPECT_GT(fractions[i], fractions[i - 1]);
  monitor.progress = [&](const std::string&, double f) {
    if (f > 0.3) cancel = true;
  };
  LoadStage stage(&monitor, "parsing");
  EXPECT_THROW(tokenize(text, "f.pbrt", &stage), Interrupted);
}

}  // namespace
}  // namespace dermis
