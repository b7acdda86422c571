// Triangle meshes in the renderer's vertex layout: the unit primitives it
// scales to physical size, and the parts of mesh files (read by lib/asset).
#pragma once
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "asset/mesh.hpp"

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
// A grass blade: base width 1 (x in [-0.5, 0.5]) at z = 0 tapering to a tip
// at z = 1 that leans to y = 1 along y = z^2; 5 vertices, 3 triangles, one
// side (drawn double-sided).  Instances scale it by (width, lean, height).
MeshData grassBlade();
// Per-vertex colors of grassBlade(): darker at the root, as grass is where
// the blades shade each other.
std::vector<Eigen::Vector4f> grassBladeShading();

// A part of a mesh file (lib/asset) in the renderer's vertex layout.
MeshData interleave(const asset::MeshPart& part);

}  // namespace rscene::render
