// Reader for PLY triangle meshes (ASCII and binary, faces and triangle strips).
//
// Dermis reads PLY itself rather than through Assimp: Assimp 5.2.5 (Debian 12) turns a
// "tristrips" element into a single triangle (checked on igea.ply: 1 face instead of
// ~270k), and pbrt scenes use such files.
#pragma once

#include <stdexcept>
#include <string>

#include "dermis/core/load_monitor.h"
#include "dermis/scene/scene_desc.h"

namespace dermis {

// Reads `path`, gzip-compressed or not (read_file_contents, gzip_file.h). Vertex properties x y z (required), nx ny nz,
// and u v / s t / texture_u texture_v / texture_s texture_t (optional). Element "face" (list property vertex_indices or
// vertex_index): triangles kept, quads split into (0,1,2) (0,2,3), larger polygons fanned from their first vertex.
// Element "tristrips" (list vertex_indices, -1 restarts a strip): triangle k of a strip is (s[k], s[k+1], s[k+2]) with
// the first two swapped for odd k so that all keep the strip's winding; triangles with a repeated index (the usual
// strip joiners) are dropped. Other elements are skipped. Throws FileReadError when the file cannot be read (missing,
// corrupt gzip data...), and std::runtime_error naming the problem otherwise (not a PLY file, unsupported property
// type, file truncated, index out of range, non-finite coordinate...).
// With a monitor: two stages, "loading NAME" (the file's bytes, inflated) and "reading
// NAME" (its elements), and Interrupted thrown once the monitor's cancel flag is set.
TriangleMeshDesc read_ply(const std::string& path, const LoadMonitor* monitor = nullptr);

}  // namespace dermis
