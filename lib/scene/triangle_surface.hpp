// A triangle surface as a file lists it: vertices in file order and
// triangles as indices into them.  A deformable record's particles are
// these vertices (scene/deformable_model.hpp); lib/asset reads OBJ files
// into it (asset/obj_surface.hpp).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace rscene {

struct TriangleSurface {
  std::vector<std::array<double, 3>> vertices;           // file order, the file's frame
  std::vector<std::array<std::uint32_t, 3>> triangles;   // zero-based
};

// Reads the surface at a resolved path; false with a sentence in `error`.
// The tools pass lib/asset's OBJ reader over their file system, so the
// scene model judges a deformable with its mesh without reading files.
using SurfaceReader = std::function<bool(const std::string& path, TriangleSurface& out, std::string& error)>;

// Whether the mesh file at a resolved path reads as a mesh with triangles
// (lib/asset's assimp reader); false with a sentence in `error`.
using MeshReader = std::function<bool(const std::string& path, std::string& error)>;

}  // namespace rscene
