// A guard before OpenEXR reads a header: every attribute's size must fit in the bytes the
// file still holds. OpenEXR 3.1 allocates an attribute's claimed size before reading it
// (a 708-byte file whose string attribute claims 1.8 GB took 1.9 GB: found by
// fuzz_image_texture), so a lying header is refused here, before OpenImageIO opens it.
// The layout read is the file format's (openexr.com, "OpenEXR File Layout"): magic,
// version and flags, then attributes (name, type, int32 size, value) up to a null byte,
// one header per part for multi-part files, ended by an empty header.
#pragma once

#include <string>

namespace dermis {

// Returns "" for a file that is not OpenEXR (other magic) or whose header sizes fit;
// otherwise what is wrong ("attribute "X" claims N bytes but the file holds only M more").
std::string exr_header_problem(const std::string& path);

}  // namespace dermis
