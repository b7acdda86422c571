// Deformable records the solver refuses: each names the key at fault,
// before anything large is allocated.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/deformable_test_util.hpp"

using namespace rscene;
using namespace rscene::sim;
using namespace rscene::sim::test;

namespace {

// The key a refused record names, with its message in `error`.
std::string refusedAt(const Deformable& d, const std::string& obj, std::string* error = nullptr) {
  std::string e, field;
  auto body = build(d, obj, &e, &field);
  EXPECT_FALSE(body) << "accepted";
  EXPECT_FALSE(e.empty());
  if (error) *error = e;
  return field;
}

}  // namespace

TEST(DeformableRecords, APinnedIndexOutsideTheMeshIsRefused) {
  Deformable d = defaultRecord();
  d.pinnedVertices = {0, 16};
  std::string error;
  EXPECT_EQ(refusedAt(d, gridObj(4, 1), &error), "pinnedVertices");
  EXPECT_EQ(error, "pinnedVertices 16 is not a vertex of mesh.obj (it has 16)");
  d.pinnedVertices = {-1};
  EXPECT_EQ(refusedAt(d, gridObj(4, 1)), "pinnedVertices");
}

TEST(DeformableRecords, FemNeedsAClosedMesh) {
  std::string error;
  EXPECT_EQ(refusedAt(defaultRecord("fem"), gridObj(4, 1), &error), "meshPath");
  EXPECT_NE(error.find("closed mesh"), std::string::npos) << error;
  // particleMode=surface: a strutted shell, no fill, no closed mesh needed.
  Deformable d = defaultRecord("fem");
  d.particleMode = "surface";
  d.particleSpacing = 0.5;
  auto shell = build(d, gridObj(4, 1));
  ASSERT_TRUE(shell);
  EXPECT_EQ(shell->positions().size(), 16u);
  EXPECT_GT(shell->distanceConstraintCount(), 33u);  // struts beyond the edges
}

TEST(DeformableRecords, AFillPastTheParticleCapIsRefusedBeforeItIsMade) {
  Deformable d = defaultRecord("fem");
  d.particleSpacing = 0.005;  // 200^3 = 8e6 particles in a 1 m cube
  std::string error;
  EXPECT_EQ(refusedAt(d, cubeObj(1), &error), "particleSpacing");
  EXPECT_EQ(error, "a fill at this spacing makes more than 1000000 particles");
  d.particleSpacing = 1e-9;  // 1e18 grid columns: refused before any is tested
  EXPECT_EQ(refusedAt(d, cubeObj(1), &error), "particleSpacing");
  EXPECT_NE(error.find("grid columns"), std::string::npos) << error;
  d.particleSpacing = 0;
  EXPECT_EQ(refusedAt(d, cubeObj(1)), "particleSpacing");
}

TEST(DeformableRecords, HostileValuesAreRefusedAtTheirKey) {
  const std::string obj = gridObj(4, 1);
  struct Case {
    const char* key;
    void (*set)(Deformable&);
  };
  const Case cases[] = {
      {"totalMass", [](Deformable& d) { d.totalMass = NAN; }},
      {"totalMass", [](Deformable& d) { d.totalMass = -1; }},
      {"totalMass", [](Deformable& d) { d.totalMass = 0; }},
      {"distanceCompliance", [](Deformable& d) { d.distanceCompliance = INFINITY; }},
      {"distanceStiffness", [](Deformable& d) { d.distanceCompliance = -1, d.distanceStiffness = 0; }},
      {"bendCompliance", [](Deformable& d) { d.bendCompliance = NAN; }},
      {"youngsModulus", [](Deformable& d) { d.youngsModulus = -5; }},
      {"thickness", [](Deformable& d) { d.youngsModulus = 1e5, d.thickness = 0; }},
      {"poissonRatio", [](Deformable& d) { d.poissonRatio = 0.5; }},
      {"damping", [](Deformable& d) { d.damping = 1.5; }},
      {"damping", [](Deformable& d) { d.damping = NAN; }},
      {"collisionRadius", [](Deformable& d) { d.collisionRadius = -0.01; }},
      {"iterations", [](Deformable& d) { d.iterations = 10001; }},
      {"iterations", [](Deformable& d) { d.iterations = -1; }},
      {"substeps", [](Deformable& d) { d.substeps = 0; }},
      {"substeps", [](Deformable& d) { d.substeps = 1001; }},
      {"scale", [](Deformable& d) { d.scale.x() = NAN; }},
      {"position", [](Deformable& d) { d.world.position.z() = INFINITY; }},
      {"position", [](Deformable& d) { d.world.position.z() = 1e300; }},
      {"kind", [](Deformable& d) { d.kind = "jelly"; }},
  };
  for (const Case& c : cases) {
    Deformable d = defaultRecord();
    c.set(d);
    EXPECT_EQ(refusedAt(d, obj), c.key);
  }
  // A vertex that is finite in the file but not once scaled.
  Deformable d = defaultRecord();
  d.scale = Eigen::Vector3d::Constant(1e300);
  EXPECT_EQ(refusedAt(d, obj), "scale");
  d.scale = Eigen::Vector3d::Constant(100);
  EXPECT_EQ(refusedAt(d, gridObj(4, 1e11)), "meshPath");  // 5e12 m
}

TEST(DeformableRecords, AStepOfUnboundedWorkIsRefused) {
  // 60 x 60 vertices, about 24,000 constraints and particles, 1e7 passes a step.
  Deformable d = defaultRecord();
  d.iterations = 10000;
  d.substeps = 1000;
  std::string error;
  EXPECT_EQ(refusedAt(d, gridObj(60, 1), &error), "iterations");
  EXPECT_NE(error.find("at most 1e+09"), std::string::npos) << error;
}

TEST(DeformableRecords, TheSchemaDefaultsMakeARigidClothThatSteps) {
  auto cloth = build(defaultRecord(), gridObj(4, 1));
  ASSERT_TRUE(cloth);
  AnalyticSurfaces none;
  run(*cloth, none, 0.1);
  EXPECT_TRUE(cloth->finite());
  EXPECT_GT(cloth->maxSpeed(), 0.5);  // falling
}
