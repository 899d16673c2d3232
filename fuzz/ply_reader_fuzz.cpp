// Fuzz target: Dermis's own PLY reader (ASCII, both binary endiannesses, gzip) on a file
// holding the input. Bad input must end in std::runtime_error (FileReadError included);
// std::bad_alloc (a header count taken on trust), other exceptions, crashes, sanitizer
// reports and hangs are findings.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <stdexcept>

#include "dermis/scene/mesh_import.h"
#include "dermis/scene/ply_reader.h"
#include "temp_file.h"
#include "unexpected.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = dermis::fuzz::write_temp_file(data, size, ".ply");
  try {
    dermis::validate_mesh(dermis::read_ply(path));
  } catch (const std::runtime_error&) {
    // the contract for bad input
  } catch (const std::exception& e) {
    dermis::fuzz::unexpected_exception("ply_reader", e);
  }
  return 0;
}
