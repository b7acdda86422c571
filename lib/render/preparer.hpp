// rscene-render's Preparer (buildRenderScene, render_scene.hpp): turns the
// scene model into what the renderer draws, one class whose jobs live in
// files of their own: materials, lights and the look (render_scene.cpp),
// bodies, robots and wires (prepare_bodies.cpp), terrain, foliage and
// instanced visuals (prepare_terrain.cpp), deformables, granular media and
// point clouds (prepare_particles.cpp).  Internal to lib/render.
#pragma once
#include "render/render_scene.hpp"

#include "core/codes.hpp"
#include "render/render_effects.hpp"
#include "scene/reader.hpp"
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <unordered_map>
#include "asset/obj_surface.hpp"
#include "render/deformed_surface.hpp"
#include "render/render_bodies.hpp"
#include "render/render_foliage.hpp"
#include "render/robot_drawables.hpp"
#include "robot/check.hpp"
#include "robot/instance.hpp"
#include "robot/kinematics.hpp"
#include "core/assets.hpp"
#include "scene/check.hpp"
#include "scene/validate.hpp"
#include "scene/granular.hpp"

namespace rscene::render::preparer_detail {

using Eigen::Affine3d;
using Eigen::Vector3d;
using Eigen::Vector3f;
using Eigen::Vector4d;
using Eigen::Vector4f;

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kMinGroundSize = 200;  // metres: the ground reads as "large" from any camera

// Colours, intensities and other shading inputs as floats the shaders can
// multiply without overflowing: beyond +-1e6 (which tone mapping saturates
// long before) they are drawn as +-1e6, and NaN as 0.  A light of 1e39 was
// infinite in float and turned the lit surfaces black (NaN).
inline constexpr double kMaxShade = 1e6;
inline float shade(double v) { return std::isnan(v) ? 0.f : float(std::clamp(v, -kMaxShade, kMaxShade)); }
inline Vector4f toF(const Vector4d& v) { return {shade(v[0]), shade(v[1]), shade(v[2]), shade(v[3])}; }
inline Vector3f toF(const Vector3d& v) { return {shade(v[0]), shade(v[1]), shade(v[2])}; }
inline Vector3f rgb(const Vector4d& v) { return toF(Vector3d(v.head<3>())); }

inline Shape shapeOf(const std::string& primitive) {
  if (primitive == "sphere") return Shape::Sphere;
  if (primitive == "cylinder") return Shape::Cylinder;
  if (primitive == "capsule") return Shape::Capsule;
  if (primitive == "mesh") return Shape::Mesh;
  if (primitive == "ground" || primitive == "half_space") return Shape::Ground;
  return Shape::Box;
}

// Unit shape -> local frame at physical size (compat-notes.md "Sizes").
inline Vector3d shapeScale(Shape s, const Vector3d& scale, double radius, double height, const Vector3d& boxSize) {
  switch (s) {
    case Shape::Box: return boxSize;
    case Shape::Sphere: return Vector3d::Constant(radius * scale.x());
    case Shape::Cylinder: return {radius * scale.x(), radius * scale.x(), height * scale.z()};
    case Shape::Mesh: return scale;
    default: return Vector3d::Ones();
  }
}

inline Affine3d affine(const Pose& p) {
  Affine3d m = Affine3d::Identity();
  m.translate(p.position);
  m.rotate(p.orientation);
  return m;
}

class Preparer {
 public:
  Preparer(const Document& doc, const Scene& scene, RenderScene& out, Diagnostics& diags, const DrawLimits& limits,
           asset::AssetCache* assets)
      : doc_(doc), s_(scene), out_(out), diags_(diags), limits_(limits), assets_(assets) {}

  bool ok() const { return ok_; }

  void run();

 private:
  std::uint32_t lineOf(int recordIndex) const;

  // Column of a field of a record, for messages about the file it names.
  std::uint32_t columnOf(int recordIndex, std::string_view field) const;
  bool hasField(int recordIndex, std::string_view field) const;
  int materialIndex(const std::string& ref) const;

  // A scene material as the shaders take it.
  RenderMaterial renderMaterial(const Material& src) const;
  void materials();
  void look();

  // The legend entry of a record, added once per record.
  int segment(const char* kind, int recordIndex, const std::string& path, const std::string& id,
              const std::string& semanticClass, std::int64_t instanceId,
              const std::optional<Eigen::Vector4d>& color = std::nullopt);

  // `body` moves it (rscene-render --trajectory): the drawable keeps its
  // transform relative to the body's pose.
  static void attach(Drawable& d, Mount::Kind kind, int index, const Pose& body, int link = -1);

  // `local`: the bounds `world` maps from, when not the unit shape's (a
  // mesh read for its size).
  void addDrawable(Drawable d, const std::optional<Eigen::AlignedBox3d>& local = std::nullopt);
  void object(const Object& o, int index);
  void compound(const Compound& c, int index);
  void light(const Light& src);
  void camera(Camera c);
  void terrainColors();
  Vector4f slotColor(int slot) const;

  // Whether every sample of `src` looks the same: one height, no holes,
  // no per-sample color.  Such a terrain is drawn as its 4 corners.
  static bool uniform(const Terrain& src);

  // Sample indices drawn along an axis of `n` samples: every `step`-th,
  // and always the last, so the drawn terrain keeps its extent.
  static std::vector<int> axisSamples(int n, int step);
  void terrain(const Terrain& src);

  // Indices a record draws: every stride-th (stride < 1 counts as 1), at
  // most `max` of them when max > 0.
  static std::size_t drawnCount(std::size_t total, std::int64_t max, std::int64_t stride);
  void instanced(const InstancedVisual& v);

  // The unit shape's scale for a primitive of extent `size`: box sides and
  // mesh scale as written, sphere/cylinder diameters halved to radii, a
  // grass blade's width, lean and height as written.
  static Vector3d unitScale(Shape shape, const Vector3d& size);

  // Room for `count` more instances under limits_.maxInstances, taken; else
  // RS9014 on the record that asks for them.
  bool reserveInstances(std::uint64_t count, std::uint32_t line, const std::string& kind);

  // The terrain an instanced_visual's terrainBinding names (id or path).
  const Terrain* boundTerrain(const InstancedVisual& v) const;

  // terrainBinding: an instance over the terrain stands on its surface,
  // its z an offset above it; one beyond the terrain's rectangle keeps its
  // position.
  static Vector3d onTerrain(const Terrain& t, Vector3d p);
  static Shape foliageShape(const std::string& primitive);

  // Every enabled terrain_foliage_layer of a drawn terrain, scattered
  // (render_foliage.hpp): visual only, so sensors do not see it.
  void foliage(const Terrain& t);

  // The bounds of a mesh file in its own frame (empty when it cannot be
  // read: the renderer reports that, with the same cache).
  Eigen::AlignedBox3d meshBounds(const std::string& path);

  // deformable: its mesh at rest (the format stores no deformed state), at
  // its pose and scale, in its material.  An OBJ is drawn from its surface
  // in file order (deformed_surface.hpp): the vertices rscene-sim moves, so
  // trajectory frames can replace them.  Any other mesh, or an OBJ that is
  // no usable surface, goes through assimp as other meshes do; a missing
  // mesh is then the renderer's RS5001 (a placeholder box of the record's
  // scale with --allow-missing-assets).
  void deformable(const Deformable& src, std::size_t index);

  // Draws `d` from the OBJ surface of a deformable, when its mesh is one
  // that reads; false (and `d` untouched) otherwise.
  bool objSurface(const Deformable& src, std::size_t index, Drawable& d);

  // granular: its particles (box fill or explicit) as spheres of their
  // radii in the record's frame, sand-colored: materialId names the
  // particles' contact material, not a look.
  void granular(const Granular& g, std::size_t index);

  // The link whose frame is RaiSim's body `body` of robot `robot` (as
  // rscene-sim attaches a wire: body 0 the root, body k the child link of
  // the k-th movable joint in RaiSim's order, fixed links merged away), or
  // -1 when the robot did not load or has no such body.
  int robotBodyLink(std::size_t robot, int body) const;

  // Where a wire end is attached: the body `ref` names (id or path; its
  // record frame, or a robot's link localIndex), or the world when `ref` is
  // empty.  False when it names nothing that is drawn at a known pose.
  bool wireEnd(const std::string& ref, int record, int localIndex, const Vector3d& point, Attachment& at,
               Vector3d& world) const;

  // wire: a dark cylinder of visualizationWidth between its two attachment
  // points, recomputed from both ends when bodies move (poseScene()).  An
  // end that names nothing drawable (the validator's RS3012, a robot
  // without that link) leaves the wire undrawn, counted as skipped.
  void wire(const Wire& w);
  void points(const PointCloud& src);

  // Every visible articulated system at the state its record gives
  // (robot::makeInstance, as sim and validate read it); one load per robot
  // file and one read per mesh file, however many robots share them.
  void robots();
  asset::AssetCache& assets() { return assets_ ? *assets_ : ownAssets_ ? *ownAssets_ : ownAssets_.emplace(); }

  const Document& doc_;
  const Scene& s_;
  RenderScene& out_;
  Diagnostics& diags_;
  const DrawLimits& limits_;
  asset::AssetCache* assets_;
  std::uint64_t instancesDrawn_ = 0;
  std::optional<asset::AssetCache> ownAssets_;  // when prepareScene was given none
  std::vector<std::vector<Pose>> robotLinks_;   // per Scene::articulated: link poses at its record's state
  int wireMaterial_ = -1;
  bool ok_ = true;
  std::unordered_map<std::string, int> materialByRef_;
  std::unordered_map<int, int> segmentOf_;  // record index -> RenderScene::segments
  std::map<int, Vector4f> slotColors_;
};

}  // namespace rscene::render::preparer_detail
