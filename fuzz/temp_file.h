// Fuzz targets whose reader takes a path: the input bytes written to a file in a private
// temporary directory (one per process, removed at exit), so that runs in parallel and
// the tree itself are left alone.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace dermis::fuzz {

// The private directory (created on first use).
const std::string& temp_dir();

// Writes `data` to `temp_dir()/input<suffix>` (replacing it) and returns the path.
std::string write_temp_file(const uint8_t* data, size_t size, const std::string& suffix);

}  // namespace dermis::fuzz
