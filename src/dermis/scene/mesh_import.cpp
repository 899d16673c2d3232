#include "dermis/scene/mesh_import.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include <array>
#include <assimp/Importer.hpp>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "dermis/scene/assimp_progress.h"

namespace dermis {

namespace {

struct Collected {
  const aiMesh* mesh;
  aiMatrix4x4 to_root;
};

void collect(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent, std::vector<Collected>& out) {
  aiMatrix4x4 m = parent * node->mTransformation;
  for (unsigned i = 0; i < node->mNumMeshes; ++i) out.push_back({scene->mMeshes[node->mMeshes[i]], m});
  for (unsigned i = 0; i < node->mNumChildren; ++i) collect(scene, node->mChildren[i], m, out);
}

// The mesh's vertices with identical attributes merged: for each vertex of `m`, the index of
// the first vertex with the same bits of position, normal (if the mesh has normals) and
// first uv set (if it has one), in order of first occurrence. Assimp's OBJ reader writes one
// vertex per face corner (three per triangle); this restores the file's own sharing.
// Assimp's aiProcess_JoinIdenticalVertices does the same with an epsilon comparison over
// a spatial sort, and took 0.1-0.3 s of the 0.4 s load of a 100k-triangle OBJ
// (scenes/meshes/nefertiti.obj); an exact hash takes a few milliseconds. The triangles are
// the same; corners that differ only below Assimp's epsilon (not the file's own shared
// vertices) stay apart. On the bust the two give the same mesh and the same image.
std::vector<uint32_t> first_identical_vertex(const aiMesh* m) {
  struct Key {
    std::array<uint32_t, 8> bits{};
    bool operator==(const Key& o) const { return bits == o.bits; }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      uint64_t h = 0x9e3779b97f4a7c15ull;
      for (uint32_t b : k.bits) h = (h ^ b) * 0xff51afd7ed558ccdull, h ^= h >> 32;
      return std::size_t(h);
    }
  };
  auto bits = [](float x) {
    uint32_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  };
  std::unordered_map<Key, uint32_t, KeyHash> first;
  first.reserve(m->mNumVertices);
  std::vector<uint32_t> remap(m->mNumVertices);
  uint32_t unique = 0;
  for (unsigned v = 0; v < m->mNumVertices; ++v) {
    Key k;
    const aiVector3D& p = m->mVertices[v];
    k.bits[0] = bits(p.x), k.bits[1] = bits(p.y), k.bits[2] = bits(p.z);
    if (m->HasNormals()) {
      const aiVector3D& n = m->mNormals[v];
      k.bits[3] = bits(n.x), k.bits[4] = bits(n.y), k.bits[5] = bits(n.z);
    }
    if (m->HasTextureCoords(0))
      k.bits[6] = bits(m->mTextureCoords[0][v].x), k.bits[7] = bits(m->mTextureCoords[0][v].y);
    const auto [it, inserted] = first.try_emplace(k, unique);
    if (inserted) ++unique;
    remap[v] = it->second;
  }
  return remap;
}

}  // namespace

ImportedMesh import_mesh_assimp(const std::string& path, const LoadMonitor* monitor) {
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw std::runtime_error(std::strerror(errno));
  }
  LoadStage stage(monitor, "reading " + std::filesystem::path(path).filename().string());
  Assimp::Importer importer;
  importer.SetProgressHandler(new AssimpStageProgress(stage));  // the importer owns it
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate);
  stage.throw_if_cancelled();
  if (!scene) throw std::runtime_error(fmt::format("Assimp: {}", importer.GetErrorString()));
  if (!scene->mRootNode || scene->mNumMeshes == 0) throw std::runtime_error("the file contains no meshes");

  std::vector<Collected> parts;
  collect(scene, scene->mRootNode, aiMatrix4x4(), parts);
  bool all_normals = true, all_uvs = true;
  for (const Collected& c : parts) {
    all_normals = all_normals && c.mesh->HasNormals();
    all_uvs = all_uvs && c.mesh->HasTextureCoords(0);
  }

  ImportedMesh out;
  TriangleMeshDesc& mesh = out.mesh;
  size_t dropped = 0;
  for (const Collected& c : parts) {
    const aiMesh* m = c.mesh;
    const uint32_t base = uint32_t(mesh.positions.size());
    aiMatrix3x3 normal_matrix(c.to_root);
    normal_matrix.Inverse().Transpose();
    const std::vector<uint32_t> shared = first_identical_vertex(m);
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      if (shared[v] != mesh.positions.size() - base) continue;  // a repeat of an earlier vertex
      aiVector3D p = c.to_root * m->mVertices[v];
      mesh.positions.emplace_back(p.x, p.y, p.z);
      if (all_normals) {
        aiVector3D n = normal_matrix * m->mNormals[v];
        mesh.normals.emplace_back(n.x, n.y, n.z);
      }
      if (all_uvs) mesh.uvs.emplace_back(m->mTextureCoords[0][v].x, m->mTextureCoords[0][v].y);
    }
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const aiFace& face = m->mFaces[f];
      if (face.mNumIndices != 3) {
        ++dropped;
        continue;
      }
      for (int k = 0; k < 3; ++k) mesh.indices.push_back(base + shared[face.mIndices[k]]);
    }
  }
  if (dropped) out.notes.push_back(fmt::format("{} point/line primitives dropped", dropped));
  bool any_normals = false;
  for (const Collected& c : parts) any_normals = any_normals || c.mesh->HasNormals();
  if (any_normals && !all_normals) out.notes.push_back("normals dropped: only some meshes of the file have them");
  if (parts.size() > 1) out.notes.push_back(fmt::format("{} meshes merged into one", parts.size()));
  if (mesh.indices.empty()) throw std::runtime_error("the file contains no triangles");
  stage.finish();
  return out;
}

void validate_mesh(const TriangleMeshDesc& mesh) {
  if (mesh.indices.size() % 3 != 0)
    throw std::runtime_error(fmt::format("{} indices is not a multiple of 3", mesh.indices.size()));
  const size_t n = mesh.positions.size();
  for (size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= n)
      throw std::runtime_error(
          fmt::format("index {} (value {}) is out of range: the mesh has {} vertices", i, mesh.indices[i], n));
  for (size_t i = 0; i < n; ++i) {
    const Vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw std::runtime_error(fmt::format("vertex {} has a non-finite coordinate", i));
  }
  if (!mesh.normals.empty() && mesh.normals.size() != n)
    throw std::runtime_error(fmt::format("{} normals for {} vertices", mesh.normals.size(), n));
  if (!mesh.uvs.empty() && mesh.uvs.size() != n)
    throw std::runtime_error(fmt::format("{} uvs for {} vertices", mesh.uvs.size(), n));
  for (const Vec3& nn : mesh.normals)
    if (!std::isfinite(nn.x) || !std::isfinite(nn.y) || !std::isfinite(nn.z))
      throw std::runtime_error("a normal has a non-finite component");
}

}  // namespace dermis
