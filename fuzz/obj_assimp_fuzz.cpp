// Fuzz target: OBJ meshes through Assimp (import_mesh_assimp) and the mesh checks the
// parser applies after it. Bad input must end in std::runtime_error. Assimp itself is not
// instrumented for coverage, so libFuzzer mutates mostly blind here; the target still
// catches crashes, sanitizer reports in Dermis's code, hangs and unbounded memory.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <stdexcept>

#include "dermis/scene/mesh_import.h"
#include "temp_file.h"
#include "unexpected.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = dermis::fuzz::write_temp_file(data, size, ".obj");
  try {
    dermis::validate_mesh(dermis::import_mesh_assimp(path).mesh);
  } catch (const std::runtime_error&) {
    // the contract for bad input
  } catch (const std::exception& e) {
    dermis::fuzz::unexpected_exception("obj_assimp", e);
  }
  return 0;
}
