// Triangle meshes read with assimp (OBJ, STL, glTF/GLB, DAE and the rest
// assimp knows), flattened into one vertex and index list in the file's
// frame (node transforms applied).
#pragma once
#include <string>
#include <vector>

namespace rscene::sim {

struct TriangleMesh {
  std::vector<double> vertices;  // x,y,z per vertex
  std::vector<int> indices;      // three per triangle
};

// False with `error` set ("cannot read ...: reason") on failure.
bool loadMesh(const std::string& path, TriangleMesh& mesh, std::string& error);

}  // namespace rscene::sim
