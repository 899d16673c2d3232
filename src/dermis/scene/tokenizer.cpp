#include "dermis/scene/tokenizer.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

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

// A text in memory, in chunks of 64 KiB (so that its progress grows as it is read).
class MemoryText final : public TextSource {
 public:
  explicit MemoryText(std::shared_ptr<const std::string> text) : text_(std::move(text)) {}
  std::string_view next_chunk() override {
    const std::string_view rest = std::string_view(*text_).substr(at_);
    const std::string_view chunk = rest.substr(0, kChunk);
    at_ += chunk.size();
    return chunk;
  }
  double fraction_read() const override { return text_->empty() ? 1.0 : double(at_) / double(text_->size()); }

 private:
  static constexpr size_t kChunk = size_t(1) << 16;
  std::shared_ptr<const std::string> text_;
  size_t at_ = 0;
};

}  // namespace

std::unique_ptr<TextSource> text_in_memory(std::shared_ptr<const std::string> text) {
  return std::make_unique<MemoryText>(std::move(text));
}

OpenText open_text(std::string text, std::string file) {
  auto shared = std::make_shared<const std::string>(std::move(text));
  auto origin = std::make_shared<TextOrigin>(TextOrigin{file, [shared] { return text_in_memory(shared); }});
  return {text_in_memory(shared), std::move(file), std::move(origin), nullptr};
}

Lexer::Lexer(std::unique_ptr<TextSource> source, std::string file, LoadStage* stage)
    : source_(std::move(source)), file_(std::move(file)), stage_(stage) {}

bool Lexer::refill() {
  if (ended_) return false;
  chunk_start_ += chunk_.size();
  chunk_ = source_->next_chunk();
  i_ = 0;
  ended_ = chunk_.empty();
  return !ended_;
}

void Lexer::skip_to(uint64_t offset, int line, int column) {
  while (offset > chunk_start_ + chunk_.size())
    if (!refill()) return;
  i_ = size_t(offset - chunk_start_);
  line_ = line;
  col_ = column;
}

bool Lexer::next(Token& t) {
  for (int c = peek_char();; c = peek_char()) {
    if (c < 0) return false;
    if (c == '#') {
      while ((c = peek_char()) >= 0 && c != '\n') advance();
    } else if (std::isspace(c)) {
      advance();
    } else {
      break;
    }
  }
  // Progress and Ctrl-C in a long text (a grid medium's millions of values), every 64 Ki tokens.
  if (stage_ && ++tokens_ >= next_report_) {
    stage_->update(source_->fraction_read());
    next_report_ = tokens_ + 0x10000;
  }
  const char c = chunk_[i_];
  t.line = line_;
  t.column = col_;
  t.offset = chunk_start_ + i_;
  t.number = 0;
  if (c == '[' || c == ']') {
    t.kind = c == '[' ? Token::Kind::LBracket : Token::Kind::RBracket;
    t.text.assign(1, c);
    advance();
  } else if (c == '"') {
    t.kind = Token::Kind::String;
    read_string(t);
  } else if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.') {
    t.kind = Token::Kind::Number;
    read_word(t.text);
    t.number = parse_number(t);
  } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
    t.kind = Token::Kind::Identifier;
    read_word(t.text);
  } else {
    throw SceneError(here(), fmt::format("unexpected character '{}' (byte 0x{:02x})",
                                         std::isprint(static_cast<unsigned char>(c)) ? std::string(1, c) : "?",
                                         static_cast<unsigned char>(c)));
  }
  end_line_ = line_;
  end_col_ = col_;
  return true;
}

// A run of characters up to the next separator, which may go on into the next chunk. No
// newline is among them: the column moves by their count.
void Lexer::read_word(std::string& out) {
  out.clear();
  do {
    const size_t start = i_;
    while (i_ < chunk_.size() && !is_separator(chunk_[i_])) ++i_;
    out.append(chunk_.substr(start, i_ - start));
    col_ += int(i_ - start);
  } while (i_ == chunk_.size() && refill());
}

void Lexer::read_string(Token& t) {
  advance();  // opening quote
  std::string& out = t.text;
  out.clear();
  while (true) {
    int c = peek_char();
    if (c < 0 || c == '\n') throw SceneError(at(t), "unterminated string (missing closing '\"' on this line)");
    if (c == '"') {
      advance();
      return;
    }
    if (c == '\\') {
      SourceLoc esc = here();
      advance();
      const int e = peek_char();
      if (e < 0 || e == '\n') throw SceneError(at(t), "unterminated string (missing closing '\"' on this line)");
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
          throw SceneError(esc, fmt::format("unknown escape sequence '\\{}' in string", char(e)));
      }
      advance();
      continue;
    }
    out += char(c);
    advance();
  }
}

double Lexer::parse_number(const Token& t) const {
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

std::vector<Token> tokenize(const std::string& text, const std::string& file, LoadStage* stage) {
  Lexer lexer(text_in_memory(std::make_shared<const std::string>(text)), file, stage);
  std::vector<Token> out;
  for (Token t; lexer.next(t);) out.push_back(t);
  return out;
}

}  // namespace dermis

namespace dermis {

TokenStream::TokenStream(OpenText text) { include(std::move(text)); }

void TokenStream::include(OpenText text) {
  Frame f;
  f.source = int(files_.size());
  files_.push_back(text.file);
  origins_.push_back(std::move(text.origin));
  f.stage = std::move(text.stage);
  f.lexer = std::make_unique<Lexer>(std::move(text.source), std::move(text.file), f.stage.get());
  frames_.push_back(std::move(f));
}

bool TokenStream::fill(Frame& f) {
  if (f.has_lookahead) return true;
  if (f.ended) return false;
  if (f.lexer->next(f.lookahead)) {
    f.has_lookahead = true;
    return true;
  }
  f.ended = true;
  if (f.stage) f.stage->finish();
  return false;
}

const Token* TokenStream::peek() const {
  for (auto f = frames_.rbegin(); f != frames_.rend(); ++f)
    if (fill(*f)) {
      f->lookahead.source = f->source;
      return &f->lookahead;
    }
  return nullptr;
}

const Token& TokenStream::next() {
  // Finished included files are closed here (not in peek), so that end_loc() still names
  // the file that ended.
  while (frames_.size() > 1 && !fill(frames_.back())) frames_.pop_back();
  Frame& f = frames_.back();
  if (!fill(f)) throw std::logic_error("TokenStream::next at the end of the text");
  std::swap(current_, f.lookahead);  // the lookahead's string keeps a buffer for the next token
  current_.source = f.source;
  f.has_lookahead = false;
  return current_;
}

std::vector<std::string> TokenStream::open_files() const {
  std::vector<std::string> open;
  for (const Frame& f : frames_) open.push_back(files_[f.source]);
  return open;
}

}  // namespace dermis
