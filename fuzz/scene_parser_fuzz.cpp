// Fuzz target: the pbrt-v4 scene parser on arbitrary text. Malformed input must end in a
// SceneError (file:line:col); any other exception, a crash, a sanitizer report or a hang
// is a finding. Relative Include/Import/mesh paths resolve in an empty private directory.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "dermis/scene/diagnostics.h"
#include "dermis/scene/parser.h"
#include "temp_file.h"
#include "unexpected.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    dermis::parse_scene_string(text, "fuzz.pbrt", dermis::fuzz::temp_dir());
  } catch (const dermis::SceneError&) {
    // the contract for bad input
  } catch (const std::exception& e) {
    dermis::fuzz::unexpected_exception("scene_parser", e);
  }
  return 0;
}
