// Robots as the renderer draws them: every visual element of every link of
// an articulated system, placed at its link's world pose (robot::linkPoses:
// the one reading of a robot's state that sim and validate share), added to
// a RenderScene as ordinary drawables so that they batch, cull, cast
// shadows and frame the automatic camera like any other body.
//
// Colours: a visual's URDF material colour (or MJCF rgba), with the
// material's texture when it names one; a mesh without one keeps its own
// materials and textures (COLLADA, glTF, OBJ+MTL); a primitive without one
// is drawn in kRobotGrey.
#pragma once
#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "asset/cache.hpp"
#include "render/render_scene.hpp"
#include "robot/model.hpp"

namespace rscene::render {

// The colour of a robot primitive whose file gives none.
inline const Eigen::Vector4f kRobotGrey(0.6f, 0.6f, 0.62f, 1.0f);

// Side, in metres, of the magenta box drawn for a robot's missing mesh with
// --allow-missing-assets (a scene object's is its own scale).
inline constexpr double kRobotPlaceholderSide = 0.1;

class RobotDrawer {
 public:
  // Meshes are read through `assets` for their bounds (framing, culling);
  // the renderer, given the same cache, reads none of them again.
  RobotDrawer(RenderScene& out, asset::AssetCache& assets) : out_(out), assets_(assets) {}

  // Adds the visuals of `model` with its links at `poses` (indexed like
  // model.links, world frame), attached to the links of robot `robot`
  // (its index in Scene::articulated), in legend entry `segment`.
  // Returns the number of drawables added.
  std::size_t add(const robot::Model& model, const std::vector<Pose>& poses, int robot = -1, int segment = -1);

 private:
  int materialFor(const robot::Visual& v, const std::string& file);
  // The mesh file's bounds in its own frame; empty when it cannot be read
  // (the renderer reports it, with the visual's file and line).
  const Eigen::AlignedBox3d& meshBounds(const std::string& path);

  RenderScene& out_;
  asset::AssetCache& assets_;
  std::map<std::tuple<float, float, float, float, std::string>, int> materials_;
  std::map<std::string, Eigen::AlignedBox3d> meshBounds_;
};

}  // namespace rscene::render
