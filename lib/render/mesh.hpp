// Triangle meshes: the unit primitives the renderer scales to physical
// size, and mesh files read through assimp (glTF/GLB, OBJ+MTL, STL, DAE,
// FBX, ...), flattened to world-of-the-file coordinates with their own
// base colors and base-color textures.
#pragma once
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "render/image.hpp"

namespace rscene::render {

struct MeshData {
  std::vector<float> vertices;  // x y z  nx ny nz  u v  (8 floats)
  std::vector<std::uint32_t> indices;
  std::size_t vertexCount() const { return vertices.size() / 8; }
};

MeshData unitBox();                              // [-0.5, 0.5]^3
MeshData unitSphere(int slices = 48, int stacks = 24);  // radius 1
MeshData unitCylinder(int slices = 48);          // radius 1, z in [-0.5, 0.5]
MeshData capsule(double radius, double height, int slices = 48);  // height between hemisphere centres, along z
MeshData unitPlane();                            // [-0.5, 0.5]^2 at z = 0, normal +z

struct MeshPart {
  MeshData mesh;
  Eigen::Vector4f baseColor{1, 1, 1, 1};
  float metallic = 0, roughness = 0.6f;
  Image texture;  // empty when the part has no readable base-color texture
};

struct LoadedMesh {
  std::vector<MeshPart> parts;
  std::vector<std::string> warnings;  // e.g. a texture it could not decode
};

// Reads `path` with assimp.  External textures are resolved against the
// mesh file's folder; embedded ones (glb, "*0") are decoded when PNG.
bool loadMesh(const std::string& path, LoadedMesh& out, std::string* error);

}  // namespace rscene::render
