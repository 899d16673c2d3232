// Triangle meshes from files: OBJ (and any other format Assimp reads) through Assimp,
// PLY through Dermis's own reader (see ply_reader.h for why).
#pragma once

#include <string>
#include <vector>

#include "dermis/core/load_monitor.h"
#include "dermis/scene/scene_desc.h"

namespace dermis {

struct ImportedMesh {
  TriangleMeshDesc mesh;
  std::vector<std::string> notes;  // non-fatal remarks (dropped points/lines, dropped normals...)
};

// Loads every mesh of the file with aiImportFile(path, aiProcess_Triangulate) and merges
// vertices identical in every attribute kept (as aiProcess_JoinIdenticalVertices, exactly) --
// no normals are generated: they are kept only when
// every mesh of the file has them -- applies the node transforms of the file's hierarchy,
// and merges everything into one mesh. Face winding is kept as written (Assimp's
// triangulation fans polygons from their first vertex in order). Throws
// std::runtime_error with Assimp's reason when the file cannot be read. With a monitor:
// stage "reading NAME" as Assimp reports it (its OBJ reader: by lines read), and
// Interrupted once the cancel flag is set -- Assimp is asked to stop, which its
// post-processing steps heed but its OBJ reader does not: it stops after the file.
ImportedMesh import_mesh_assimp(const std::string& path, const LoadMonitor* monitor = nullptr);

// Checks the invariants every mesh must satisfy: indices in range and a multiple of 3,
// finite coordinates, normals/uvs either absent or one per vertex. Throws
// std::runtime_error naming the first violation.
void validate_mesh(const TriangleMeshDesc& mesh);

}  // namespace dermis
