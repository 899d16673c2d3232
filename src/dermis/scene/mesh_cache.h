// The meshes Assimp imports (mesh_import.h), kept in Dermis' cache directory
// (core/cache_dir.h) so that rendering the same OBJ again does not parse it again.
//
// Why: Assimp's OBJ reader takes 0.2-0.4 s for the 100k-triangle bust
// (scenes/meshes/nefertiti.obj), most of it in its allocations and page faults
// (docs/results/results-rendering.md, "Loading large meshes"): three quarters of a small render's process
// and, in the family's whole-process convention, of Dermis' time on the bust. Reading the
// imported arrays back takes milliseconds. An artist re-rendering an asset pays the parse
// once.
//
// A cache file holds the source file's canonical path, size, modification time and the
// CRC-32 (zlib) of its bytes, then the mesh (positions, normals, uvs, indices, the
// importer's notes) as written in memory, then the CRC-32 of all that. It is used only if
// all of them match the file as it is now, and the mesh passes validate_mesh: an edited,
// replaced, truncated or corrupted cache is a miss, never an error, and the file is
// imported again (and the cache rewritten). Written to a temporary file and renamed, so
// concurrent renders (an MPI group) never read half a file.
#pragma once

#include <optional>
#include <string>

#include "dermis/core/load_monitor.h"
#include "dermis/scene/mesh_import.h"

namespace dermis {

// The cache file of a mesh file (in cache_dir; named by the CRC-32 of its canonical path).
std::string mesh_cache_path(const std::string& cache_dir, const std::string& canonical_path);

// The cached import of `path`, if cache_dir holds a valid one for the file as it is now.
std::optional<ImportedMesh> load_cached_mesh(const std::string& cache_dir, const std::string& path);

// Writes the import of `path` to cache_dir (created if needed). False when it could not
// (no directory, full disk, the file changed while it was read): the cache is optional.
bool save_cached_mesh(const std::string& cache_dir, const std::string& path, const ImportedMesh& mesh);

// Imports that took less than this are not cached (a small file parses about as fast as
// its cache reads back, and would only add a file).
inline constexpr double kMinImportSecondsToCache = 0.05;

// import_mesh_assimp through the cache: the cached import if valid (reported as the stage
// "reading NAME", as the import is, and stopped by the monitor's cancel flag), else the
// file imported and, if that took min_import_seconds or more, cached. An empty cache_dir
// (no $XDG_CACHE_HOME or $HOME) imports without a cache. The same mesh and notes either
// way. Saving also removes the cache files of sources that no longer exist.
ImportedMesh import_mesh_cached(const std::string& path, const LoadMonitor* monitor, const std::string& cache_dir,
                                double min_import_seconds = kMinImportSecondsToCache);

}  // namespace dermis
