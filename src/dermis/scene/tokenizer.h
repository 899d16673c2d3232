// Splits pbrt-v4 scene text into tokens, each with its exact line and column.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "dermis/scene/diagnostics.h"

namespace dermis {

struct Token {
  enum class Kind { Identifier, String, Number, LBracket, RBracket };
  Kind kind = Kind::Identifier;
  std::string text;    // identifier / number as written; string contents with escapes resolved
  double number = 0;   // Number tokens only
  int line = 0, column = 0;  // 1-based; the column counts bytes
};

// Human-readable token kind ("string", "number", "'['"...), for messages.
const char* token_kind_name(Token::Kind kind);

// Tokenizes `text`. `file` names the source in messages (and in SourceLoc).
// Rules: '#' starts a comment to the end of the line; strings are "..." on one line with
// the escapes \" \\ \n \t \r \b \f; numbers are anything starting with a digit, '+', '-'
// or '.', parsed completely by strtod and required to be finite; '[' and ']' are tokens;
// everything else that starts with a letter or '_' is an identifier.
// Throws SceneError at the offending character on malformed input.
std::vector<Token> tokenize(const std::string& text, const std::string& file);

}  // namespace dermis

namespace dermis {

// A cursor over the tokens of one file.
class TokenStream {
 public:
  TokenStream(std::vector<Token> tokens, std::string file) : tokens_(std::move(tokens)), file_(std::move(file)) {}
  bool at_end() const { return pos_ >= tokens_.size(); }
  // The next token, or nullptr at the end of the file.
  const Token* peek() const { return at_end() ? nullptr : &tokens_[pos_]; }
  const Token& next() { return tokens_[pos_++]; }
  const std::string& file() const { return file_; }
  // The directory relative file names in parameter values resolve against.
  const std::string& base_dir() const { return base_dir_; }
  void set_base_dir(std::string dir) { base_dir_ = std::move(dir); }
  SourceLoc loc(const Token& t) const { return {file_, t.line, t.column}; }
  // Where the end of the file is (just after the last token), for "unexpected end" errors.
  SourceLoc end_loc() const;

 private:
  std::vector<Token> tokens_;
  std::string file_;
  std::string base_dir_;
  size_t pos_ = 0;
};

}  // namespace dermis
