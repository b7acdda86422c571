// Deformable particles against the rigid world (AnalyticSurfaces): a cloth
// draping over a sphere, reactions on a dynamic body, a fem cube on the
// ground, and identical runs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "sim/deformable_test_util.hpp"

using namespace rscene;
using namespace rscene::sim;
using namespace rscene::sim::test;

namespace {

// A 2 m cloth of 21 x 21 vertices 0.3 m above a sphere of radius 0.5 at
// the origin, the ground at z = -2.
struct Drape {
  AnalyticSurfaces world;
  std::unique_ptr<XpbdDeformable> cloth;
  Drape() {
    world.groundHeights = {-2};
    world.spheres.push_back({});
    world.spheres[0].radius = 0.5;
    Deformable d = defaultRecord();
    d.world.position = {0, 0, 0.8};
    d.totalMass = 0.5;
    d.bendCompliance = 1000;  // rad/(N m): a limp fabric (1 mN m bends a hinge by 1 rad)
    d.collisionRadius = 0.02;
    d.damping = 0.02;
    cloth = build(d, gridObj(21, 2));
  }
};

}  // namespace

TEST(DeformableContact, ClothDropsOnASphereAndDrapesOverIt) {
  Drape s;
  ASSERT_TRUE(s.cloth);
  double deepest = 0;
  for (int i = 0; i < 600; ++i) {  // 3 s
    s.cloth->step(0.005, {0, 0, -9.81}, s.world);
    for (const auto& p : s.cloth->positions()) deepest = std::max(deepest, 0.5 + 0.02 - p.norm());
  }
  // No particle's sphere ever inside the sphere by more than 1 mm: the
  // contacts are projected last in every iteration, and what the distance
  // constraints pull back in is the little left of the last pass.
  EXPECT_LT(deepest, 1e-3);
  // Draped: the centre rests on top, the edges hang below the equator.
  const auto& p = s.cloth->positions();
  EXPECT_NEAR(p[10 * 21 + 10].z(), 0.52, 0.01);
  // (The corners are 1.41 m from the top: they fall about 0.6 m below the
  // equator; the middles of the sides, 1 m out, gather in folds near it.)
  for (int corner : {0, 20, 420, 440}) EXPECT_LT(p[static_cast<std::size_t>(corner)].z(), -0.3) << corner;
  // Nothing went through to the ground, and friction held it on top.
  EXPECT_GT(lowest(p), -2);
  EXPECT_LT(std::abs(centroid(p).x()) + std::abs(centroid(p).y()), 0.05);
}

TEST(DeformableContact, RunsAreIdenticalBitForBit) {
  Drape a, b;
  for (int i = 0; i < 200; ++i) {
    a.cloth->step(0.005, {0, 0, -9.81}, a.world);
    b.cloth->step(0.005, {0, 0, -9.81}, b.world);
  }
  const auto &pa = a.cloth->positions(), &pb = b.cloth->positions();
  ASSERT_EQ(pa.size(), pb.size());
  EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(pa[0])), 0);
}

TEST(DeformableContact, ARestingClothPushesADynamicSphereWithItsWeight) {
  // A 0.4 m cloth on top of a 1 m sphere that takes forces: once at rest,
  // one step's reaction averages the cloth's weight.
  AnalyticSurfaces world;
  world.spheres.push_back({});
  world.spheres[0].radius = 1;
  world.spheres[0].dynamic = true;
  Deformable d = defaultRecord();
  d.world.position = {0, 0, 1.05};
  d.totalMass = 0.3;
  d.damping = 0.05;
  auto cloth = build(d, gridObj(5, 0.4));
  run(*cloth, world, 2);
  world.spheres[0].force.setZero();
  cloth->step(0.005, {0, 0, -9.81}, world);
  // Within 1%: what is left of the settling motion after 2 s.
  EXPECT_NEAR(world.spheres[0].force.z(), -0.3 * 9.81, 0.01 * 0.3 * 9.81);
  EXPECT_NEAR(world.spheres[0].force.x(), 0, 0.01);
  EXPECT_NEAR(world.spheres[0].force.y(), 0, 0.01);
}

TEST(DeformableContact, NotCollidableFallsThrough) {
  Drape s;
  Deformable d = defaultRecord();
  d.collidable = false;
  d.damping = 0;
  d.world.position = {0, 0, 0.8};
  auto ghost = build(d, gridObj(5, 2));
  run(*ghost, s.world, 1);
  // Free fall through the sphere and the ground, as the semi-implicit
  // integrator has it after n = 200 steps: g dt^2 n (n + 1) / 2.
  EXPECT_NEAR(centroid(ghost->positions()).z(), 0.8 - 9.81 * 0.005 * 0.005 * 200 * 201 / 2, 1e-9);
}

TEST(DeformableContact, FemCubeFallsOnTheGroundAndKeepsItsVolume) {
  AnalyticSurfaces world;
  world.groundHeights = {0};
  Deformable d = defaultRecord("fem");
  d.world.position = {0, 0, 1};
  d.particleSpacing = 0.1;
  d.distanceCompliance = 1e-6;
  d.bendCompliance = -1;  // no bending: the struts alone hold the shape
  d.bendStiffness = 0;
  d.damping = 0.02;
  const std::string obj = cubeObj(0.4);
  auto cube = build(d, obj);
  ASSERT_TRUE(cube);
  // 8 corners + a 4 x 4 x 4 fill at 0.1 m.
  EXPECT_EQ(cube->positions().size(), 8u + 64u);
  EXPECT_EQ(cube->surfaceVertexCount(), 8u);
  const asset::ObjSurface surface = surfaceOf(obj);
  auto volume = [&] {  // of the closed surface, by the divergence theorem
    double v = 0;
    const auto& p = cube->positions();
    for (const auto& t : surface.triangles) v += p[t[0]].dot(p[t[1]].cross(p[t[2]])) / 6;
    return std::abs(v);
  };
  const double before = volume();
  EXPECT_NEAR(before, 0.064, 1e-12);
  run(*cube, world, 2);
  // On the ground (corners at the collision radius) and not squashed:
  // the struts keep the volume within 5% under its own weight.
  EXPECT_NEAR(lowest(cube->positions()), 0.01, 2e-3);
  EXPECT_NEAR(volume(), before, 0.05 * before);
  EXPECT_LT(cube->maxSpeed(), 0.01);
}
