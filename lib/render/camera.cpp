#include "render/camera.hpp"

#include <algorithm>
#include <cmath>

#include "core/suggest.hpp"
#include "render/renderer.hpp"

namespace rscene::render {
namespace {
constexpr double kPi = 3.14159265358979323846;
double radians(double d) { return d * kPi / 180; }
// The automatic view's aspect when no size is known yet: the default image's.
constexpr double kDefaultAspect = double(kDefaultImageWidth) / kDefaultImageHeight;

// The orientation looking along `forward` (unit) with +z up: local +x
// forward, +y left, +z up (the scene's camera frame).  Straight up or
// down, +y is the image's up.
Eigen::Quaterniond lookingAlong(const Eigen::Vector3d& forward) {
  Eigen::Vector3d left = Eigen::Vector3d::UnitZ().cross(forward);
  if (left.norm() < 1e-9) left = Eigen::Vector3d::UnitY().cross(forward);
  left.normalize();
  Eigen::Vector3d up = forward.cross(left);
  Eigen::Matrix3d r;
  r.col(0) = forward, r.col(1) = left, r.col(2) = up;
  return Eigen::Quaterniond(r).normalized();
}
}  // namespace

bool chooseCamera(const RenderScene& scene, const std::string& selector, Camera& out, std::string* error) {
  if (selector == "auto") {
    out = autoCamera(scene, kDefaultAspect);
    return true;
  }
  if (selector.empty()) {
    for (const Camera& c : scene.cameras)
      if (c.enabled) {
        out = c;
        return true;
      }
    out = autoCamera(scene, kDefaultAspect);
    return true;
  }
  for (const Camera& c : scene.cameras)
    if (c.path == selector || c.id == selector) {
      out = c;
      return true;
    }
  if (error) {
    // Name the closest camera, or the ones there are (an editor's scene has few).
    // Paths compare by their last part: a shared /World/ is no likeness.
    auto last = [](std::string_view p) { return p.substr(p.rfind('/') + 1); };
    const bool isPath = selector.find('/') != std::string::npos;
    std::vector<std::string_view> names;
    for (const Camera& c : scene.cameras) names.push_back(isPath ? last(c.path) : std::string_view(c.id));
    *error = "no camera with path or id '" + selector + "'";
    std::string near = closestName(isPath ? last(selector) : std::string_view(selector), names);
    if (!near.empty()) {
      const Camera& c = scene.cameras[static_cast<std::size_t>(std::find(names.begin(), names.end(), near) - names.begin())];
      near = isPath ? c.path : c.id;
      *error += "; did you mean '" + near + "'?";
    } else if (scene.cameras.empty()) {
      *error += "; the scene has no camera (leave out --camera, or use --camera auto)";
    } else {
      std::string list;
      for (std::size_t i = 0; i < scene.cameras.size() && i < 8; ++i)
        list += (i ? ", " : "") + scene.cameras[i].path;
      *error += "; its cameras: " + list + (scene.cameras.size() > 8 ? ", ..." : "");
    }
  }
  return false;
}

Camera autoCamera(const RenderScene& scene, double aspect) {
  Camera c;
  c.path = "auto";
  c.verticalFov = 50;
  c.width = c.height = 0;  // no size of its own: the caller's
  Eigen::AlignedBox3d box = scene.bounds;
  if (box.isEmpty()) box = Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, 0), Eigen::Vector3d(1, 1, 1));
  Eigen::Vector3d center = box.center();
  double radius = std::max(0.5 * box.diagonal().norm(), 0.25);
  double vfov = radians(c.verticalFov);
  double hfov = 2 * std::atan(std::tan(vfov / 2) * aspect);
  double distance = radius / std::sin(std::min(vfov, hfov) / 2) * 1.3;
  // From the front-left and a little above (azimuth -135 degrees from +x,
  // 15 up) so the horizon and some sky stay in the frame.
  const double pitch = radians(15);
  Eigen::Vector3d toCamera = Eigen::Vector3d(-std::cos(pitch) * std::cos(radians(45)),
                                             -std::cos(pitch) * std::sin(radians(45)), std::sin(pitch));
  c.world.position = center + distance * toCamera;
  c.world.orientation = lookingAlong(-toCamera);
  c.local = c.world;
  c.nearPlane = std::max(0.01, (distance - radius) * 0.2);
  c.farPlane = (distance + radius) * 50 + 500;
  return c;
}

std::string lookAtProblem(const Eigen::Vector3d& position, const Eigen::Vector3d& target, double fovDeg) {
  if (!position.allFinite()) return "the camera position is not a finite point";
  if (!target.allFinite()) return "the look-at point is not a finite point";
  if ((target - position).norm() < 1e-9) return "the camera position and the look-at point are the same point";
  if (!std::isfinite(fovDeg) || fovDeg < 1 || fovDeg > 175) return "the field of view must be 1 to 175 degrees";
  return "";
}

Camera lookAtCamera(const Eigen::Vector3d& position, const Eigen::Vector3d& target, double fovDeg, int width,
                    int height) {
  Camera c;
  c.path = "look-at";
  c.verticalFov = fovDeg;
  c.width = width;
  c.height = height;
  c.enabled = true;
  Eigen::Vector3d along = target - position;
  double distance = along.norm();
  c.world.position = position;
  c.world.orientation = lookingAlong(along / distance);
  c.local = c.world;
  c.nearPlane = std::clamp(0.01 * distance, 0.005, 0.1);
  c.farPlane = std::max(1000.0, 100 * distance);
  return c;
}

Eigen::Matrix4d viewMatrix(const Camera& camera) {
  Eigen::Matrix3d r = camera.world.orientation.normalized().toRotationMatrix();
  Eigen::Vector3d forward = r.col(0), up = r.col(2);
  Eigen::Vector3d right = forward.cross(up);
  Eigen::Matrix4d v = Eigen::Matrix4d::Identity();
  v.block<1, 3>(0, 0) = right.transpose();
  v.block<1, 3>(1, 0) = up.transpose();
  v.block<1, 3>(2, 0) = -forward.transpose();
  v.block<3, 1>(0, 3) = -v.block<3, 3>(0, 0) * camera.world.position;
  return v;
}

double effectiveVerticalFov(const Camera& camera, double aspect) {
  double vfov = std::clamp(camera.verticalFov, 1.0, 175.0);
  if (camera.horizontalFov > 0) {
    double h = radians(std::clamp(camera.horizontalFov, 1.0, 175.0));
    vfov = std::clamp(2 * std::atan(std::tan(h / 2) / aspect) * 180 / kPi, 1.0, 175.0);
  }
  return vfov;
}

Eigen::Matrix4d projectionMatrix(const Camera& camera, double aspect) {
  double n = camera.nearPlane, f = camera.farPlane;
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  if (camera.projection == "orthographic") {
    double h = std::max(camera.orthoScale, 1e-6) / 2, w = h * aspect;
    p(0, 0) = 1 / w;
    p(1, 1) = 1 / h;
    p(2, 2) = -2 / (f - n);
    p(2, 3) = -(f + n) / (f - n);
    p(3, 3) = 1;
    return p;
  }
  double t = 1 / std::tan(radians(effectiveVerticalFov(camera, aspect)) / 2);
  p(0, 0) = t / aspect;
  p(1, 1) = t;
  p(2, 2) = -(f + n) / (f - n);
  p(2, 3) = -2 * f * n / (f - n);
  p(3, 2) = -1;
  return p;
}

Eigen::Matrix4d intrinsicProjection(double fx, double fy, double cx, double cy, int width, int height, double n,
                                    double f) {
  // GL eye space: x right (= -y of the camera frame), y up (= z), -z
  // forward, so u = cx + fx * xe / -ze and NDC x = 2u/width - 1; v grows
  // downwards while NDC y grows upwards.
  double w = width, h = height;
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = 2 * fx / w;
  p(0, 2) = 1 - 2 * cx / w;
  p(1, 1) = 2 * fy / h;
  p(1, 2) = 2 * cy / h - 1;
  p(2, 2) = -(f + n) / (f - n);
  p(2, 3) = -2 * f * n / (f - n);
  p(3, 2) = -1;
  return p;
}

bool boxInFrustum(const Eigen::Matrix4d& m, const Eigen::AlignedBox3d& b) {
  if (b.isEmpty()) return false;
  Eigen::Vector4d c[8];
  for (int i = 0; i < 8; ++i) c[i] = m * b.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)).homogeneous();
  for (int plane = 0; plane < 6; ++plane) {
    int axis = plane / 2;
    double s = plane % 2 ? -1 : 1;
    bool allOut = true;
    for (int i = 0; i < 8 && allOut; ++i)
      if (s * c[i][axis] <= c[i].w()) allOut = false;
    if (allOut) return false;
  }
  return true;
}

bool seesAnything(const RenderScene& scene, const Camera& camera, double aspect) {
  Eigen::Matrix4d m = projectionMatrix(camera, aspect) * viewMatrix(camera);
  auto visible = [&](const Eigen::AlignedBox3d& b) { return boxInFrustum(m, b); };
  for (const Drawable& d : scene.drawables)
    if (visible(d.bounds)) return true;
  for (const TerrainMesh& t : scene.terrains)
    if (visible(t.bounds)) return true;
  for (const Instanced& b : scene.instanced)
    if (visible(b.bounds)) return true;
  for (const PointBatch& p : scene.pointClouds)
    if (visible(p.bounds)) return true;
  return false;
}

}  // namespace rscene::render
