#include "dermis/scene/params.h"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <sstream>

namespace dermis {

namespace {

enum class ValueKind { Numbers, Strings, Bools, NumbersOrString };

// Canonical name and value kind of each parameter type (pbrt-v3 aliases included).
bool canonical_type(const std::string& written, std::string& canonical, ValueKind& kind) {
  static const std::map<std::string, std::pair<std::string, ValueKind>> kTypes = {
      {"integer", {"integer", ValueKind::Numbers}},
      {"float", {"float", ValueKind::Numbers}},
      {"point2", {"point2", ValueKind::Numbers}},
      {"vector2", {"vector2", ValueKind::Numbers}},
      {"point3", {"point3", ValueKind::Numbers}},
      {"point", {"point3", ValueKind::Numbers}},
      {"vector3", {"vector3", ValueKind::Numbers}},
      {"vector", {"vector3", ValueKind::Numbers}},
      {"normal3", {"normal3", ValueKind::Numbers}},
      {"normal", {"normal3", ValueKind::Numbers}},
      {"rgb", {"rgb", ValueKind::Numbers}},
      {"color", {"rgb", ValueKind::Numbers}},
      {"blackbody", {"blackbody", ValueKind::Numbers}},
      {"spectrum", {"spectrum", ValueKind::NumbersOrString}},
      {"bool", {"bool", ValueKind::Bools}},
      {"string", {"string", ValueKind::Strings}},
      {"texture", {"texture", ValueKind::Strings}},
  };
  auto it = kTypes.find(written);
  if (it == kTypes.end()) return false;
  canonical = it->second.first;
  kind = it->second.second;
  return true;
}

std::string type_list(std::initializer_list<const char*> types) {
  std::string s;
  for (const char* t : types) s += (s.empty() ? "" : " or ") + std::string(t);
  return s;
}

// One number more: past kLongNumberList values of a non-integer type, the list moves to floats
// (Param::long_numbers) and grows there.
void add_number(ParsedParam& p, double x) {
  Param& q = p.param;
  if (q.long_numbers) {
    q.long_numbers->push_back(float(x));
    return;
  }
  q.numbers.push_back(x);
  if (q.numbers.size() <= kLongNumberList || p.type == "integer") return;
  auto floats = std::make_shared<FloatArray>();
  floats->reserve(q.numbers.size());
  for (double d : q.numbers) floats->push_back(float(d));
  q.long_numbers = std::move(floats);
  std::vector<double>().swap(q.numbers);  // its memory given back, not only emptied
}

void add_value(ParsedParam& p, ValueKind kind, const Token& t, const TokenStream& ts) {
  SourceLoc loc = ts.loc(t);
  const std::string& name = p.param.name;
  switch (kind) {
    case ValueKind::Numbers:
      if (t.kind != Token::Kind::Number)
        throw SceneError(loc, fmt::format("parameter \"{} {}\" expects numbers, found {} '{}'", p.param.type, name,
                                          token_kind_name(t.kind), excerpt(t.text)));
      if (p.type == "integer" && t.number != std::floor(t.number))
        throw SceneError(loc,
                         fmt::format("parameter \"integer {}\" expects integers, found '{}'", name, excerpt(t.text)));
      add_number(p, t.number);
      break;
    case ValueKind::Strings:
      if (t.kind != Token::Kind::String)
        throw SceneError(loc, fmt::format("parameter \"{} {}\" expects quoted strings, found {} '{}'", p.param.type,
                                          name, token_kind_name(t.kind), t.text));
      p.param.strings.push_back(t.text);
      break;
    case ValueKind::Bools: {
      // pbrt accepts both true and "true".
      if ((t.kind == Token::Kind::String || t.kind == Token::Kind::Identifier) &&
          (t.text == "true" || t.text == "false")) {
        p.param.bools.push_back(t.text == "true");
      } else {
        throw SceneError(loc, fmt::format("parameter \"bool {}\" expects true or false, found {} '{}'", name,
                                          token_kind_name(t.kind), t.text));
      }
      break;
    }
    case ValueKind::NumbersOrString:
      if (t.kind == Token::Kind::Number && p.param.strings.empty()) {
        add_number(p, t.number);
      } else if (t.kind == Token::Kind::String && p.param.number_count() == 0 && p.param.strings.empty()) {
        p.param.strings.push_back(t.text);
      } else {
        throw SceneError(loc, fmt::format("parameter \"spectrum {}\" expects [wavelength value ...] pairs or one "
                                          "named spectrum, found {} '{}'",
                                          name, token_kind_name(t.kind), t.text));
      }
      break;
  }
}

}  // namespace

size_t ParsedParam::size() const { return param.number_count() + param.strings.size() + param.bools.size(); }

SourceLoc ParsedParam::value_at(size_t i) const {
  if (!value_origin || i >= size()) return value_loc;
  try {
    Lexer lexer(value_origin->reopen(), value_loc.file);
    lexer.skip_to(value_offset, value_loc.line, value_loc.column);
    Token t;
    if (!lexer.next(t)) return value_loc;
    if (t.kind == Token::Kind::LBracket && !lexer.next(t)) return value_loc;
    for (size_t k = 0; k < i; ++k)
      if (!lexer.next(t)) return value_loc;
    // A list that ran on into an included file, or a text changed since: not this list's value.
    if (t.kind == Token::Kind::LBracket || t.kind == Token::Kind::RBracket) return value_loc;
    return {value_loc.file, t.line, t.column};
  } catch (const std::exception&) {
    return value_loc;
  }
}

ParamList ParamList::parse(TokenStream& ts) {
  ParamList list;
  while (const Token* t = ts.peek()) {
    if (t->kind != Token::Kind::String) break;
    const Token decl = ts.next();
    ParsedParam p;
    p.param.loc = ts.loc(decl);
    std::istringstream words(decl.text);
    std::string type, name, extra;
    words >> type >> name >> extra;
    if (type.empty() || name.empty() || !extra.empty())
      throw SceneError(p.param.loc,
                       fmt::format("expected a parameter declaration \"type name\", found \"{}\"", excerpt(decl.text)));
    ValueKind kind;
    if (!canonical_type(type, p.type, kind))
      throw SceneError(p.param.loc, fmt::format("unknown parameter type '{}' in \"{}\" (expected integer, float, "
                                                "point2, vector2, point3, vector3, normal3, rgb, spectrum, "
                                                "blackbody, bool, string or texture)",
                                                type, decl.text));
    p.param.type = type;
    p.param.name = name;
    for (const ParsedParam& q : list.items_)
      if (q.param.name == name)
        throw SceneError(p.param.loc, fmt::format("parameter '{}' given twice (first at {})", name, q.param.loc.str()));
    const Token* v = ts.peek();
    if (!v) throw SceneError(ts.end_loc(), fmt::format("missing value of parameter \"{}\"", excerpt(decl.text)));
    p.value_loc = ts.loc(*v);
    p.value_offset = v->offset;
    p.value_origin = ts.origin(*v);
    p.base_dir = ts.base_dir();
    p.file_access = ts.file_access();
    if (v->kind == Token::Kind::LBracket) {
      ts.next();
      while (true) {
        const Token* e = ts.peek();
        if (!e)
          throw SceneError(p.value_loc, fmt::format("missing ']' closing the values of parameter \"{}\"", decl.text));
        if (e->kind == Token::Kind::RBracket) {
          ts.next();
          break;
        }
        if (e->kind == Token::Kind::Identifier && kind != ValueKind::Bools)
          throw SceneError(ts.loc(*e), fmt::format("missing ']' closing the values of parameter \"{}\" (found "
                                                   "directive '{}')",
                                                   decl.text, e->text));
        add_value(p, kind, ts.next(), ts);
      }
      if (p.size() == 0) throw SceneError(p.value_loc, fmt::format("parameter \"{}\" has no values", decl.text));
      if (p.param.long_numbers) p.param.long_numbers->shrink_to_fit();
    } else {
      add_value(p, kind, ts.next(), ts);
    }
    list.items_.push_back(std::move(p));
  }
  return list;
}

const ParsedParam* ParamList::find(const std::string& name) const {
  for (const ParsedParam& p : items_)
    if (p.param.name == name) return &p;
  return nullptr;
}

const ParsedParam& ParamList::expect_type(const ParsedParam& p, std::initializer_list<const char*> types) const {
  p.used = true;
  for (const char* t : types)
    if (p.type == t) return p;
  throw SceneError(p.param.loc, fmt::format("parameter '{}' has type '{}', expected {}", p.param.name, p.param.type,
                                            type_list(types)));
}

namespace {
void expect_one(const ParsedParam& p) {
  if (p.size() != 1)
    throw SceneError(p.value_loc, fmt::format("parameter \"{} {}\" expects exactly one value, got {}", p.param.type,
                                              p.param.name, p.size()));
}
}  // namespace

float ParamList::get_float(const std::string& name, float def) const {
  const ParsedParam* p = find(name);
  if (!p) return def;
  expect_type(*p, {"float"});
  expect_one(*p);
  return float(p->param.numbers[0]);
}

int ParamList::get_int(const std::string& name, int def) const {
  const ParsedParam* p = find(name);
  if (!p) return def;
  expect_type(*p, {"integer"});
  expect_one(*p);
  double v = p->param.numbers[0];
  if (std::abs(v) > 2147483647.0)
    throw SceneError(p->value_loc, fmt::format("integer parameter '{}' is out of range", name));
  return int(v);
}

bool ParamList::get_bool(const std::string& name, bool def) const {
  const ParsedParam* p = find(name);
  if (!p) return def;
  expect_type(*p, {"bool"});
  expect_one(*p);
  return p->param.bools[0];
}

std::string ParamList::get_string(const std::string& name, const std::string& def) const {
  const ParsedParam* p = find(name);
  if (!p) return def;
  expect_type(*p, {"string"});
  expect_one(*p);
  return p->param.strings[0];
}

std::optional<std::string> ParamList::get_texture(const std::string& name) const {
  const ParsedParam* p = find(name);
  if (!p || p->type != "texture") return std::nullopt;
  p->used = true;
  expect_one(*p);
  return p->param.strings[0];
}

const ParsedParam* ParamList::find_numbers(const std::string& name, std::initializer_list<const char*> types,
                                           size_t arity) const {
  const ParsedParam* p = find(name);
  if (!p) return nullptr;
  expect_type(*p, types);
  if (!p->param.strings.empty()) throw SceneError(p->value_loc, fmt::format("parameter '{}' expects numbers", name));
  if (arity > 1 && p->param.number_count() % arity != 0)
    throw SceneError(p->value_loc, fmt::format("parameter \"{} {}\" needs a multiple of {} values, got {}",
                                               p->param.type, name, arity, p->param.number_count()));
  return p;
}

std::vector<double> ParamList::get_numbers(const std::string& name, std::initializer_list<const char*> types,
                                           size_t arity) const {
  const ParsedParam* p = find_numbers(name, types, arity);
  return p ? p->param.numbers_as_doubles() : std::vector<double>{};
}

std::shared_ptr<const FloatArray> ParamList::get_float_array(const std::string& name,
                                                             std::initializer_list<const char*> types,
                                                             size_t arity) const {
  const ParsedParam* p = find_numbers(name, types, arity);
  if (!p) return nullptr;
  if (p->param.long_numbers) return p->param.long_numbers;
  auto floats = std::make_shared<FloatArray>();
  floats->reserve(p->param.numbers.size());
  for (double d : p->param.numbers) floats->push_back(float(d));
  return floats;
}

std::vector<Vec3> ParamList::get_vec3s(const std::string& name, std::initializer_list<const char*> types) const {
  const ParsedParam* p = find_numbers(name, types, 3);
  if (!p) return {};
  const Param& q = p->param;
  std::vector<Vec3> out(q.number_count() / 3);
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = Vec3(float(q.number(3 * i)), float(q.number(3 * i + 1)), float(q.number(3 * i + 2)));
  return out;
}

std::optional<Vec3> ParamList::get_vec3(const std::string& name, std::initializer_list<const char*> types) const {
  const ParsedParam* p = find(name);
  if (!p) return std::nullopt;
  std::vector<Vec3> v = get_vec3s(name, types);
  if (v.size() != 1)
    throw SceneError(p->value_loc, fmt::format("parameter \"{} {}\" expects 3 values, got {}", p->param.type, name,
                                               p->param.number_count()));
  return v[0];
}

void ParamList::mark_all_used() const {
  for (const ParsedParam& p : items_) p.used = true;
}

void ParamList::warn_unused(Diagnostics& diag, const std::string& context) const {
  for (const ParsedParam& p : items_)
    if (!p.used)
      diag.warn(p.param.loc,
                fmt::format("unused parameter \"{} {}\" (ignored by {})", p.param.type, p.param.name, context));
}

std::string param_text(const Param& p) {
  auto quoted = [](const std::string& s) {
    std::string q = "\"";
    for (char c : s) {
      if (c == '"' || c == '\\') q += '\\';
      q += c;
    }
    return q + "\"";
  };
  std::string text = quoted(p.type + " " + p.name) + " [";
  for (double x : p.numbers) text += fmt::format(" {}", x);  // shortest form that reads back exactly
  if (p.long_numbers)
    for (float x : *p.long_numbers) text += fmt::format(" {}", x);  // the float's shortest form
  for (const std::string& s : p.strings) text += " " + quoted(s);
  for (bool b : p.bools) text += b ? " true" : " false";
  return text + " ]";
}

void ParamList::replace(const ParamList& changes) {
  std::erase_if(items_, [&](const ParsedParam& p) { return changes.has(p.param.name); });
  items_.insert(items_.end(), changes.items_.begin(), changes.items_.end());
  for (const ParsedParam& p : items_) p.used = false;
}

std::vector<Param> ParamList::as_written() const {
  std::vector<Param> out;
  out.reserve(items_.size());
  for (const ParsedParam& p : items_) out.push_back(p.param);
  return out;
}

}  // namespace dermis
