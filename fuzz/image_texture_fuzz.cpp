// Fuzz target: image textures and environment maps (read_image through OpenImageIO). The
// file is named after the input's magic bytes (.png, .exr, .hdr; anything else .png), as
// a scene names its textures. Bad input must end in std::runtime_error; a header whose
// size is taken on trust (std::bad_alloc, libFuzzer's malloc limit), crashes and hangs are
// findings. OpenImageIO is not instrumented for coverage.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <stdexcept>

#include "dermis/render/image.h"
#include "temp_file.h"
#include "unexpected.h"

namespace {

const char* suffix_for(const uint8_t* data, size_t size) {
  static const uint8_t kExr[4] = {0x76, 0x2f, 0x31, 0x01};
  if (size >= 4 && std::memcmp(data, kExr, 4) == 0) return ".exr";
  if (size >= 2 && data[0] == '#' && data[1] == '?') return ".hdr";
  return ".png";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = dermis::fuzz::write_temp_file(data, size, suffix_for(data, size));
  try {
    dermis::read_image(path);
  } catch (const std::runtime_error&) {
    // the contract for bad input
  } catch (const std::exception& e) {
    dermis::fuzz::unexpected_exception("image_texture", e);
  }
  return 0;
}
