#include "dermis/scene/tokenizer.h"

#include <gtest/gtest.h>

#include <atomic>
#include <memory>

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

// A text handed out `size` bytes at a time: every token may straddle two chunks.
class SmallChunks final : public TextSource {
 public:
  SmallChunks(std::string text, std::size_t size) : text_(std::move(text)), size_(size) {}
  std::string_view next_chunk() override {
    const std::string_view chunk = std::string_view(text_).substr(std::min(at_, text_.size()), size_);
    at_ += chunk.size();
    return chunk;
  }
  double fraction_read() const override { return double(at_) / double(text_.size()); }

 private:
  std::string text_;
  std::size_t size_, at_ = 0;
};

// Read in chunks of 1, 2, 3 and 7 bytes, a text gives the tokens it gives whole: kinds, text,
// numbers, lines, columns and byte offsets.
TEST(Tokenizer, ChunkBoundariesChangeNoToken) {
  const std::string text =
      "Shape \"sphere\"  # comment [ \"x\"\r\n  \"float radius\" [ -2.5e1 ]\n\"a\\\"b\" ident_2 [1 2.5 .5 +3]# end";
  const std::vector<Token> whole = tokenize(text, "f");
  ASSERT_EQ(whole.size(), 14u);
  EXPECT_EQ(whole[6].text, "a\"b");
  EXPECT_EQ(text.substr(whole[7].offset, 7), "ident_2");
  for (std::size_t size : {1, 2, 3, 7}) {
    Lexer lexer(std::make_unique<SmallChunks>(text, size), "f");
    std::vector<Token> parts;
    for (Token t; lexer.next(t);) parts.push_back(t);
    ASSERT_EQ(parts.size(), whole.size()) << size;
    for (std::size_t i = 0; i < whole.size(); ++i) {
      EXPECT_EQ(parts[i].kind, whole[i].kind) << size << " " << i;
      EXPECT_EQ(parts[i].text, whole[i].text) << size << " " << i;
      EXPECT_EQ(parts[i].number, whole[i].number) << size << " " << i;
      EXPECT_EQ(parts[i].line, whole[i].line) << size << " " << i;
      EXPECT_EQ(parts[i].column, whole[i].column) << size << " " << i;
      EXPECT_EQ(parts[i].offset, whole[i].offset) << size << " " << i;
    }
    EXPECT_EQ(lexer.end_loc().line, 3);
    EXPECT_EQ(lexer.end_loc().column, 29);  // just after the last ']'
  }
}

// skip_to goes on from a token read before, at its line and column.
TEST(Tokenizer, SkipToResumesAtAToken) {
  const std::string text = "A [ 1\n 2\n\n  3 ]";
  const std::vector<Token> whole = tokenize(text, "f");
  ASSERT_EQ(whole.size(), 6u);
  for (std::size_t size : {1, 4, 100}) {
    Lexer lexer(std::make_unique<SmallChunks>(text, size), "f");
    lexer.skip_to(whole[3].offset, whole[3].line, whole[3].column);
    Token t;
    ASSERT_TRUE(lexer.next(t));
    EXPECT_EQ(t.text, "2");
    ASSERT_TRUE(lexer.next(t));
    EXPECT_EQ(t.text, "3");
    EXPECT_EQ(t.line, 4);
    EXPECT_EQ(t.column, 3);
  }
}

// An included text's tokens come before the rest of the including one; peek looks through a
// finished text to the one that goes on.
TEST(TokenStream, IncludedTextComesFirst) {
  TokenStream ts(open_text("A [ 1", "outer"));
  EXPECT_EQ(ts.next().text, "A");
  ts.include(open_text("B 2", "inner"));
  std::vector<std::string> seen;
  while (!ts.at_end()) {
    const Token& t = ts.next();
    seen.push_back(ts.loc(t).file + ":" + t.text);
  }
  EXPECT_EQ(seen, (std::vector<std::string>{"inner:B", "inner:2", "outer:[", "outer:1"}));
  EXPECT_EQ(ts.end_loc().column, 6);
}

}  // namespace
}  // namespace dermis
