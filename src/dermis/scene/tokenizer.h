// Splits pbrt-v4 scene text into tokens, each with its exact line and column.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "dermis/core/load_monitor.h"
#include "dermis/scene/diagnostics.h"
#include "dermis/scene/file_access.h"

namespace dermis {

struct Token {
  enum class Kind { Identifier, String, Number, LBracket, RBracket };
  Kind kind = Kind::Identifier;
  std::string text;          // identifier / number as written; string contents with escapes resolved
  double number = 0;         // Number tokens only
  int line = 0, column = 0;  // 1-based; the column counts bytes
  int source = 0;            // TokenStream: which of its files the token came from
};

// Human-readable token kind ("string", "number", "'['"...), for messages.
const char* token_kind_name(Token::Kind kind);

// Tokenizes `text`. `file` names the source in messages (and in SourceLoc).
// Rules: '#' starts a comment to the end of the line; strings are "..." on one line with
// the escapes \" \\ \n \t \r \b \f; numbers are anything starting with a digit, '+', '-'
// or '.', parsed completely by strtod and required to be finite; '[' and ']' are tokens;
// everything else that starts with a letter or '_' is an identifier.
// Throws SceneError at the offending character on malformed input.
// `stage` (if given) reports how far it is and stops it on Ctrl-C (throws Interrupted).
std::vector<Token> tokenize(const std::string& text, const std::string& file, LoadStage* stage = nullptr);

}  // namespace dermis

namespace dermis {

// A cursor over the tokens of a scene file and the files it includes. As in pbrt-v4, an
// included file's tokens are read in place of the Include, and the stream then goes on
// with the including file: a parameter list may begin in one file and continue in the
// other.
class TokenStream {
 public:
  TokenStream(std::vector<Token> tokens, std::string file);
  // Reads the tokens of `file` next, then the rest of the current one.
  void include(std::vector<Token> tokens, std::string file);
  bool at_end() const { return peek() == nullptr; }
  // The next token, or nullptr at the end of the last file.
  const Token* peek() const;
  const Token& next();
  // The file of the innermost open file.
  const std::string& file() const { return files_[frames_.back().source]; }
  SourceLoc loc(const Token& t) const { return {files_[t.source], t.line, t.column}; }
  // The directory relative file names in parameter values resolve against (a .spd spectrum):
  // the main scene file's, for every file of the stream, as pbrt-v4 resolves them.
  const std::string& base_dir() const { return base_dir_; }
  void set_base_dir(std::string dir) { base_dir_ = std::move(dir); }
  // Which files those names may reach (scene/file_access.h); null: any.
  const std::shared_ptr<const FileAccess>& file_access() const { return file_access_; }
  void set_file_access(std::shared_ptr<const FileAccess> access) { file_access_ = std::move(access); }
  // Where the end of the innermost file is (just after its last token), for "unexpected end" errors.
  SourceLoc end_loc() const;
  // The files being read, outermost first (the main file, then each Include in turn).
  std::vector<std::string> open_files() const;

 private:
  struct Frame {
    std::vector<Token> tokens;
    int source = 0;
    size_t pos = 0;
  };
  std::vector<Frame> frames_;
  std::vector<std::string> files_;  // by Token::source; never shrinks, so that locations stay valid
  std::string base_dir_;
  std::shared_ptr<const FileAccess> file_access_;
};

}  // namespace dermis
