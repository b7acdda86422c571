// Deformables and granular records as rscene-render draws them along a
// simulation: a deformable's OBJ surface in file order (the vertices are
// the particles rscene-sim moves and writes to the trajectory), its normals
// recomputed whenever the vertices move, and granular particles whose
// centres a trajectory frame replaces.  Geometry only, no GL: the
// renderer uploads what these return (renderer.cpp).
#pragma once
#include <Eigen/Geometry>
#include <vector>

#include "asset/obj_surface.hpp"
#include "render/mesh.hpp"
#include "render/render_scene.hpp"

namespace rscene::render {

// The surface of `obj` carried to the world by `world` (the record's pose
// times its scale); `drawable` left for the caller.
DeformedSurface surfaceFromObj(const asset::ObjSurface& obj, const Eigen::Affine3d& world);

// The surface in the renderer's vertex layout (x y z, nx ny nz, u v; uv 0:
// the OBJ surface carries no texture coordinates) with the OBJ's triangles
// as indices.  Each vertex's normal is the sum of its triangles' unscaled
// cross products (area-weighted, so a sliver barely tilts it), normalised;
// a vertex of no triangle, or of triangles of no area, gets +z.
MeshData surfaceMesh(const DeformedSurface& surface);
// Only the vertex floats of surfaceMesh() (what a frame re-uploads), into `out`.
void surfaceVertices(const DeformedSurface& surface, std::vector<float>& out);

// Applies what frames gave to the drawn surfaces and granular batches
// (those whose ParticlePositions version moved and that gave a granular
// record's count, or at least a deformable's OBJ vertices: the points past
// them fill a volume and are not drawn), updating their bounds and
// versions.  True when something moved.
bool poseParticles(RenderScene& scene, const robot::ParticlePositions& particles);

}  // namespace rscene::render
