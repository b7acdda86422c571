// Where each shadow map looks (CPU, no GL): the orthographic box of a
// directional light fitted to the part of the scene the view sees, the
// perspective frustum of a spot light, the six faces of a point light's
// cube, and the packing of all maps into one depth atlas.  gl_lights.cpp
// draws them; shader_lights.cpp reads them back with the same conventions.
#pragma once
#include <Eigen/Geometry>
#include <vector>

namespace rscene::render {

// One shadow map's projection.  `viewProj` maps world points to clip space
// (GL conventions: depth increases away from the light).  Depth runs from
// `nearPlane` to `farPlane` metres along the light (orthographic: from the
// box's near face).  `texelWorld`: the world size of one texel
// (perspective: per metre of distance along the light's axis).
struct ShadowView {
  Eigen::Matrix4d viewProj = Eigen::Matrix4d::Identity();
  double nearPlane = 0.05, farPlane = 1;
  double texelWorld = 0;
  bool perspective = false;
  bool empty = true;  // nothing to shadow (the view sees no receiver)
};

// A directional light travelling along unit `dir`: the light-space box
// that covers what `cameraViewProj` sees of `receivers` (the casters'
// box carried down along the light to `floorZ`), deep enough towards the
// light to hold every caster in `casters`, widened by `marginTexels` of a
// `resolution`-texel map.
ShadowView fitDirectionalShadow(const Eigen::Vector3d& dir, const Eigen::Matrix4d& cameraViewProj,
                                const Eigen::AlignedBox3d& casters, double floorZ, int resolution,
                                double marginTexels);
// The casters' box, with the points where their shadows land: each corner
// carried along `dir` down to `floorZ`, at most `maxDrop` metres.
Eigen::AlignedBox3d withShadowFootprint(const Eigen::AlignedBox3d& casters, const Eigen::Vector3d& dir,
                                        double floorZ, double maxDrop = 50);
// shadowUseCustomPosition: a box of half size `halfSize` around `centre`;
// the light's eye is farPlane/2 before the centre, depth nearPlane..farPlane from it.
ShadowView customDirectionalShadow(const Eigen::Vector3d& dir, const Eigen::Vector3d& centre, double halfSize,
                                   double nearPlane, double farPlane, int resolution);
// A perspective map from `eye` along unit `dir` covering a cone of
// `halfAngleDeg` (< 90).
ShadowView perspectiveShadow(const Eigen::Vector3d& eye, const Eigen::Vector3d& dir, double halfAngleDeg,
                             double nearPlane, double farPlane, int resolution);

// Cube faces: face k looks along kCubeForward[k] with kCubeRight[k] to
// the right and up = right x forward; its projection is a 90-degree
// frustum widened by 1/faceScale so that filtering near a face's edge
// stays inside the face.  shader_lights.cpp holds the same tables.
inline constexpr int kCubeForward[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
inline constexpr int kCubeRight[6][3] = {{0, 1, 0}, {0, -1, 0}, {-1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}};
ShadowView cubeFaceShadow(const Eigen::Vector3d& eye, int face, double nearPlane, double farPlane, double faceScale,
                          int resolution);
// faceScale leaving `marginTexels` texels of a `resolution`-texel face on each side.
double cubeFaceScale(int resolution, double marginTexels);

// Shelf packing of rectangles (width, height in texels) into a square of
// `side` texels: origins in the same order; false when they do not fit.
bool packAtlas(const std::vector<Eigen::Vector2i>& sizes, int side, std::vector<Eigen::Vector2i>& origins);

}  // namespace rscene::render
