// A ProfileTable (tabulated.h) on disk, so that a table that takes seconds to build (the
// photon-beam-diffusion profile's) is built once per machine rather than once per
// process. The file holds the table's arrays as they are in memory (little-endian
// doubles) after a magic, a format version and a key naming what was tabulated; a reader
// takes a file only when its key is the one asked for.
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>

#include "dermis/sss/profiles/tabulated.h"

namespace dermis::sss {

inline constexpr uint32_t kProfileTableFileVersion = 1;

// Writes the table; false when the stream failed.
bool write_profile_table(std::ostream& out, const std::string& key, const ProfileTable& table);
// The table, or null when the stream does not hold a table of this format version and
// key, is truncated, or its arrays are inconsistent (sizes, non-finite values): a
// damaged or stale file is never used.
std::shared_ptr<const ProfileTable> read_profile_table(std::istream& in, const std::string& key);

// The table cached in `dir` under `key` (a file name), or built by `build` and then
// written there (a temporary file renamed, so that a concurrent reader never sees half a
// table). An empty dir, or one that cannot be read or written, only means no cache.
std::shared_ptr<const ProfileTable> cached_profile_table(const std::string& dir, const std::string& key,
                                                         const std::function<ProfileTable()>& build);

}  // namespace dermis::sss
