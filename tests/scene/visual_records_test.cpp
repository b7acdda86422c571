// The look records (decals, fog and irradiance volumes, reflection probes,
// terrain foliage) and the soft and granular bodies in the scene model:
// schema defaults, parent frames, the granular box fill and its bounds.
#include <gtest/gtest.h>

#include "core/loader.hpp"
#include "scene/scene.hpp"
#include "test_util.hpp"

using namespace rscene;

namespace {

struct Built {
  Scene scene;
  Diagnostics diags;
  bool ok = false;
};

Built build(std::string text) {
  Built b;
  LoadResult r = parse(std::move(text));
  EXPECT_TRUE(r.ok()) << (r.diagnostics.empty() ? "" : r.diagnostics[0].message);
  b.ok = buildScene(r.document, {}, b.scene, b.diags);
  return b;
}

TEST(VisualRecords, DefaultsComeFromTheSchema) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "projected_decal /World/D 1 2 0 1 0 0 0 1 1 1\n"
      "local_fog /World/F 0 0 1 2\n"
      "irradiance_volume /World/I 0 0 1 1 0 0 0 1 1 1\n"
      "reflection_probe /World/P 0 0 1.5 4\n");
  ASSERT_TRUE(b.ok);
  ASSERT_EQ(b.scene.decals.size(), 1u);
  const Decal& d = b.scene.decals[0];
  EXPECT_EQ(d.color, Eigen::Vector4d(1, 1, 1, 1));
  EXPECT_EQ(d.halfExtents, Eigen::Vector3d(0.5, 0.5, 0.5));
  EXPECT_DOUBLE_EQ(d.albedoMix, 1);
  EXPECT_TRUE(d.enabled);
  EXPECT_EQ(d.world.position, Eigen::Vector3d(1, 2, 0));
  ASSERT_EQ(b.scene.localFogs.size(), 1u);
  EXPECT_DOUBLE_EQ(b.scene.localFogs[0].radius, 2);
  EXPECT_DOUBLE_EQ(b.scene.localFogs[0].density, 0.5);
  ASSERT_EQ(b.scene.irradianceVolumes.size(), 1u);
  EXPECT_DOUBLE_EQ(b.scene.irradianceVolumes[0].strength, 1);
  ASSERT_EQ(b.scene.reflectionProbes.size(), 1u);
  EXPECT_EQ(b.scene.reflectionProbes[0].cubemapSize, 128);
  EXPECT_DOUBLE_EQ(b.scene.reflectionProbes[0].radius, 4);
  EXPECT_TRUE(b.scene.skipped.empty());
}

TEST(VisualRecords, ParentGroupsCarryThem) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "group /World/G id=g position=10,0,0\n"
      "local_fog /World/G/F 0 0 1 2 parentGroupId=g\n"
      "projected_decal /World/G/D 1 0 0 1 0 0 0 1 1 1 parentGroupId=g\n");
  ASSERT_TRUE(b.ok);
  // Groups are folders (no transform of their own): world = local.
  EXPECT_EQ(b.scene.localFogs[0].center, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(b.scene.decals[0].world.position, Eigen::Vector3d(1, 0, 0));
}

TEST(VisualRecords, FoliageLayersJoinTheirTerrain) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "terrain_region /World/T 2 2 4 4 0 0 0 id=t heights=0,0,0,0\n"
      "terrain_foliage_layer /World/T id=grass density=1,0,0,1 densityPerSquareMeter=50 seed=7\n");
  ASSERT_TRUE(b.ok) << b.diags.size();
  ASSERT_EQ(b.scene.terrains.size(), 1u);
  ASSERT_EQ(b.scene.terrains[0].foliageLayers.size(), 1u);
  const FoliageLayer& l = b.scene.terrains[0].foliageLayers[0];
  EXPECT_EQ(l.density, (std::vector<double>{1, 0, 0, 1}));
  EXPECT_DOUBLE_EQ(l.densityPerSquareMeter, 50);
  EXPECT_EQ(l.seed, 7);
  EXPECT_EQ(l.primitive, "grass_blade");
  EXPECT_DOUBLE_EQ(l.maxSlopeDegrees, 90);
}

TEST(VisualRecords, FoliageDensityOfTheWrongLengthIsAnError) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "terrain_region /World/T 2 2 4 4 0 0 0 id=t heights=0,0,0,0\n"
      "terrain_foliage_layer /World/T density=1,0\n");
  EXPECT_FALSE(b.ok);
}

TEST(VisualRecords, DeformableScaleIsThePositionalTimesTheNamed) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "deformable /World/Flag cloth flag.obj 0 0 2 1 0 0 0 1 2 1 scale=2 pinnedVertices=0,3 totalMass=0.2\n");
  ASSERT_TRUE(b.ok);
  ASSERT_EQ(b.scene.deformables.size(), 1u);
  const Deformable& d = b.scene.deformables[0];
  EXPECT_EQ(d.scale, Eigen::Vector3d(2, 4, 2));
  EXPECT_EQ(d.pinnedVertices, (std::vector<std::int64_t>{0, 3}));
  EXPECT_DOUBLE_EQ(d.totalMass, 0.2);
  EXPECT_EQ(d.kind, "cloth");
}

TEST(VisualRecords, GranularBoxFillFollowsRaiSim) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "granular /World/S particles 0 0 0 1 0 0 0 1 1 1 boxMin=0,0,0 boxMax=0.1,0.05,0.05 radius=0.01 "
      "spacing=0.025\n");
  ASSERT_TRUE(b.ok);
  std::vector<Eigen::Vector3d> p;
  std::vector<double> r;
  ASSERT_EQ(granularParticles(b.scene.granulars[0], 1'000'000, p, r), "");
  // x: 0.01, 0.035, 0.06, 0.085 (0.11 > 0.09); y and z: 0.01, 0.035.
  ASSERT_EQ(p.size(), 4u * 2 * 2);
  EXPECT_NEAR(p[0].x(), 0.01, 1e-12);
  EXPECT_NEAR(p[3].x(), 0.085, 1e-12);
  EXPECT_NEAR(p[4].y(), 0.035, 1e-12);
  EXPECT_NEAR(p.back().z(), 0.035, 1e-12);
  EXPECT_EQ(r, std::vector<double>(16, 0.01));
}

TEST(VisualRecords, GranularFillBeyondItsLimitsIsRefusedBeforeAllocating) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "granular /World/S particles 0 0 0 1 0 0 0 1 1 1 boxMin=-1e6,-1e6,-1e6 boxMax=1e6,1e6,1e6 radius=0.001 "
      "spacing=0.002 maxParticles=0\n"
      "granular /World/T particles 0 0 0 1 0 0 0 1 1 1 boxMin=0,0,0 boxMax=1,1,1 maxParticles=10\n");
  ASSERT_TRUE(b.ok);
  std::vector<Eigen::Vector3d> p;
  std::vector<double> r;
  std::string why = granularParticles(b.scene.granulars[0], 1'000'000, p, r);
  EXPECT_NE(why.find("limit of 1000000"), std::string::npos) << why;
  EXPECT_TRUE(p.empty());
  why = granularParticles(b.scene.granulars[1], 1'000'000, p, r);
  EXPECT_NE(why.find("maxParticles 10"), std::string::npos) << why;
}

TEST(VisualRecords, GranularExplicitPositionsWinOverTheBox) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "granular /World/S particles 0 0 0 1 0 0 0 1 1 1 positions=0,0,1;0,0,2 radii=0.1,0.2 boxMin=0,0,0 "
      "boxMax=1,1,1\n");
  ASSERT_TRUE(b.ok);
  std::vector<Eigen::Vector3d> p;
  std::vector<double> r;
  ASSERT_EQ(granularParticles(b.scene.granulars[0], 100, p, r), "");
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[1], Eigen::Vector3d(0, 0, 2));
  EXPECT_EQ(r, (std::vector<double>{0.1, 0.2}));
}

TEST(VisualRecords, LightShadowAndPostSettingsAreRead) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "environment 0.1 0.1 0.1 0.2 0.2 0.2 0 true true 10 - bloomIntensity=0.3 fxaa=true\n"
      "rayrai_render preset=high custom=true shadowPcfRadius=2 autoExposure=true\n"
      "light /World/L 0 0 -1 2 type=spot position=0,0,3 shadowResolution=512 shadowStrength=0.5\n"
      "wire /World/W stiff - - 1 visualizationWidth=0.05\n");
  ASSERT_TRUE(b.ok);
  EXPECT_DOUBLE_EQ(b.scene.environment.bloomIntensity, 0.3);
  EXPECT_TRUE(b.scene.environment.fxaa);
  EXPECT_FALSE(b.scene.environment.ssao);
  EXPECT_TRUE(b.scene.renderSettings.custom);
  EXPECT_DOUBLE_EQ(b.scene.renderSettings.shadowPcfRadius, 2);
  EXPECT_TRUE(b.scene.renderSettings.autoExposure);
  ASSERT_EQ(b.scene.lights.size(), 1u);
  EXPECT_EQ(b.scene.lights[0].shadowResolution, 512);
  EXPECT_DOUBLE_EQ(b.scene.lights[0].shadowStrength, 0.5);
  EXPECT_DOUBLE_EQ(b.scene.lights[0].shadowBias, 0.0008);
  ASSERT_EQ(b.scene.wires.size(), 1u);
  EXPECT_DOUBLE_EQ(b.scene.wires[0].visualizationWidth, 0.05);
}

}  // namespace
