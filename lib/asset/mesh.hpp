// Mesh files through assimp (glTF/GLB, OBJ+MTL, STL, DAE, FBX, ...), read
// through a FileSystem: the mesh file and everything it references (MTL,
// glTF buffers, textures) come from the same interface, so tests run on an
// in-memory disk and a device or FIFO named as a mesh is refused.
//
// One import serves both users: the simulator asks for Geometry (one part
// of positions and triangles), the renderer for Surface (per material:
// normals, texture coordinates, base colour, base-colour texture).  Node
// transforms are applied: coordinates are in the file's frame.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "asset/image.hpp"
#include "core/filesystem.hpp"

namespace rscene::asset {

enum class MeshContent { Geometry, Surface };

struct MeshMaterial {
  std::array<float, 4> baseColor{1, 1, 1, 1};  // linear RGBA, opacity folded into alpha
  float metallic = 0, roughness = 0.6f;
  std::shared_ptr<const Image> texture;  // base colour; null when none or not readable
};

struct MeshPart {
  std::vector<float> positions;  // x y z per vertex
  std::vector<float> normals;    // Surface: x y z per vertex
  std::vector<float> uvs;        // Surface: u v per vertex, v = 0 at the top row (OpenGL)
  std::vector<std::uint32_t> indices;  // three per triangle
  MeshMaterial material;         // Surface only
  std::size_t vertexCount() const { return positions.size() / 3; }
};

struct Mesh {
  std::vector<MeshPart> parts;        // Geometry: exactly one
  std::vector<std::string> warnings;  // e.g. "texture wood.jpg is not drawn: ..."
  std::size_t triangleCount() const;
};

struct AssetLimits {
  std::uint64_t maxFileBytes = FileSystem::kDefaultMaxBytes;  // per file read
  ImageLimits image;
};

// Reads a texture by its resolved path (AssetCache shares them).
using TextureSource = std::function<std::shared_ptr<const Image>(const std::string& path, std::string* error)>;

// False with `error` ("no such file", "no triangles in mesh file", or
// assimp's reason) when `path` gives no triangles.
bool loadMesh(const FileSystem& fs, const std::string& path, MeshContent content, Mesh& out, std::string* error,
              const AssetLimits& limits = {}, const TextureSource& textures = nullptr);

}  // namespace rscene::asset
