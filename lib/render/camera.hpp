// Camera choice and projection: the scene's first enabled camera, one named
// by path or id, or an automatic three-quarter view framing everything
// visible.  Cameras are the scene view's (scene/scene.hpp): world pose,
// looking along local +x with local +z up (compat-notes.md).
#pragma once
#include <Eigen/Geometry>
#include <string>

#include "render/render_scene.hpp"

namespace rscene::render {

// `selector`: "" (first enabled camera, else auto), "auto", or a camera's
// path or id.  False with `error` when the named camera does not exist.
bool chooseCamera(const RenderScene& scene, const std::string& selector, Camera& out, std::string* error);

// Three-quarter view (from -x,-y, 15 degrees up) framing scene.bounds.
Camera autoCamera(const RenderScene& scene, double aspect);

Eigen::Matrix4d viewMatrix(const Camera& camera);
Eigen::Matrix4d projectionMatrix(const Camera& camera, double aspect);
// Vertical field of view actually used, degrees (horizontalFov>0 wins).
double effectiveVerticalFov(const Camera& camera, double aspect);

// Whether a world-space box may be seen through clip-space matrix
// `viewProj` (false only when all eight corners lie beyond one clip plane).
bool boxInFrustum(const Eigen::Matrix4d& viewProj, const Eigen::AlignedBox3d& box);

// Whether any drawable, terrain, batch or point cloud (the ground included)
// has bounds inside the camera's frustum.
bool seesAnything(const RenderScene& scene, const Camera& camera, double aspect);

}  // namespace rscene::render
