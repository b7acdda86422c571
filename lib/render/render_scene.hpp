// What the renderer draws, read from a Document: materials, drawables at
// physical size in world space, lights, cameras, terrain meshes, instanced
// batches, point clouds and the environment.  Records it cannot draw are
// counted in `skipped`.  Asset paths are resolved (core/assets.hpp) but not
// opened here; the renderer opens them.
//
// This is a render-side adapter over the Document (typed by the schema
// table through RecordView).  It will read lib/core/scene.hpp's typed view
// where that covers a record kind.
#pragma once
#include <Eigen/Geometry>
#include <map>
#include <string>
#include <vector>

#include "core/diagnostic.hpp"
#include "core/document.hpp"

namespace rscene::render {

struct Material {
  std::string id;
  Eigen::Vector4f color{0.55f, 0.62f, 0.72f, 1.f};
  float metallic = 0;
  float roughness = 0.55f;
  Eigen::Vector3f emissive = Eigen::Vector3f::Zero();  // color x strength
  bool doubleSided = false;
  bool blend = false;           // alphaMode=blend or alpha < 1
  std::string albedoTexture;    // resolved path, empty when none
  std::uint32_t line = 0;
  bool isDefault = true;        // engine_default: meshes keep their own materials
};

enum class Shape { Box, Sphere, Cylinder, Capsule, Ground, Mesh };

struct Drawable {
  Shape shape = Shape::Box;
  // Unit shape -> world: boxes are unit cubes, spheres unit radius,
  // cylinders radius 1 height 1, the ground a unit square; meshes per-axis
  // scaled.  Capsules keep their own radius/height (not scalable).
  Eigen::Affine3d world = Eigen::Affine3d::Identity();
  double capsuleRadius = 0, capsuleHeight = 0;
  std::string meshPath;   // resolved
  std::string meshWritten;
  int material = 0;
  bool castShadow = true;
  std::uint32_t line = 0;
  Eigen::AlignedBox3d bounds;  // world-space, for framing and visibility
};

enum class LightType { Directional, Point, Spot, Area };

struct Light {
  LightType type = LightType::Directional;
  Eigen::Vector3d direction{0, 0, -1};  // the way the light travels, unit
  Eigen::Vector3d position{0, 0, 3};
  Eigen::Vector3f color{1, 1, 1};       // color x intensity
  Eigen::Vector3f attenuation{1, 0.04f, 0.012f};
  float coneDegrees = 30, innerConeDegrees = 18;
  float range = 0;
  Eigen::Vector2f areaSize{1, 1};
  bool shadows = false;
};

struct Camera {
  std::string path, id;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // looks along local +x, local +z up
  double verticalFov = 52, horizontalFov = 0;
  double nearPlane = 0.05, farPlane = 100;
  int width = 0, height = 0;
  bool orthographic = false;
  double orthoScale = 10;  // full height of the view in metres
  bool enabled = true;
  std::uint32_t line = 0;
};

struct Terrain {
  int xSamples = 0, ySamples = 0;
  std::vector<Eigen::Vector3f> positions;  // world space
  std::vector<Eigen::Vector4f> colors;
  std::vector<bool> holes;
  int material = 0;
  Eigen::AlignedBox3d bounds;
};

struct Instanced {
  Shape shape = Shape::Box;
  std::string meshPath;
  std::vector<Eigen::Affine3d> worlds;  // unit shape -> world
  std::vector<Eigen::Vector4f> colors;
  int material = 0;
  std::uint32_t line = 0;
  Eigen::AlignedBox3d bounds;
};

struct PointCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector4f> colors;
  float pointSize = 1;
  Eigen::AlignedBox3d bounds;
};

enum class Background { PlainColor, Hdr, Sky };
enum class ToneMap { Linear, Aces, Filmic, AgX, Unreal };

struct Environment {
  Eigen::Vector3f background{0.38f, 0.38f, 0.38f};
  Eigen::Vector3f ambient{0.15f, 0.16f, 0.20f};
  float fogDensity = 0;
  Eigen::Vector3f fogColor{0.66f, 0.78f, 0.96f};
  bool shadows = true;
  float exposure = 1, gamma = 2.2f;
  Background mode = Background::Sky;
  std::string hdrPath;  // resolved
  std::uint32_t hdrLine = 0;
  ToneMap toneMap = ToneMap::Aces;
  Eigen::Vector3d sunDirection{0, 0, 1};  // towards the sun, unit
  float cloudCoverage = 0;
  bool overcast = false, night = false;
};

struct SceneOptions {
  std::string sceneDir = ".";   // directory that relative asset paths start from
};

struct RenderScene {
  std::vector<Material> materials;  // [0] is engine_default
  std::vector<Drawable> drawables;
  std::vector<Light> lights;
  std::vector<Camera> cameras;
  std::vector<Terrain> terrains;
  std::vector<Instanced> instanced;
  std::vector<PointCloud> pointClouds;
  Environment environment;
  std::map<std::string, int> skipped;  // record kind -> count
  Eigen::AlignedBox3d bounds;          // everything visible but the ground
  bool hasGround = false;
};

// Fills `out`; diagnostics are warnings only (the Document already loaded).
void buildRenderScene(const Document& doc, const SceneOptions& options, RenderScene& out, Diagnostics& diags);

}  // namespace rscene::render
