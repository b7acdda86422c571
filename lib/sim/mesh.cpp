#include "sim/mesh.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>

namespace rscene::sim {
namespace {

void collect(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent, TriangleMesh& out) {
  aiMatrix4x4 m = parent * node->mTransformation;
  for (unsigned i = 0; i < node->mNumMeshes; ++i) {
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[i]];
    int base = static_cast<int>(out.vertices.size() / 3);
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      aiVector3D p = m * mesh->mVertices[v];
      out.vertices.insert(out.vertices.end(), {p.x, p.y, p.z});
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines carry no volume
      for (int k = 0; k < 3; ++k) out.indices.push_back(base + static_cast<int>(face.mIndices[k]));
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c) collect(scene, node->mChildren[c], m, out);
}

}  // namespace

bool loadMesh(const std::string& path, TriangleMesh& mesh, std::string& error) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode) {
    error = "cannot read mesh '" + path + "': " + importer.GetErrorString();
    return false;
  }
  mesh = {};
  collect(scene, scene->mRootNode, aiMatrix4x4(), mesh);
  if (mesh.vertices.empty()) {
    error = "mesh '" + path + "' has no vertices";
    return false;
  }
  return true;
}

}  // namespace rscene::sim
