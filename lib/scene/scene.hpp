// The typed scene model (DESIGN.md, lib/scene): plain structs with Eigen
// types for the records that validate's scene checks, the simulator and the
// renderer consume.
//
// - Every value is typed.  Every absent field, and every field of an absent
//   singleton record, holds the default of the schema table
//   (FieldDef::defaultValue), read by scene/reader.hpp: the structs below
//   initialise their members to zero, never to a second copy of a default
//   (tests/scene/defaults_test.cpp).  Rules the schema cannot hold are
//   compat-notes.md's (fog colour = background, contact pairs = the
//   solver's defaults, the two default terrain slots).
// - Enumerations hold their canonical name (EnumDef::canonical), so
//   `plane`, `fixed`, `sun` arrive as `ground`, `static`, `directional`.
// - Poses are given twice: `local` as written in the file and `world`
//   resolved (groups are folders in the world frame; a node parented to a
//   non-group node inherits that node's world pose when
//   scene_graph inheritedTransforms=true, the default).  Only position and
//   orientation are inherited, never scale.
// - Asset paths are resolved with the rule of assets.hpp.
// - Every struct keeps `recordIndex` into Document::records, so a tool can
//   write values back with Document::setValue on the positional tokens.
//
// The view is built in one pass and owns its data; it does not point into
// the Document.  buildScene() never throws on bad input: a value that does
// not parse is reported with the validator's code for it (RS2xxx, RS4xxx)
// and the default is used instead.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/codes.hpp"
#include "core/assets.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "scene/pose.hpp"
#include "scene/visual_records.hpp"

namespace rscene {

// Diagnostic codes of the scene model.  Where lib/core's validator checks
// the same condition, the model reports the validator's code at the same
// field, so validate, sim and render name one problem one way (the registry
// in core/check_codes.cpp lists every code and who emits it).
namespace scene_code {
inline constexpr const char* kBadValue = rs::RS7001;      // list whose length the type cannot hold (points, colors)
inline constexpr const char* kZeroSize = rs::RS7003;      // body shape with a zero or negative physical size
inline constexpr const char* kNoMesh = rs::RS7004;        // mesh body without a mesh path
inline constexpr const char* kBadMesh = rs::RS7007;       // mesh file that cannot be read
inline constexpr const char* kBadTimeStep = rs::RS7008;   // time_step not positive
inline constexpr const char* kBadChildShape = rs::RS7009; // compound child that is a plane (ground, half_space)
inline constexpr const char* kUnsupported = rs::RS7010;   // records kept but not simulated (warning)
inline constexpr const char* kWireSkipped = rs::RS7011;   // wire to a node sim does not model (warning)
inline constexpr const char* kBadMassValue = rs::RS7020;  // dynamic mass not a finite normal double (scene/limits.hpp)
inline constexpr const char* kBadPose = rs::RS7021;       // pose not finite, orientation not normalisable
inline constexpr const char* kTinyTimeStep = rs::RS7022;  // positive time_step not finite or outside [kMinTimeStep, kMaxTimeStep]
inline constexpr const char* kHugeValue = rs::RS7026;     // size, wire attachment or length, gravity beyond kMaxLength
inline constexpr const char* kBadCoefficient = rs::RS7027;  // coefficient or solver iterations out of range
inline constexpr const char* kBadCameraSize = rs::RS7028;   // camera width or height outside 0..16384
inline constexpr const char* kBadInertia = rs::RS7090;      // custom inertia diagonal not positive, finite, within kMaxInertia
// Codes shared with lib/core's validator (same condition, same code).
inline constexpr const char* kBadMass = rs::RS4008;       // dynamic body with mass <= 0
inline constexpr const char* kMissingFile = rs::RS5001;   // asset file that does not exist
inline constexpr const char* kUnknownBody = rs::RS3012;   // wire body that names no node
}  // namespace scene_code

struct SceneOptions {
  std::string sceneDir = ".";  // directory of the scene file (assets resolve against it)
  std::string baseDir;         // when set, replaces sceneDir (e.g. for stdin)
  ProjectPlace project;        // the Engine 2 project the scene is in (core/assets.hpp), if any
  FileExists exists = fileExistsOnDisk;
  // Build only what checkScene() reads: time step, groups, objects,
  // compounds, wires, point clouds, and terrains without their per-sample
  // lists.  rscene-validate builds this much on top of lib/core's checks,
  // which already report every value problem of the records left out.
  bool bodiesOnly = false;
};

enum class BodyMode { Static, Kinematic, Dynamic, VisualOnly };
const char* bodyModeName(BodyMode m);  // canonical enum name

// solver record (Engine 2 defaults from the schema table).
struct Solver {
  int recordIndex = -1;  // -1: absent, all defaults
  int iterations{};
  double tolerance{};
  double erp{};
  std::string mode{};
  double erp2{};
  double defaultFriction{};
  double defaultRestitution{};
  double defaultRestitutionThreshold{};
  double defaultStaticFriction{};
  double defaultStaticFrictionVelocityThreshold{};
  double defaultRollingFriction{};
  double defaultSpinningFriction{};
  int contactMaxIterations{};
  int maxContactsPerPair{};
  bool sweptCcdEnabled{};
  double sweptCcdMinSpeed{};
  double sweptCcdSpeculativeMargin{};
  bool sleepingEnabled{};
  double sleepingLinearVelocityThreshold{};
  double sleepingAngularVelocityThreshold{};
  int sleepingQuietSteps{};
  std::string broadphaseType{};
  Eigen::Vector3d broadphaseWorldMin{Eigen::Vector3d::Zero()};
  Eigen::Vector3d broadphaseWorldMax{Eigen::Vector3d::Zero()};
  bool broadphaseUseWorldBounds{};
  bool fixedContactSolverIterationOrder{};
  double worldTime{};
};

// environment record.
struct Environment {
  int recordIndex = -1;
  Eigen::Vector3d background{Eigen::Vector3d::Zero()};
  Eigen::Vector3d ambient{Eigen::Vector3d::Zero()};
  double fogDensity{};
  bool shadows{};
  std::string envMapPath;                  // resolved; empty = none
  Eigen::Vector4d fogColor{Eigen::Vector4d::Zero()};  // defaults to the background colour
  double exposure{};
  double gamma{};
  std::string backgroundMode{};  // plain_color | hdr | rayrai_sky
  std::string colorMode;                      // empty: renderer's choice
  double pbrEnvironmentIntensity{};
  bool heightFogEnabled{};
  double heightFogDensity{}, heightFogBaseHeight{}, heightFogFalloff{};
  // Post-processing (rayrai PostProcess): bloom, FXAA, SSAO; shadow map size.
  double bloomIntensity{}, bloomThreshold{}, bloomRadius{};
  bool fxaa{}, ssao{};
  std::int64_t shadowMapSize{}, shadowedLightBudget{};
};

// weather record (only what a renderer needs for lighting and fog).
struct Weather {
  int recordIndex = -1;
  bool enabled{};
  std::string preset{};
  double timeOfDay{};  // hours
  bool useExplicitSunAngles{};
  double sunAzimuthDegrees{};
  double sunElevationDegrees{};
  double fogDensity{};
  std::optional<double> cloudCoverage;  // absent: the preset's
};

// rayrai_render record (what a renderer needs of Engine 2's view settings).
struct RenderSettings {
  int recordIndex = -1;
  std::string preset{};
  std::string colorMode;  // empty: not written (environment colorMode wins when written)
  bool custom{};  // the named fields below override the preset's
  std::int64_t msaaSamples{};  // viewerMsaaSamples
  std::int64_t shadowResolution{};
  double shadowBias{}, shadowStrength{}, shadowPcfRadius{};
  bool autoExposure{};
  double autoExposureKey{}, autoExposureSpeed{};
  double pbrExposure{}, pbrEnvironmentIntensity{};
  bool reflectiveGround{}, screenSpaceReflections{};
  double screenSpaceReflectionStrength{};
  bool volumetricFog{};
  double volumetricFogDensity{}, volumetricLightStrength{};
  bool contactShadows{};
  double contactShadowsLength{}, contactShadowsStrength{};
  bool depthOfField{};
  double depthOfFieldFocusDistance{}, depthOfFieldAperture{};
  bool motionBlur{};
};

struct Material {
  int recordIndex = -1;  // -1: the implicit engine_default
  std::string id;        // defaults to the name
  std::string name;
  Eigen::Vector4d color{Eigen::Vector4d::Zero()};
  double metallic{};
  double roughness{};
  Eigen::Vector3d emissive = Eigen::Vector3d::Zero();
  double emissiveStrength{};
  bool doubleSided{};
  std::string alphaMode{};  // opaque | mask | hash | blend
  double alphaCutoff{};
  // Resolved texture paths; empty = none.
  std::string albedoTexture, normalTexture, metallicTexture, roughnessTexture, aoTexture, emissiveTexture;
};

// contact_material: properties of one pair of contact-material names.
struct ContactMaterial {
  int recordIndex = -1;
  std::string materialA, materialB;
  double friction{};
  double restitution{};
  double restitutionThreshold{};
  double staticFriction{};
  double staticFrictionVelocityThreshold{};
  double rollingFriction{};
  double spinningFriction{};
};

struct TerrainTexture {
  int recordIndex = -1;  // -1: a default slot
  int slot{};
  std::string id, name;
  Eigen::Vector4d color{Eigen::Vector4d::Zero()};
  std::string albedo, normal;  // resolved
  double uvScale{};
  double roughness{};
};

struct Group {
  int recordIndex = -1;
  std::string path, id, parentId;
  bool visible{};
};

struct Light {
  int recordIndex = -1;
  std::string path, id, parentId;
  std::string type{};  // directional | point | spot | area
  Eigen::Vector3d direction{Eigen::Vector3d::Zero()};  // the way the light travels, world frame, normalised
  double intensity{};
  Eigen::Vector3d position{Eigen::Vector3d::Zero()};  // world frame
  Eigen::Vector4d color{Eigen::Vector4d::Zero()};
  double attenuationConstant{}, attenuationLinear{}, attenuationQuadratic{};
  double range{};  // 0: unlimited
  double coneAngle{};  // degrees
  double innerConeAngle{};  // degrees
  double radius{};
  Eigen::Vector3d areaSize = Eigen::Vector3d::Zero();
  bool shadows{};
  bool negative{};  // subtracts light
  // Shadow map: resolution in texels (0: the renderer's), depth bias, how
  // dark (0..1), filter radius in texels.
  std::int64_t shadowResolution{};
  double shadowBias{}, shadowStrength{}, shadowPcfRadius{};
  // Custom directional shadow box (shadowUseCustomPosition).
  double shadowOrthoHalfSize{}, shadowNear{}, shadowFar{};
  Eigen::Vector3d shadowCenter = Eigen::Vector3d::Zero(), shadowPosition = Eigen::Vector3d::Zero();
  bool shadowUseCustomPosition{};
  bool distanceFadeEnabled{};
  double distanceFadeBegin{}, distanceFadeShadow{}, distanceFadeLength{};
  bool hiddenByGroup = false;  // an ancestor group has visible=false
};

// What a camera or sensor rides on: the body its `local` pose is written
// in.  A camera rides on the object, compound or articulated system its
// parentGroupId names (a group is a folder: World); a sensor on its
// parentObject, at its parentLink when that names a robot link or frame.
struct Mount {
  enum class Kind { World, Object, Compound, Articulated };
  Kind kind = Kind::World;
  int index = -1;    // into Scene::objects, compounds or articulated
  std::string link;  // Articulated: a link or frame name; empty = the root link
};

struct Camera {
  int recordIndex = -1;
  std::string path, id;
  Pose local, world;  // looks along local +x with local +z up
  double verticalFov{};  // degrees, clamped to [1, 175]
  double horizontalFov{};  // > 0 overrides the aspect-derived one
  double nearPlane{}, farPlane{};
  int width{}, height{};  // only the aspect ratio
  std::string renderMode{};
  std::string projection{};
  double orthoScale{};
  bool enabled{};
  std::string outputPath;  // as written ("-" and empty: none); not an asset, never resolved
  Mount mount;             // the body parentGroupId names (World: a group or nothing)
};

// The numbers of a camera-like or physical sensor, from a sensor record or
// from a robot's sensor-set file (lib/robot).  Angles in degrees, lengths
// in metres, rates in Hz; 0 means "not given" where a comment says so.
struct SensorParams {
  int width{}, height{};                  // image size (camera-like kinds)
  double verticalFov{}, horizontalFov{};  // degrees; 0: not given
  double nearPlane{}, farPlane{};         // 0: not given
  // Pinhole intrinsics in pixels (RaiSim's frame: a point (x forward, y
  // left, z up) lands at column cx - fx*y/x, row cy - fy*z/x); all four
  // given or none (0: not given).
  double fx{}, fy{}, cx{}, cy{};
  double updateRate{};  // Hz; 0: every simulation step
  // LiDAR: channels (rows, pitch) x samples (columns, yaw), the pitch span
  // [minPitch, maxPitch] in degrees, ranges; spinRate (Hz) and direction.
  int lidarChannels{}, lidarSamples{};
  double lidarMinPitch{}, lidarMaxPitch{};
  double lidarMinRange{}, lidarMaxRange{};
  double lidarSpinRate{};
  bool lidarClockwise{};
  bool segmentation{};  // a camera that also writes segmentation
  // Additive Gaussian noise on depth, range and IMU readings; the same seed
  // gives the same noise.
  double noiseMean{}, noiseStddev{};
  std::uint64_t noiseSeed{};
  // IMU saturation (RaiSim's <limit acc_limit ang_vel_limit>); 0: none.
  double accelerationLimit{}, angularVelocityLimit{};
};

// sensor record.  `kind` is the canonical sensor_kind (rgb, depth,
// segmentation, rgb_depth, imu, lidar, force_torque, or as written when
// the schema does not know it).
struct Sensor {
  int recordIndex = -1;
  std::string path, id;
  std::string kind{};
  std::string parentObject;  // as written (id or path of a body); empty: the world
  std::string parentLink;    // as written
  Mount mount;               // parentObject/parentLink resolved; World when it names nothing known
  Pose local, world;         // world: at the scene's state (robots at their record's q)
  SensorParams params;
  bool enabled{};
  std::string outputPath;  // as written ("-" and empty: none)
};

struct Object {
  int recordIndex = -1;
  std::string path, id, parentId;
  std::string primitive{};  // ground box sphere cylinder capsule mesh half_space
  Pose local, world;
  Eigen::Vector3d scale{Eigen::Vector3d::Zero()};
  double radius{}, height{};  // as written (#12, #13)
  double mass{};  // as written
  // Segmentation (rscene-render): the record's color when it writes one,
  // else a color derived from instanceId (>= 0) or semanticClass.
  std::string semanticClass;  // "" and "-": none
  std::int64_t instanceId{};  // -1: none
  std::optional<Eigen::Vector4d> segmentationColor;
  std::string contactMaterial;      // contact-material name (may be empty / "default")
  std::string material;             // visual material id
  bool visible{};
  bool hiddenByGroup = false;  // an ancestor group has visible=false
  bool castShadow{};
  BodyMode bodyMode{};  // resolved from #21, #17, #19, collidable
  bool collidable{};
  std::uint64_t collisionGroup{};
  std::uint64_t collisionMask{};
  std::string meshPath;           // resolved render mesh (renderMeshPath= overrides #20)
  std::string collisionMeshPath;  // resolved collision mesh (collisionMeshPath= or the render mesh)
  std::string collisionMode{};  // convex_hull | original_mesh | convexify
  // customInertia=true with an inertiaDiagonal: the principal moments (kg m^2,
  // body frame) rscene-sim gives a dynamic body instead of its shape's.  A
  // flag without a diagonal keeps the shape's inertia.
  bool hasInertia{};
  Eigen::Vector3d inertiaDiagonal = Eigen::Vector3d::Zero();
  // Positional token of position.x in the record (orientation w follows at +3),
  // for writing poses back.
  int positionToken = -1;

  // Physical sizes per compat-notes.md.
  double physicsRadius() const { return radius * scale.x(); }
  double physicsHeight() const { return height * scale.z(); }
  double meshScale() const { return (scale.x() + scale.y() + scale.z()) / 3; }
  // A dynamic body needs mass > 0; other modes treat mass <= 0 as 1 kg.
  double effectiveMass() const { return bodyMode != BodyMode::Dynamic && mass <= 0 ? 1.0 : mass; }
};

struct CompoundChild {
  int recordIndex = -1;
  std::string primitive{};
  Pose local;  // in the compound's frame
  Eigen::Vector3d scale{Eigen::Vector3d::Zero()};
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // box full side lengths (size x scale)
  double radius{}, height{};
  std::string contactMaterial, material;
  std::string meshPath;  // resolved
};

struct Compound {
  int recordIndex = -1;
  std::string path, id, parentId;
  Pose local, world;
  Eigen::Vector3d scale{Eigen::Vector3d::Zero()};
  double mass{};
  BodyMode bodyMode{};
  bool visible{}, collidable{};
  bool hiddenByGroup = false;
  bool hasCenterOfMass{}, hasInertia{};
  Eigen::Vector3d centerOfMass = Eigen::Vector3d::Zero();  // compound frame
  Eigen::Vector3d inertiaDiagonal = Eigen::Vector3d::Zero();
  std::uint64_t collisionGroup{};
  std::uint64_t collisionMask{};
  std::string contactMaterial, material;
  std::string semanticClass;
  std::vector<CompoundChild> children;
  int positionToken = -1;
};

// Physical sizes of a compound child (compat-notes.md "Sizes"; the child's
// scale times the compound's): box sides are `size` x scale, or the scale
// itself when `size` is absent or zero; radius `radius` x scale.x, height
// `height` x scale.z.  An absent radius or height is 0: a sphere child
// without a radius is a zero-size shape (RS7003), never a guessed size.
inline Eigen::Vector3d childScale(const Compound& c, const CompoundChild& ch) { return ch.scale.cwiseProduct(c.scale); }
inline Eigen::Vector3d childBox(const Compound& c, const CompoundChild& ch) {
  Eigen::Vector3d s = childScale(c, ch);
  return ch.size.isZero() ? s : Eigen::Vector3d(ch.size.cwiseProduct(s));
}
inline double childRadius(const Compound& c, const CompoundChild& ch) { return ch.radius * childScale(c, ch).x(); }
inline double childHeight(const Compound& c, const CompoundChild& ch) { return ch.height * childScale(c, ch).z(); }
// The child's pose in the compound's body frame: its position scales with
// the compound.
inline Pose childPose(const Compound& c, const CompoundChild& ch) {
  Pose p = ch.local;
  p.position = p.position.cwiseProduct(c.scale);
  return p;
}

struct TerrainSplatLayer {
  int recordIndex = -1;
  int slot{};
  bool enabled{};
  double strength{};
  std::vector<double> weights;  // one per sample or empty
};

// terrain_region: sample (x, y) is heights[y * xSamples + x], located at
// center.xy - size/2 + (x, y) * size / (samples - 1), height relative to center.z.
struct Terrain {
  int recordIndex = -1;
  std::string path, id, parentId;
  int xSamples{}, ySamples{};
  double xSize{}, ySize{};
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  std::vector<double> heights;  // xSamples*ySamples (zeros when the file has none)
  std::string material, contactMaterial;
  int baseTexture{};
  bool visible{}, collidable{}, castShadow{}, receiveShadow{};
  bool hiddenByGroup = false;
  bool textureSplatting{};  // textureSplattingEnabled
  std::string sourceKind{};
  std::vector<double> texturePrimary, textureSecondary, textureBlend, wetness, holes;  // per sample or empty
  std::vector<Eigen::Vector4d> vertexColors;  // per sample or empty
  std::vector<TerrainSplatLayer> splatLayers;
  std::vector<FoliageLayer> foliageLayers;

  Eigen::Vector3d samplePosition(int x, int y) const {
    return {center.x() - xSize / 2 + x * xSize / (xSamples - 1), center.y() - ySize / 2 + y * ySize / (ySamples - 1),
            center.z() + heights[static_cast<std::size_t>(y) * xSamples + x]};
  }
};

// articulated_resource: a URDF or MJCF robot description that articulated
// records instantiate (lib/robot reads the file).
struct ArticulatedResource {
  int recordIndex = -1;
  std::string id, name;
  std::string path;               // resolved robot file
  std::string resourceDirectory;  // resolved directory for package:// and modules; empty = none
  std::vector<std::string> modules, jointOrder;
  bool doNotCollideWithParent{}, convexifyCollisionMeshes{};
};

// articulated_ik: one frame target of the articulated system it follows.
struct ArticulatedIk {
  int recordIndex = -1;
  std::string frame;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  bool enabled{}, useOrientation{};
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // normalised
  int maxIterations{};
  double positionTolerance{}, orientationTolerance{}, orientationWeight{};
  double damping{}, stepSize{}, maxStep{}, svdTolerance{}, finiteDifferenceStep{}, transposeGain{};
  bool applyBestOnFailure{}, enforceJointLimits{};
  std::string inverseMethod{};  // damped_least_squares | pseudo_inverse | transpose (or as written)
};

// articulated: an instance of an articulated_resource.  Fields the record
// writes override the resource's (sourcePath, resourceDirectory, modules,
// jointOrder, doNotCollideWithParent, convexifyCollisionMeshes).
//
// Base pose: a fixed-base robot's base is placed at `world`; a floating
// base's pose is the first 7 numbers of generalizedCoordinate (position,
// quaternion w x y z, world frame) when the record writes them, else
// `world`.
struct Articulated {
  int recordIndex = -1;
  std::string path, id, parentId;
  std::string resourceRef;  // as written (resource id or name)
  int resource = -1;        // index into Scene::articulatedResources, -1 when it names none
  int resourceRecord = -1;  // that resource's record index
  std::string sourcePath;   // resolved robot file (the record's sourcePath=, else the resource's)
  std::string resourceDirectory;
  std::vector<std::string> modules, jointOrder;
  Pose local, world;
  Eigen::Vector3d scale{Eigen::Vector3d::Zero()};
  bool visible{}, collidable{};
  bool hiddenByGroup = false;
  bool doNotCollideWithParent{}, convexifyCollisionMeshes{};
  std::uint64_t collisionGroup{}, collisionMask{};
  bool hasCoordinate = false, hasVelocity = false;  // the record writes them
  std::vector<double> generalizedCoordinate, generalizedVelocity;  // as written
  std::string semanticClass;
  std::vector<ArticulatedIk> ik;
  int positionToken = -1;  // token of position.x (orientation w at +3)
  // --allow-missing-assets: its robot file is missing, so it is neither
  // simulated nor drawn (robot::leaveOutMissingRobots); its record is
  // written back as it was.
  bool leftOut = false;
};

// What one end of a wire names (compat-notes.md, "Wire kinds": a body by id
// or path, a terrain counts as a body; nothing means a point in the world).
// Articulated: an articulated system, attached at its body localIndexA/B.
enum class WireEnd { World, Body, Articulated, NotSimulated, Unknown };

struct Wire {
  int recordIndex = -1;
  std::string path, id;
  std::string kind{};  // stiff | compliant | custom
  std::string bodyA, bodyB;    // as written (id or path), decoded
  double length{};
  int localIndexA{}, localIndexB{};
  Eigen::Vector3d localPositionA = Eigen::Vector3d::Zero(), localPositionB = Eigen::Vector3d::Zero();
  double stiffness{}, damping{}, compliance{};
  double visualizationWidth{};
  bool enabled{};
  WireEnd endA = WireEnd::World, endB = WireEnd::World;
  std::string tagA, tagB;  // record kind an end names (when it names a node)
  // The record each end names, by the model's one rule (an id first, then
  // a path); -1 for the world or a name nothing has.  Sim, render and the
  // robot checks attach by this, never by the name again.
  int recordA = -1, recordB = -1;

  // Whether a simulator attaches this wire: enabled, and each end is the
  // world, a simulated body (object, compound, terrain) or an articulated
  // system (at its body localIndexA/B).  A wire to a visual-only object or
  // another node the simulator does not model is skipped with RS7011.
  bool simulated() const {
    auto ok = [](WireEnd e) { return e == WireEnd::World || e == WireEnd::Body || e == WireEnd::Articulated; };
    return enabled && ok(endA) && ok(endB);
  }
};

struct Instance {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d scale = Eigen::Vector3d::Zero();  // numbers 8..10
};

struct InstancedVisual {
  int recordIndex = -1;
  std::string path, id, parentId;
  std::string primitive{};
  std::string meshPath;  // resolved
  Eigen::Vector3d size{Eigen::Vector3d::Zero()};
  Eigen::Vector4d colorA{Eigen::Vector4d::Zero()}, colorB{Eigen::Vector4d::Zero()};
  std::vector<Instance> instances;
  std::vector<double> colorWeights;  // one per instance or empty
  // How much a renderer draws: every stride-th instance, at most max of
  // them (0: no limit of the record's own); the data keeps them all.
  std::int64_t maxRendered = 0, renderedStride = 1;
  bool castShadows{}, enabled{}, grassPatch{};
  // terrainBinding: the terrain_region (id or path, as written) the
  // instances stand on; terrainFoliageLayer: which of its foliage layers
  // the patch belongs to (-1: none).
  std::string terrainBinding;
  std::int64_t terrainFoliageLayer = -1;
  bool hiddenByGroup = false;
};

struct PointCloud {
  int recordIndex = -1;
  std::string path, id, parentId;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector4d> colors;  // one per point or empty
  double pointSize{};
  std::int64_t maxRendered = 0, renderedStride = 1;  // as InstancedVisual's
  bool enabled{};
  bool hiddenByGroup = false;
};

// A scene-content record the view does not model (deformable,
// granular, decals, fog volumes, probes, foliage layers ...).
struct SkippedRecord {
  int recordIndex = -1;
  std::string tag, path;
};

struct Scene {
  int timeStepRecord = -1;  // the time_step record in force, or -1
  double timeStep{};
  Eigen::Vector3d gravity{Eigen::Vector3d::Zero()};
  Solver solver;
  bool inheritedTransforms{};
  std::string assetRoot;  // decoded asset_root (core/assets.hpp: "." when absent)
  Environment environment;
  Weather weather;
  RenderSettings renderSettings;
  Material defaultMaterial;         // engine_default as Engine 2 assumes it (the material schema's defaults)
  std::vector<Material> materials;  // never empty: engine_default without material records
  std::vector<ContactMaterial> contactMaterials;
  std::vector<TerrainTexture> terrainTextures;  // never empty: slots 0/1 by default
  std::vector<Group> groups;
  std::vector<Light> lights;
  std::vector<Camera> cameras;
  std::vector<Object> objects;
  std::vector<Compound> compounds;
  std::vector<Terrain> terrains;
  std::vector<Wire> wires;
  std::vector<ArticulatedResource> articulatedResources;
  std::vector<Articulated> articulated;
  std::vector<InstancedVisual> instancedVisuals;
  std::vector<PointCloud> pointClouds;
  std::vector<Sensor> sensors;
  std::vector<Decal> decals;
  std::vector<LocalFog> localFogs;
  std::vector<IrradianceVolume> irradianceVolumes;
  std::vector<ReflectionProbe> reflectionProbes;
  std::vector<Deformable> deformables;
  std::vector<Granular> granulars;
  std::vector<SkippedRecord> skipped;

  const Material* findMaterial(const std::string& id) const;
  // The contact_material record of a pair of names (either order), or nullptr.
  const ContactMaterial* findContact(const std::string& a, const std::string& b) const;
};

// Builds the view.  Returns false when an error diagnostic was added; the
// scene is still filled as far as possible.
bool buildScene(const Document& doc, const SceneOptions& options, Scene& scene, Diagnostics& diagnostics);

// Most samples a terrain may hold (compat-notes.md: 64 Mi in total).
inline constexpr std::uint64_t kMaxTerrainSamples = 64ull * 1024 * 1024;

}  // namespace rscene
