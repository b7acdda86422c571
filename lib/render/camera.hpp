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

// The look-at form (rscene-render --camera-position --look-at --fov): a
// camera at `position` looking at `target` with the scene's up, +z (gravity
// is -z), vertical field of view fovDeg, for a width x height image.  Clip
// planes from the distance: near 1 % of it (0.005 to 0.1 m), far 100 times
// it and at least 1000 m.  Looking straight up or down the image's up is
// +y.  Check lookAtProblem() first: equal or non-finite points make no
// camera.
Camera lookAtCamera(const Eigen::Vector3d& position, const Eigen::Vector3d& target, double fovDeg, int width,
                    int height);
// Why these values make no look-at camera ("" when they do): a
// non-finite coordinate, position == target, fovDeg outside [1, 175].
std::string lookAtProblem(const Eigen::Vector3d& position, const Eigen::Vector3d& target, double fovDeg);

Eigen::Matrix4d viewMatrix(const Camera& camera);
Eigen::Matrix4d projectionMatrix(const Camera& camera, double aspect);
// The perspective projection of pinhole intrinsics in pixels for a
// width x height image.  Image coordinates (u right, v down) start at the
// top-left corner of the top-left pixel, so pixel (col, row) covers
// [col, col+1) x [row, row+1) and its centre is (col + 0.5, row + 0.5):
// cx = width/2, cy = height/2 is the image's centre.  A point (x forward,
// y left, z up) in the camera frame projects to u = cx - fx*y/x,
// v = cy - fy*z/x.  (OpenCV/ROS calibrations put pixel centres on integers:
// add 0.5 to their cx and cy.)
Eigen::Matrix4d intrinsicProjection(double fx, double fy, double cx, double cy, int width, int height,
                                    double nearPlane, double farPlane);
// Vertical field of view actually used, degrees (horizontalFov>0 wins).
double effectiveVerticalFov(const Camera& camera, double aspect);

// Whether a world-space box may be seen through clip-space matrix
// `viewProj` (false only when all eight corners lie beyond one clip plane).
bool boxInFrustum(const Eigen::Matrix4d& viewProj, const Eigen::AlignedBox3d& box);

// Whether any drawable, terrain, batch or point cloud (the ground included)
// has bounds inside the camera's frustum.
bool seesAnything(const RenderScene& scene, const Camera& camera, double aspect);

}  // namespace rscene::render
