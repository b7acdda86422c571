// The ANYmal C scene and view of passes_robot_test.cpp, shared with its
// benchmark (bench/render/passes_robot.cpp): ../shared's robot standing on
// a ground under a shadowing sun, seen from 1.7 m front-right at 640x480
// with RGB, depth and segmentation; frame f of n slides the whole robot
// 0.3 m along -y, a new pose per frame as a trajectory gives.  The test
// asserts what the images show, the benchmark times the frames.
#pragma once
#include <filesystem>
#include <memory>
#include <string>

#include "asset/cache.hpp"
#include "core/loader.hpp"
#include "render/view.hpp"
#include "robot/sensors.hpp"

namespace rscene::render::test {

inline std::filesystem::path anymalUrdf() {
  return std::filesystem::path(RSCENE_SHARED_DIR) / "corpus/robots/anymal_c/urdf/anymal.urdf";
}

// Built on the heap: the renderer's options point at the asset cache.
struct AnymalScene {
  asset::AssetCache assets;
  Scene model;
  RenderScene scene;
  RenderOptions options;
  std::unique_ptr<Renderer> renderer;
  robot::BodyPoses rest;
};

// Null when the scene does not build (the reason is in `diags`).
inline std::unique_ptr<AnymalScene> makeAnymalScene(Diagnostics& diags) {
  LoadResult loaded = parse(
      "raisim_engine_scene 1\n"
      "environment 0.38 0.38 0.38 0.15 0.16 0.2 0 true true 10 - backgroundMode=rayrai_sky\n"
      "material ground 0.45 0.47 0.5 1 0 0.8 0 0 0 0 false - - - - - - id=ground\n"
      "light /World/Sun -0.4 0.3 -1 3 type=directional shadows=true\n"
      "object /World/Ground ground 0 0 0 1 0 0 0 50 50 1 1 0 0 default ground false true true - static true 1 "
      "18446744073709551615 semanticClass=floor\n"
      "articulated_resource anymal ANYmal " +
      anymalUrdf().string() +
      "\n"
      "articulated /World/Anymal anymal 0 0 0.54 1 0 0 0 true true semanticClass=robot generalizedCoordinate=0,0,0.54,"
      "1,0,0,0,0.03,0.4,-0.8,-0.03,0.4,-0.8,0.03,-0.4,0.8,-0.03,-0.4,0.8\n");
  if (!loaded.ok()) return nullptr;
  auto s = std::make_unique<AnymalScene>();
  if (!buildRenderScene(loaded.document, {}, s->model, s->scene, diags, {}, &s->assets)) return nullptr;
  s->options.assets = &s->assets;
  s->renderer = Renderer::create(s->scene, s->options, diags);
  if (!s->renderer) return nullptr;
  s->rest = robot::restPoses(s->model, s->scene.robotModels);
  return s;
}

// From 1.7 m front-right, 0.8 m up, looking at the robot (render.bats).
inline View anymalView() {
  View v;
  v.name = "/World/Cam";
  v.camera.world.position = Eigen::Vector3d(1.2, -1.2, 0.8);
  v.camera.world.orientation = Eigen::Quaterniond(0.37947, -0.11947, 0.04949, 0.91612).normalized();
  v.camera.verticalFov = 50;
  v.camera.nearPlane = 0.05;
  v.camera.farPlane = 100;
  v.camera.width = 640;
  v.camera.height = 480;
  v.camera.projection = "perspective";
  v.passes = {Pass::Color, Pass::Depth, Pass::Segmentation};
  return v;
}

// Poses frame f of `frames` (the robot 0.3 f / (frames - 1) m along -y)
// and updates the renderer's poses (the shadow map is redrawn).
inline void poseFrame(AnymalScene& s, int f, int frames) {
  robot::BodyPoses p = s.rest;
  for (Pose& link : p.robotLinks[0]) link.position.y() -= 0.3 * f / (frames - 1);
  BodyPoseView pv;
  pv.robotLinks = &p.robotLinks;
  poseScene(s.scene, pv);
  s.renderer->updatePoses();
}

}  // namespace rscene::render::test
