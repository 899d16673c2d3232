#include "dermis/scene/tokenizer.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace dermis {

const char* token_kind_name(Token::Kind kind) {
  switch (kind) {
    case Token::Kind::Identifier:
      return "identifier";
    case Token::Kind::String:
      return "string";
    case Token::Kind::Number:
      return "number";
    case Token::Kind::LBracket:
      return "'['";
    case Token::Kind::RBracket:
      return "']'";
  }
  return "token";
}

namespace {

bool is_separator(char c) {
  return std::isspace(static_cast<unsigned char>(c)) || c == '[' || c == ']' || c == '"' || c == '#';
}

class Lexer {
 public:
  Lexer(const std::string& text, const std::string& file, LoadStage* stage) : s_(text), file_(file), stage_(stage) {}

  std::vector<Token> run() {
    std::vector<Token> out;
    while (i_ < s_.size()) {
      // Progress and Ctrl-C in a long file (a grid medium's millions of values), every 64 Ki tokens.
      if (stage_ && out.size() >= next_report_) {
        stage_->update(double(i_) / double(s_.size()));
        next_report_ = out.size() + 0x10000;
      }
      char c = s_[i_];
      if (c == '\n') {
        advance();
        continue;
      }
      if (std::isspace(static_cast<unsigned char>(c))) {
        advance();
        continue;
      }
      if (c == '#') {
        while (i_ < s_.size() && s_[i_] != '\n') advance();
        continue;
      }
      Token t;
      t.line = line_;
      t.column = col_;
      if (c == '[' || c == ']') {
        t.kind = c == '[' ? Token::Kind::LBracket : Token::Kind::RBracket;
        t.text = std::string(1, c);
        advance();
      } else if (c == '"') {
        t.kind = Token::Kind::String;
        t.text = read_string(t);
      } else if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.') {
        t.kind = Token::Kind::Number;
        t.text = read_word();
        t.number = parse_number(t);
      } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
        t.kind = Token::Kind::Identifier;
        t.text = read_word();
      } else {
        throw SceneError(here(), fmt::format("unexpected character '{}' (byte 0x{:02x})",
                                             std::isprint(static_cast<unsigned char>(c)) ? std::string(1, c) : "?",
                                             static_cast<unsigned char>(c)));
      }
      out.push_back(std::move(t));
    }
    return out;
  }

 private:
  SourceLoc here() const { return {file_, line_, col_}; }
  SourceLoc at(const Token& t) const { return {file_, t.line, t.column}; }

  void advance() {
    if (s_[i_] == '\n') {
      ++line_;
      col_ = 1;
    } else {
      ++col_;
    }
    ++i_;
  }

  std::string read_word() {
    size_t start = i_;
    while (i_ < s_.size() && !is_separator(s_[i_])) advance();
    return s_.substr(start, i_ - start);
  }

  std::string read_string(const Token& t) {
    advance();  // opening quote
    std::string out;
    while (true) {
      if (i_ >= s_.size() || s_[i_] == '\n')
        throw SceneError(at(t), "unterminated string (missing closing '\"' on this line)");
      char c = s_[i_];
      if (c == '"') {
        advance();
        return out;
      }
      if (c == '\\') {
        SourceLoc esc = here();
        advance();
        if (i_ >= s_.size() || s_[i_] == '\n')
          throw SceneError(at(t), "unterminated string (missing closing '\"' on this line)");
        char e = s_[i_];
        switch (e) {
          case 'n':
            out += '\n';
            break;
          case 't':
            out += '\t';
            break;
          case 'r':
            out += '\r';
            break;
          case 'b':
            out += '\b';
            break;
          case 'f':
            out += '\f';
            break;
          case '\\':
            out += '\\';
            break;
          case '"':
            out += '"';
            break;
          case '\'':
            out += '\'';
            break;
          default:
            throw SceneError(esc, fmt::format("unknown escape sequence '\\{}' in string", e));
        }
        advance();
        continue;
      }
      out += c;
      advance();
    }
  }

  double parse_number(const Token& t) {
    const char* begin = t.text.c_str();
    char* end = nullptr;
    double v = std::strtod(begin, &end);
    if (end == begin || *end != '\0') throw SceneError(at(t), fmt::format("invalid number '{}'", excerpt(t.text)));
    if (!std::isfinite(v)) throw SceneError(at(t), fmt::format("number '{}' is not finite", excerpt(t.text)));
    // Geometry, transforms and colours are 32-bit floats: a larger number would become
    // infinity there, silently (an object translated by 1e39 vanishes).
    if (std::abs(v) > double(std::numeric_limits<float>::max()))
      throw SceneError(at(t), fmt::format("number '{}' is beyond the range of 32-bit floats (3.4e38) in which the "
                                          "scene is stored",
                                          excerpt(t.text)));
    return v;
  }

  const std::string& s_;
  std::string file_;
  LoadStage* stage_;
  std::size_t next_report_ = 0x10000;
  size_t i_ = 0;
  int line_ = 1, col_ = 1;
};

}  // namespace

std::vector<Token> tokenize(const std::string& text, const std::string& file, LoadStage* stage) {
  return Lexer(text, file, stage).run();
}

}  // namespace dermis

namespace dermis {

TokenStream::TokenStream(std::vector<Token> tokens, std::string file) { include(std::move(tokens), std::move(file)); }

void TokenStream::include(std::vector<Token> tokens, std::string file) {
  const int source = int(files_.size());
  files_.push_back(std::move(file));
  for (Token& t : tokens) t.source = source;
  frames_.push_back({std::move(tokens), source, 0});
}

const Token* TokenStream::peek() const {
  for (auto f = frames_.rbegin(); f != frames_.rend(); ++f)
    if (f->pos < f->tokens.size()) return &f->tokens[f->pos];
  return nullptr;
}

const Token& TokenStream::next() {
  // Finished included files are closed here (not in peek), so that a token just returned
  // stays valid until the next call.
  while (frames_.size() > 1 && frames_.back().pos >= frames_.back().tokens.size()) frames_.pop_back();
  Frame& f = frames_.back();
  return f.tokens[f.pos++];
}

std::vector<std::string> TokenStream::open_files() const {
  std::vector<std::string> open;
  for (const Frame& f : frames_) open.push_back(files_[f.source]);
  return open;
}

SourceLoc TokenStream::end_loc() const {
  const Frame& f = frames_.back();
  if (f.tokens.empty()) return {files_[f.source], 1, 1};
  const Token& t = f.tokens.back();
  int width = t.kind == Token::Kind::String ? int(t.text.size()) + 2 : int(t.text.size());
  return {files_[f.source], t.line, t.column + width};
}

}  // namespace dermis
