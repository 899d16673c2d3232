// Splits pbrt-v4 scene text into tokens, each with its exact line and column, as it is read.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
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
  uint64_t offset = 0;       // where its first byte is in its text
};

// Human-readable token kind ("string", "number", "'['"...), for messages.
const char* token_kind_name(Token::Kind kind);

// Where a scene text's bytes come from, a chunk at a time: a scene is never held whole (a
// grid medium's millions of values).
class TextSource {
 public:
  virtual ~TextSource() = default;
  // The next bytes; empty at the end of the text. Valid until the next call.
  virtual std::string_view next_chunk() = 0;
  // How much of the text has been read, in [0, 1] (progress).
  virtual double fraction_read() const = 0;
};

// A text in memory, handed out in chunks.
std::unique_ptr<TextSource> text_in_memory(std::shared_ptr<const std::string> text);

// A scene text that can be read again from its start. Parsed values keep no position each
// (8 bytes a value, more than a grid's float): a value found wrong after its list was read is
// placed by reading the list again (ParsedParam::value_at).
struct TextOrigin {
  std::string file;                                     // as messages name it
  std::function<std::unique_ptr<TextSource>()> reopen;  // may throw: the value is then placed at its list
};

// Splits a scene text into tokens, one at a time, each with its exact line and column.
// Rules: '#' starts a comment to the end of the line; strings are "..." on one line with
// the escapes \" \\ \n \t \r \b \f; numbers are anything starting with a digit, '+', '-'
// or '.', parsed completely by strtod and required to be finite; '[' and ']' are tokens;
// everything else that starts with a letter or '_' is an identifier.
// Throws SceneError at the offending character on malformed input. `file` names the text
// in messages; `stage` (if given) reports how far it is and stops it on Ctrl-C (throws
// Interrupted).
class Lexer {
 public:
  Lexer(std::unique_ptr<TextSource> source, std::string file, LoadStage* stage = nullptr);
  // Reads the next token into `t`; false at the end of the text.
  bool next(Token& t);
  // Just after the last token read (1:1 before any).
  SourceLoc end_loc() const { return {file_, end_line_, end_col_}; }
  // Goes on from byte `offset`, a token's start at line:column read before from the same text.
  void skip_to(uint64_t offset, int line, int column);

 private:
  // The character at the cursor, or -1 at the end of the text.
  int peek_char() {
    if (i_ == chunk_.size() && !refill()) return -1;
    return static_cast<unsigned char>(chunk_[i_]);
  }
  bool refill();
  void advance() {
    if (chunk_[i_] == '\n') {
      ++line_;
      col_ = 1;
    } else {
      ++col_;
    }
    ++i_;
  }
  SourceLoc here() const { return {file_, line_, col_}; }
  SourceLoc at(const Token& t) const { return {file_, t.line, t.column}; }
  void read_word(std::string& out);
  void read_string(Token& t);
  double parse_number(const Token& t) const;

  std::unique_ptr<TextSource> source_;
  std::string file_;
  LoadStage* stage_;
  std::string_view chunk_;
  size_t i_ = 0;              // the cursor in chunk_
  uint64_t chunk_start_ = 0;  // the offset of chunk_ in the text
  bool ended_ = false;
  int line_ = 1, col_ = 1;
  int end_line_ = 1, end_col_ = 1;
  uint64_t tokens_ = 0, next_report_ = 0x10000;
};

// Every token of `text` (tests, and short texts such as a material's changed parameters).
std::vector<Token> tokenize(const std::string& text, const std::string& file, LoadStage* stage = nullptr);

// A text opened for a TokenStream: its source, its name in messages, how to read it again
// (null: values are placed at the start of their list) and the load stage that shows its
// progress (null: none).
struct OpenText {
  std::unique_ptr<TextSource> source;
  std::string file;
  std::shared_ptr<const TextOrigin> origin;
  std::unique_ptr<LoadStage> stage;
};

// A text in memory, opened.
OpenText open_text(std::string text, std::string file);

}  // namespace dermis

namespace dermis {

// A cursor over the tokens of a scene file and the files it includes. As in pbrt-v4, an
// included file's tokens are read in place of the Include, and the stream then goes on
// with the including file: a parameter list may begin in one file and continue in the
// other.
class TokenStream {
 public:
  explicit TokenStream(OpenText text);
  // Reads the tokens of `text` next, then the rest of the current one.
  void include(OpenText text);
  bool at_end() const { return peek() == nullptr; }
  // The next token, or nullptr at the end of the last file. Valid until next().
  const Token* peek() const;
  // The next token (there must be one: peek first). Valid until the next call.
  const Token& next();
  // The file of the innermost open file.
  const std::string& file() const { return files_[frames_.back().source]; }
  SourceLoc loc(const Token& t) const { return {files_[t.source], t.line, t.column}; }
  // How to read the file of `t` again (null: it cannot be).
  const std::shared_ptr<const TextOrigin>& origin(const Token& t) const { return origins_[t.source]; }
  // The directory relative file names in parameter values resolve against (a .spd spectrum):
  // the main scene file's, for every file of the stream, as pbrt-v4 resolves them.
  const std::string& base_dir() const { return base_dir_; }
  void set_base_dir(std::string dir) { base_dir_ = std::move(dir); }
  // Which files those names may reach (scene/file_access.h); null: any.
  const std::shared_ptr<const FileAccess>& file_access() const { return file_access_; }
  void set_file_access(std::shared_ptr<const FileAccess> access) { file_access_ = std::move(access); }
  // Where the end of the innermost file is (just after its last token), for "unexpected end" errors.
  SourceLoc end_loc() const { return frames_.back().lexer->end_loc(); }
  // The files being read, outermost first (the main file, then each Include in turn).
  std::vector<std::string> open_files() const;

 private:
  struct Frame {
    std::unique_ptr<LoadStage> stage;  // before the lexer, which reports to it
    std::unique_ptr<Lexer> lexer;
    int source = 0;
    Token lookahead;
    bool has_lookahead = false, ended = false;
  };
  // Lexes the frame's next token into its lookahead, if it has one.
  static bool fill(Frame& f);

  mutable std::vector<Frame> frames_;  // tokens are read when first looked at
  Token current_;                      // the token next() returned
  std::vector<std::string> files_;     // by Token::source; never shrinks, so that locations stay valid
  std::vector<std::shared_ptr<const TextOrigin>> origins_;
  std::string base_dir_;
  std::shared_ptr<const FileAccess> file_access_;
};

}  // namespace dermis
