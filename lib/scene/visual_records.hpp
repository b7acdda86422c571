// The scene-content records that are mostly looks (rayrai's Lighting and
// Weather pages: decals, fog volumes, irradiance volumes, reflection
// probes, terrain foliage) and the soft and granular bodies, as the typed
// scene model holds them.  Included by scene.hpp; read by visual_records.cpp
// with the schema's defaults (lib/core/schema_table.cpp).
//
// Poses are resolved like a light's: a node's position (and orientation)
// is carried by its parent group's frame into the world (`world`).
#pragma once
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/pose.hpp"

namespace rscene {

// projected_decal: a box (world pose, halfExtents times the positional
// scale) whose contents are painted on every surface inside it, projected
// along the box's local -z (rayrai: "project a textured box onto any
// surface inside it").
struct Decal {
  int recordIndex = -1;
  std::string path, id, parentId;
  Pose local, world;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  Eigen::Vector3d halfExtents = Eigen::Vector3d::Zero();
  Eigen::Vector4d color = Eigen::Vector4d::Zero();
  double edgeFade{}, normalFade{}, upperFade{}, lowerFade{};
  std::string albedoTexture, emissionTexture, normalTexture, ormTexture;  // resolved; empty: none
  Eigen::Vector2d uvScale = Eigen::Vector2d::Ones(), uvOffset = Eigen::Vector2d::Zero();
  double albedoMix{}, emissionEnergy{}, normalStrength{}, ormStrength{};
  bool distanceFadeEnabled{};
  double distanceFadeBegin{}, distanceFadeLength{};
  bool enabled{};
  bool hiddenByGroup = false;
};

// local_fog: a sphere of fog (world centre).
struct LocalFog {
  int recordIndex = -1;
  std::string path, id, parentId;
  Eigen::Vector3d localCenter = Eigen::Vector3d::Zero(), center = Eigen::Vector3d::Zero();
  double radius{};
  Eigen::Vector3d color = Eigen::Vector3d::Zero();
  double density{}, edgeFade{}, noiseScale{}, noiseStrength{};
  bool enabled{};
  bool hiddenByGroup = false;
};

// irradiance_volume: a box of constant indirect light.
struct IrradianceVolume {
  int recordIndex = -1;
  std::string path, id, parentId;
  Pose local, world;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  Eigen::Vector3d halfExtents = Eigen::Vector3d::Zero();
  Eigen::Vector4d color = Eigen::Vector4d::Zero();
  double strength{}, edgeFade{}, normalBias{};
  bool enabled{};
  bool hiddenByGroup = false;
};

// reflection_probe: a cube map captured at `position` (world), used by
// surfaces within `radius`, box-projected onto [boxMin, boxMax] (world)
// when boxProjection.
struct ReflectionProbe {
  int recordIndex = -1;
  std::string path, id, parentId;
  Eigen::Vector3d localPosition = Eigen::Vector3d::Zero(), position = Eigen::Vector3d::Zero();
  double radius{}, strength{};
  bool boxProjection{};
  Eigen::Vector3d boxMin = Eigen::Vector3d::Zero(), boxMax = Eigen::Vector3d::Zero();
  std::int64_t cubemapSize{};
  bool captureDrawVisualizationObjects{}, captureDrawPointClouds{}, captureShadows{};
  bool captureEnvironmentBackground{};
  double captureEnvironmentExposure{};
  std::int64_t irradianceResolution{}, irradianceSamples{};
  std::int64_t prefilteredResolution{}, prefilteredMipLevels{}, prefilteredSamples{};
  std::int64_t brdfLutSize{}, brdfLutSamples{};
  bool enabled{};
  bool hiddenByGroup = false;
};

// terrain_foliage_layer: instances scattered over its terrain_region
// (Terrain::foliageLayers).  density: one value in 0..1 per terrain sample
// (empty: 1 everywhere), scaling densityPerSquareMeter.
struct FoliageLayer {
  int recordIndex = -1;
  std::string id, name;
  bool enabled{};
  std::string primitive{};  // grass_blade, box, sphere, ... or mesh (meshPath)
  std::string meshPath;     // resolved; empty: none
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  Eigen::Vector4d colorA = Eigen::Vector4d::Zero(), colorB = Eigen::Vector4d::Zero();
  std::vector<double> density;
  double densityPerSquareMeter{};
  std::int64_t maxInstances{};
  double minScale{}, maxScale{};
  double randomYawDegrees{}, randomPitchDegrees{}, randomRollDegrees{};
  bool alignToNormal{};
  double minHeight{}, maxHeight{};
  double minSlopeDegrees{}, maxSlopeDegrees{};
  bool castShadows{};
  std::int64_t maxRenderedInstances{}, renderedInstanceStride{};
  std::int64_t seed{};
};

// deformable: a soft body (cloth, mass_spring, fem) from an OBJ mesh.  The
// format stores no deformed state: the mesh at `world` scaled by `scale`
// is its rest shape.
struct Deformable {
  int recordIndex = -1;
  std::string path, id, parentId;
  std::string kind{};     // cloth | mass_spring | fem | ...
  std::string meshPath;   // resolved
  Pose local, world;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();  // positional scale times the named uniform scale
  std::vector<std::int64_t> pinnedVertices;
  double totalMass{};
  double distanceCompliance{}, distanceStiffness{}, bendCompliance{}, bendStiffness{};
  double youngsModulus{}, poissonRatio{}, thickness{}, damping{}, collisionRadius{};
  std::int64_t iterations{}, substeps{};
  std::string solverMode, particleMode;
  double particleSpacing{};
  std::string contactMaterial, material;
  bool visible{}, collidable{};
  std::uint64_t collisionGroup{}, collisionMask{};
  bool hiddenByGroup = false;
  int meshToken = -1;  // token of meshPath, for messages
};

// granular: particles, explicit (positions/radii) or a box fill
// (granularParticles()).  Positions are in the record's frame (`world`).
struct Granular {
  int recordIndex = -1;
  std::string path, id, parentId;
  std::string kind{};
  Pose local, world;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  std::vector<Eigen::Vector3d> positions;
  std::vector<double> radii;
  Eigen::Vector3d boxMin = Eigen::Vector3d::Zero(), boxMax = Eigen::Vector3d::Zero();
  double radius{}, spacing{};
  std::int64_t maxParticles{};
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero(), angularVelocity = Eigen::Vector3d::Zero();
  std::int64_t materialId{};
  bool fixed{};
  double density{};
  double normalStiffness{}, normalDamping{}, tangentialStiffness{}, tangentialDamping{};
  double friction{}, rollingFriction{}, cohesionStiffness{}, cohesionMaxDistance{};
  std::string normalContactModel{};
  std::int64_t substeps{};
  bool visible{};
  bool hiddenByGroup = false;
};

// The particles of a granular record in its own frame: its explicit
// positions (radius: radii[i], or radii[0] for all, or `radius`), else the
// box fill RaiSim's addGranularBox makes: centres from boxMin + radius in
// steps of spacing along x, then y, then z, while within boxMax - radius.
// An empty string when they fit in maxParticles (0: no limit of the
// record's own) and in `hardLimit`; else why not, with nothing allocated
// beyond the limit.
std::string granularParticles(const Granular& g, std::uint64_t hardLimit, std::vector<Eigen::Vector3d>& positions,
                              std::vector<double>& radii);

}  // namespace rscene
