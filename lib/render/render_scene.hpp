// What the renderer draws, prepared from the typed scene model of lib/scene
// (scene/scene.hpp, shared with rscene-sim and rscene-validate): materials in the form the
// shaders take, drawables at physical size in world space, lights, terrain
// meshes with their colors, instanced batches, point clouds and the look of
// the environment.  Nothing here reads the Document's fields; the Document
// is consulted only for the source line of a record, for messages.
//
// Cameras are the scene view's own rscene::Camera (world pose, looks along
// local +x with local +z up).
#pragma once
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "asset/cache.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "robot/model.hpp"
#include "robot/trajectory_read.hpp"
#include "scene/scene.hpp"

namespace rscene::render {

// A scene material as the shaders take it.  This struct and Look below are
// always filled from the scene model (whose defaults are the schema's), so
// they keep no defaults of their own.
struct RenderMaterial {
  std::string id;
  Eigen::Vector4f color = Eigen::Vector4f::Zero();
  float metallic = 0;
  float roughness = 0;
  Eigen::Vector3f emissive = Eigen::Vector3f::Zero();  // color x strength
  bool doubleSided = false;
  bool blend = false;           // alphaMode=blend or alpha < 1
  std::string albedoTexture;    // resolved path, empty when none
  std::uint32_t line = 0;
  std::uint32_t textureColumn = 0;  // of albedoTexture on `line`, for messages
  std::string file;             // the robot file `line` is in; empty: the scene
  bool isDefault = true;        // engine_default: meshes keep their own materials
};

// GrassBlade: mesh.hpp's grassBlade() (terrain foliage, grass patches).
enum class Shape { Box, Sphere, Cylinder, Capsule, Ground, Mesh, GrassBlade };

// The body a drawable moves with (rscene-render --trajectory): its world
// transform is the body's current pose times `local`.  World: it never
// moves.  Indices as in robot::BodyPoses (Scene::objects, compounds,
// articulated; `link` into the robot model's links).
struct Attachment {
  Mount::Kind kind = Mount::Kind::World;
  int index = -1;
  int link = -1;
  Eigen::Affine3d local = Eigen::Affine3d::Identity();
};

// One entry of the segmentation legend: a record drawn in one flat color
// in segmentation images.  The color is the record's segmentationColor
// when it writes one, else derived from its instanceId (>= 0) within its
// semanticClass, else from its semanticClass, else from its path
// (segmentColor()); never black, the background's.
struct Segment {
  std::uint8_t rgb[3] = {0, 0, 0};
  std::string kind;  // record kind: object, compound, articulated, terrain_region, ...
  std::string path, id, semanticClass;
  std::int64_t instanceId = -1;
  std::uint32_t line = 0;
};

struct Drawable {
  Shape shape = Shape::Box;
  // Unit shape -> world: boxes are unit cubes, spheres unit radius,
  // cylinders radius 1 height 1, the ground a unit square; meshes per-axis
  // scaled.  Capsules keep their own radius/height (not scalable).
  Eigen::Affine3d world = Eigen::Affine3d::Identity();
  double capsuleRadius = 0, capsuleHeight = 0;
  std::string meshPath;   // resolved
  int material = 0;
  bool castShadow = true;
  bool receiveShadow = true;
  bool doubleSided = false;  // both faces drawn whatever the material says (cloth)
  std::uint32_t line = 0;
  std::uint32_t meshColumn = 0;  // of the mesh path field on `line`, for messages
  std::string file;  // the robot file `line` is in (a link's visual); empty: the scene
  // Unit box -> world of the magenta box drawn for a missing mesh with
  // --allow-missing-assets; none: `world` (a scene object's own scale).
  std::optional<Eigen::Affine3d> placeholderWorld;
  Eigen::AlignedBox3d bounds;  // world-space, for framing and visibility
  Eigen::AlignedBox3d localBounds;  // in the frame `world` maps from (bounds = world x localBounds)
  Attachment attachment;       // what it moves with
  int segment = -1;            // index into RenderScene::segments
  // A simulated body (not visual-only), a terrain or a robot: what sensor
  // views draw (RaiSim renders sensors from world objects only).
  bool worldObject = false;
  // A wire's line (index into RenderScene::wires): its transform spans two
  // bodies, so poseScene() recomputes it from both ends.
  int wire = -1;
  // A deformable's surface (index into RenderScene::surfaces): its vertices
  // are world positions (`world` stays the identity) that trajectory frames
  // replace.
  int surface = -1;
};

// A deformable drawn from its OBJ surface in file order (asset/obj_surface:
// the particles rscene-sim moves are those vertices, the triangles its
// constraints run along): world positions (at rest the record's pose and
// scale applied; along a trajectory a frame's points) and the OBJ's
// triangles.  The renderer recomputes area-weighted vertex normals (so the
// mesh shades smoothly) and re-uploads the vertices when `version` moves.
struct DeformedSurface {
  std::size_t drawable = 0;                            // index into RenderScene::drawables
  std::vector<Eigen::Vector3f> positions;              // world
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::uint64_t version = 0;                           // bumped by poseScene() when positions change
  std::uint64_t framesVersion = 0;                     // the ParticlePositions version last applied
  // A volume (fem) the simulator may fill with particles past the OBJ's
  // vertices: trajectory lines then hold more points than are drawn.
  bool mayFill = false;
};

// A wire drawn as a cylinder of `width` between two attachment points:
// each end is a point (`local`'s translation) on the body its Attachment
// names, or in the world.  `a` and `b` are the ends' current world points.
struct WireSpan {
  std::size_t drawable = 0;  // index into RenderScene::drawables
  Attachment endA, endB;
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
  double width = 0;
};

enum class LightType { Directional, Point, Spot, Area };

struct RenderLight {
  LightType type = LightType::Directional;
  Eigen::Vector3d direction{0, 0, -1};  // the way the light travels, unit
  Eigen::Vector3d position{0, 0, 3};
  Eigen::Vector3f color{1, 1, 1};       // color x intensity (negative lights subtract)
  Eigen::Vector3f attenuation{1, 0.04f, 0.012f};
  float coneDegrees = 30, innerConeDegrees = 18;
  float range = 0;
  Eigen::Vector2f areaSize{1, 1};
  bool shadows = false;
  // Shadow map of this light (when `shadows`): side in texels (0: the
  // renderer's choice), depth bias, strength (0 none .. 1 black), filter
  // radius in texels.  Filled from the light record (defaults: the schema's),
  // overridden by rayrai_render when custom=true.
  int shadowResolution = 0;
  float shadowBias = 0, shadowStrength = 1, shadowPcfRadius = 1;
  // A directional light's shadow box when shadowUseCustomPosition: centred
  // on shadowCenter, half size shadowOrthoHalfSize, near/far along the light.
  bool customShadowBox = false;
  Eigen::Vector3d shadowCenter = Eigen::Vector3d::Zero();
  float shadowOrthoHalfSize = 0, shadowNear = 0, shadowFar = 0;
  std::uint32_t line = 0;
};

struct TerrainMesh {
  int xSamples = 0, ySamples = 0;
  std::vector<Eigen::Vector3f> positions;  // world space
  std::vector<Eigen::Vector4f> colors;
  std::vector<bool> holes;
  int material = 0;
  bool castShadow = true;
  bool receiveShadow = true;
  Eigen::AlignedBox3d bounds;
  int segment = -1;
};

struct Instanced {
  Shape shape = Shape::Box;
  std::string meshPath;
  std::vector<Eigen::Affine3d> worlds;  // unit shape -> world
  std::vector<Eigen::Vector4f> colors;
  std::vector<Eigen::AlignedBox3d> instanceBounds;  // world-space, one per instance
  int material = 0;
  bool castShadow = true;
  bool doubleSided = false;  // grass blades: both faces drawn and lit
  bool worldObject = false;  // drawn by sensor views too (granular particles)
  std::uint32_t line = 0;
  std::uint32_t meshColumn = 0;  // of meshPath on `line`
  Eigen::AlignedBox3d bounds;
  int segment = -1;
  // What it was made from, for messages and tests: the record kind
  // (instanced_visual, terrain_foliage_layer, granular) and how many
  // instances that record generated before the draw limits (foliage: those
  // scattered; otherwise the record's own count).
  std::string kind = "instanced_visual";
  std::uint64_t generated = 0;
  // A granular record's particles (one instance each, in the record's
  // order): their radii, kept while trajectory frames move the centres;
  // `version` bumped by poseScene() when they move.
  std::vector<double> radii;
  std::uint64_t version = 0, framesVersion = 0;
};

struct PointBatch {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector4f> colors;
  float pointSize = 1;
  Eigen::AlignedBox3d bounds;
  int segment = -1;
};

enum class Background { PlainColor, Hdr, Sky };
enum class ToneMap { Linear, Aces, Filmic, AgX, Unreal };

struct Look {
  Eigen::Vector3f background = Eigen::Vector3f::Zero();
  Eigen::Vector3f ambient = Eigen::Vector3f::Zero();
  float fogDensity = 0;
  Eigen::Vector3f fogColor = Eigen::Vector3f::Zero();
  bool shadows = false;
  float exposure = 0, gamma = 0;
  Background mode = Background::Sky;
  std::string hdrPath;  // resolved
  std::uint32_t hdrLine = 0;
  ToneMap toneMap = ToneMap::Aces;
  Eigen::Vector3d sunDirection{0, 0, 1};  // towards the sun, unit
  float cloudCoverage = 0;
  bool overcast = false, night = false;
  // Height fog (environment heightFog*): density(z) = heightFogDensity *
  // exp(-heightFogFalloff * (z - heightFogBase)), on top of fogDensity
  // (which includes the weather's fogDensity).
  bool heightFog = false;
  float heightFogDensity = 0, heightFogBase = 0, heightFogFalloff = 0;
  float environmentIntensity = 1;  // image-based light from the sky or HDR (pbrEnvironmentIntensity)
  // Post-processing asked for by the environment and rayrai_render records.
  float bloomIntensity = 0, bloomThreshold = 1, bloomRadius = 4;
  bool fxaa = false, ssao = false;
  bool autoExposure = false;
  float autoExposureKey = 0.18f;
  bool depthOfField = false;
  float focusDistance = 5, aperture = 0;
  // Shadow defaults (rayrai_render custom=true, else the preset's) and how
  // many lights get shadow maps (environment shadowedLightBudget; 0: all).
  int shadowResolution = 2048;
  float shadowBias = 0.0008f, shadowStrength = 0.85f, shadowPcfRadius = 1.25f;
  bool customShadows = false;  // rayrai_render custom=true: its shadow fields override each light's
  int shadowedLightBudget = 0;
  int shadowMapSize = 0;       // environment shadowMapSize: the largest map side (0: no cap)
  int msaaSamples = 4;         // viewerMsaaSamples
  std::string preset;          // rayrai_render preset: fast | balanced | high | ultra
};

// projected_decal: what lies inside the box `world` maps the unit cube
// [-1, 1]^3 to (pose x scale x halfExtents) is painted, projected along the
// box's local -z; uv = local xy in [0, 1] x uvScale + uvOffset.
struct RenderDecal {
  Eigen::Affine3d world = Eigen::Affine3d::Identity();
  Eigen::Vector4f color = Eigen::Vector4f::Ones();
  float edgeFade = 0, normalFade = 0, upperFade = 0, lowerFade = 0;
  std::string albedoTexture, emissionTexture, normalTexture, ormTexture;  // resolved; empty: none
  Eigen::Vector2f uvScale = Eigen::Vector2f::Ones(), uvOffset = Eigen::Vector2f::Zero();
  float albedoMix = 1, emissionEnergy = 0, normalStrength = 1, ormStrength = 1;
  float fadeBegin = 0, fadeLength = 0;  // distance fade; fadeLength 0: none
  Eigen::AlignedBox3d bounds;
  std::uint32_t line = 0;
  std::array<std::uint32_t, 4> textureColumns{};  // of albedo, emission, normal, ormTexture on `line`
};

// local_fog: a sphere of fog; density (per metre) falls to 0 over the
// outer edgeFade fraction of the radius, modulated by value noise of
// frequency noiseScale (per metre) by +-noiseStrength.
struct RenderFog {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  float radius = 0, density = 0, edgeFade = 0, noiseScale = 0, noiseStrength = 0;
  Eigen::Vector3f color = Eigen::Vector3f::Ones();  // linear
  std::uint32_t line = 0;
};

// irradiance_volume: constant indirect light `color` (linear, x strength) inside
// the box `world` maps the unit cube [-1, 1]^3 to, fading over edgeFade
// (metres) at its faces.
struct RenderIrradiance {
  Eigen::Affine3d world = Eigen::Affine3d::Identity();
  Eigen::Vector3f color = Eigen::Vector3f::Zero();
  float edgeFade = 0, normalBias = 0;
  Eigen::AlignedBox3d bounds;
  std::uint32_t line = 0;
};

// reflection_probe: a cube map captured at `position`, for surfaces within
// `radius`; box-projected onto `box` when boxProjection.
struct RenderProbe {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  float radius = 0, strength = 1;
  bool boxProjection = false;
  Eigen::AlignedBox3d box;
  int cubemapSize = 128, prefilteredResolution = 128, prefilteredMipLevels = 5, prefilteredSamples = 64;
  int irradianceResolution = 32, irradianceSamples = 64, brdfLutSize = 128, brdfLutSamples = 512;
  bool captureShadows = true, captureBackground = true, drawVisuals = false, drawPointClouds = false;
  float exposure = 1;
  std::uint32_t line = 0;
};

struct RenderScene {
  std::vector<RenderMaterial> materials;  // [0] is engine_default
  std::vector<Drawable> drawables;
  std::vector<RenderLight> lights;
  std::vector<Camera> cameras;  // the scene view's, near/far made usable
  std::vector<TerrainMesh> terrains;
  std::vector<Instanced> instanced;
  std::vector<PointBatch> pointClouds;
  std::vector<Segment> segments;  // the segmentation legend
  std::vector<RenderDecal> decals;
  std::vector<RenderFog> fogs;
  std::vector<RenderIrradiance> irradianceVolumes;
  std::vector<RenderProbe> probes;
  std::vector<WireSpan> wires;
  std::vector<DeformedSurface> surfaces;
  // What draws each record of Scene::deformables (an index into surfaces)
  // and Scene::granulars (into instanced); -1: not drawn so (hidden, not an
  // OBJ surface): trajectory frames then move nothing of it.
  std::vector<int> deformableSurfaces, granularBatches;
  Look environment;
  std::size_t robots = 0;              // articulated systems drawn
  // Every articulated system's model, indexed like Scene::articulated
  // (hidden ones too: their sensors still see); null when it did not load.
  std::vector<std::shared_ptr<const robot::Model>> robotModels;
  std::map<std::string, int> skipped;  // record kind -> count
  Eigen::AlignedBox3d bounds;          // everything visible but the ground
  bool hasGround = false;
};

// How much the renderer prepares at most, whatever the file declares
// (README, "Resource limits: rscene-render").  A record's own
// maxRenderedInstances / renderedInstanceStride / maxRenderedPoints /
// renderedPointStride are honoured first.
struct DrawLimits {
  // Instances drawn, all instanced_visual, terrain_foliage_layer and
  // granular records together; past it the record that crosses it is an
  // error (RS9014; a granular record: RS9070).  ~1 KB each in all.
  std::uint64_t maxInstances = 1'000'000;
  // Vertices of one drawn terrain grid: a larger one is drawn decimated
  // (every k-th sample, the last row and column kept), a uniform flat one
  // as its 4 corners.  Not an error: the scene is drawn at bounded cost.
  std::uint64_t maxTerrainVertices = std::uint64_t{1} << 20;
  // --allow-missing-assets: an unreadable mesh is drawn as a placeholder
  // later, so the scene check does not read meshes (RS7007) before.
  bool allowMissingAssets = false;
};

// The segmentation color of a record (see Segment): never black.
void segmentColor(const std::optional<Eigen::Vector4d>& written, std::int64_t instanceId,
                  const std::string& semanticClass, const std::string& path, std::uint8_t rgb[3]);

// Moves every attached drawable to its body's pose in `poses` (indices as
// robot::BodyPoses: objects, compounds, robot links) and recomputes its
// bounds; a body `poses` lacks stays where it is.
struct BodyPoseView {
  const std::vector<Pose>* objects = nullptr;
  const std::vector<Pose>* compounds = nullptr;
  const std::vector<std::vector<Pose>>* robotLinks = nullptr;
  // Deformable vertices and granular centres (world) of the records a
  // frame gave; a count other than what is drawn moves nothing (the
  // poser's particleCounts() refuses it first).
  const robot::ParticlePositions* particles = nullptr;
};
void poseScene(RenderScene& scene, const BodyPoseView& poses);

// How many points a trajectory line must give per deformable (at least its
// OBJ's vertices) and granular record, as drawn (robot::TrajectoryPoser):
// -1 for what is not drawn.
robot::ParticleCounts particleCounts(const RenderScene& scene);
// Reader limits for a trajectory of this scene: lines as long as its
// largest drawn particle record needs (TrajectoryLimits::forPoints), the
// defaults when a record's count is unknown (not drawn, or a volume the
// simulator may fill).
robot::TrajectoryLimits trajectoryLimits(const RenderScene& scene);

// The world-space bounds of `local` carried by `m` (its eight corners).
Eigen::AlignedBox3d transformBox(const Eigen::Affine3d& m, const Eigen::AlignedBox3d& local);
// The bounds of a drawable's unit shape (Drawable::world maps it to the
// world); a capsule's are at its own size.
Eigen::AlignedBox3d unitShapeBounds(Shape s, double capsuleRadius = 0, double capsuleHeight = 0);

// Prepares `out` from a scene view built from `doc` (the Document gives
// record lines for messages).  False with RS9014 when the instances to draw
// exceed limits.maxInstances; the batch that crosses it is left out.
//
// Articulated systems are loaded (lib/robot: URDF, MJCF) and drawn at
// their record's state; a robot that does not load, or whose record does
// not match its model (RS70xx), is an error.  Their meshes are read through
// `assets` for their bounds (null: a cache of this call's own); give
// renderScene the same cache (RenderOptions::assets) to read each once.
bool prepareScene(const Document& doc, const Scene& scene, RenderScene& out, Diagnostics& diags,
                  const DrawLimits& limits = {}, asset::AssetCache* assets = nullptr);

// buildScene(), checkScene() (scene/check.hpp: what validate and sim
// refuse too) then prepareScene(); false when either reported an error (a
// value that does not parse, a malformed terrain, a zero-size body ...).
// `out` is filled as far as possible either way.
bool buildRenderScene(const Document& doc, const SceneOptions& options, RenderScene& out, Diagnostics& diags,
                      const DrawLimits& limits = {}, asset::AssetCache* assets = nullptr);
// The same, keeping the scene model it built in `scene` (cameras, sensors,
// bodies: what views and trajectories are read against).
bool buildRenderScene(const Document& doc, const SceneOptions& options, Scene& scene, RenderScene& out,
                      Diagnostics& diags, const DrawLimits& limits = {}, asset::AssetCache* assets = nullptr);

}  // namespace rscene::render
