// Fuzz target: the reader of pbrt-v4's nanovdb media (materials/nanovdb_grid.h, over
// NanoVDB's own reader) on a file holding the input: a density grid loaded, sampled and
// bounded. Bad input must end in std::runtime_error; other exceptions, crashes, sanitizer
// reports and hangs are findings.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <stdexcept>

#include "dermis/materials/nanovdb_grid.h"
#include "temp_file.h"
#include "unexpected.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = dermis::fuzz::write_temp_file(data, size, ".nvdb");
  try {
    const auto grid = dermis::NanoVdbGrid::load(path, "density");
    const dermis::Vec3 lo = grid->world_min(), hi = grid->world_max();
    volatile float sink = grid->value((lo + hi) * 0.5f) + grid->max_over(lo, hi);
    (void)sink;
  } catch (const std::runtime_error&) {
    // the contract for bad input
  } catch (const std::exception& e) {
    dermis::fuzz::unexpected_exception("nanovdb", e);
  }
  return 0;
}
