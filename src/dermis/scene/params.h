// Parameter lists of pbrt-v4 directives: `"type name" value` or `"type name" [values]`,
// with typed getters that check the type and the number of values and mark the
// parameter used, so that the ones nobody read can be reported.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "dermis/core/float_array.h"
#include "dermis/core/vec.h"
#include "dermis/scene/diagnostics.h"
#include "dermis/scene/scene_desc.h"
#include "dermis/scene/tokenizer.h"

namespace dermis {

struct ParsedParam {
  Param param;                                     // as written (type spelled as in the file)
  std::string type;                                // canonical type: integer float point2 vector2 point3 vector3
                                                   // normal3 rgb spectrum blackbody bool string texture
  SourceLoc value_loc;                             // first token of the value ('[' or the single value)
  uint64_t value_offset = 0;                       // that token's byte in its text
  std::shared_ptr<const TextOrigin> value_origin;  // the text, read again by value_at (null: never)
  std::string base_dir;                            // where a file named in the value (a .spd spectrum) is looked for
  std::shared_ptr<const FileAccess> file_access;   // which files it may reach; null: any
  mutable bool used = false;

  size_t size() const;  // number of values of whatever kind
  // Where value i is: found by reading the list again from its text (no value keeps its
  // position: a grid's millions of values would need more than their own bytes), for
  // messages; value_loc when it cannot be.
  SourceLoc value_at(size_t i) const;
};

// One parameter as pbrt text: `"type name" [ values ]`, read back to the same values.
std::string param_text(const Param& p);

class ParamList {
 public:
  // Reads parameters while the next token is a string. Throws on a malformed list.
  static ParamList parse(TokenStream& ts);

  const ParsedParam* find(const std::string& name) const;
  bool has(const std::string& name) const { return find(name) != nullptr; }

  // Single values; the default when absent. Wrong type or count: SceneError.
  float get_float(const std::string& name, float def) const;
  int get_int(const std::string& name, int def) const;
  bool get_bool(const std::string& name, bool def) const;
  std::string get_string(const std::string& name, const std::string& def) const;
  // "texture name" parameters: the texture name, if present.
  std::optional<std::string> get_texture(const std::string& name) const;
  // Arrays: every value of a parameter of one of `types` (canonical); empty when absent.
  // `arity` values form one element: an error when the count is not a multiple of it.
  std::vector<double> get_numbers(const std::string& name, std::initializer_list<const char*> types,
                                  size_t arity) const;
  // The same as floats, null when absent: a long list's own array (shared, never copied), or
  // one made from a short list.
  std::shared_ptr<const FloatArray> get_float_array(const std::string& name, std::initializer_list<const char*> types,
                                                    size_t arity) const;
  std::vector<Vec3> get_vec3s(const std::string& name, std::initializer_list<const char*> types) const;
  std::optional<Vec3> get_vec3(const std::string& name, std::initializer_list<const char*> types) const;

  // Throws unless the parameter has one of the canonical types (marks it used).
  const ParsedParam& expect_type(const ParsedParam& p, std::initializer_list<const char*> types) const;

  void mark_all_used() const;
  // One warning per parameter that no getter read, naming its file:line:col.
  void warn_unused(Diagnostics& diag, const std::string& context) const;
  // Drops the parameters `changes` names, appends those of `changes`, and marks all
  // unused again (for re-reading a material with some parameters changed).
  void replace(const ParamList& changes);
  // All parameters as written.
  std::vector<Param> as_written() const;
  const std::vector<ParsedParam>& items() const { return items_; }

 private:
  // The numbers parameter `name`, checked as get_numbers checks it; null when absent.
  const ParsedParam* find_numbers(const std::string& name, std::initializer_list<const char*> types,
                                  size_t arity) const;

  std::vector<ParsedParam> items_;
};

}  // namespace dermis
