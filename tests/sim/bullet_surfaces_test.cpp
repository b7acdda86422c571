// BulletSurfaces against closed-form answers: a sphere probe at known
// places around every shape rscene-sim builds gives the depth, normal and
// surface point geometry says; forces reach Bullet's bodies as F/m.
// Scenes are text, built into a World; a far-away grain gives the world
// its particle surfaces (World::particleSurfaces).  Tolerances: 1e-12 for
// closed forms (round-off only), others stated where asserted.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/loader.hpp"
#include "robot/load.hpp"
#include "scene/scene.hpp"
#include "sim/bullet_surfaces.hpp"
#include "sim/robot_layout.hpp"
#include "sim/world.hpp"
#include "sim/world_test_scene.hpp"

using namespace rscene;
using namespace rscene::sim;
using Eigen::Vector3d;
namespace fs = std::filesystem;

namespace {

constexpr const char* kAll = "18446744073709551615";
constexpr std::uint64_t kAllBits = ~std::uint64_t{0};
const std::string kGrain = "granular /World/Grain particles 0 0 0 1 0 0 0 1 1 1 positions=0,0,90 radii=0.01\n";

struct Run : test::WorldRun {
  BulletSurfaces* surfaces = nullptr;
};

using test::firstMessage;

std::unique_ptr<Run> make(const std::string& body, bool withRobots = false) {
  test::WorldRunOptions options;
  options.robots = withRobots;
  options.checkPhysics = true;
  auto r = std::make_unique<Run>();
  test::buildWorld(*r, body + kGrain, options);
  EXPECT_TRUE(r->world) << firstMessage(r->diags);
  if (r->world) r->surfaces = r->world->particleSurfaces();
  EXPECT_TRUE(r->surfaces);
  return r;
}

// An object record: primitive at a position and orientation (w x y z).
std::string object(const std::string& path, const std::string& prim, const Vector3d& at,
                   const std::string& quat = "1 0 0 0", const std::string& scale = "1 1 1", double radius = 0.5,
                   double height = 1, double mass = 1, const std::string& mode = "static", const std::string& mesh = "-",
                   const std::string& contact = "default", const std::string& group = "1",
                   const std::string& mask = kAll) {
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "object %s %s %.17g %.17g %.17g %s %s %.17g %.17g %.17g %s engine_default false true false %s %s true "
                "%s %s\n",
                path.c_str(), prim.c_str(), at.x(), at.y(), at.z(), quat.c_str(), scale.c_str(), radius, height, mass,
                contact.c_str(), mesh.c_str(), mode.c_str(), group.c_str(), mask.c_str());
  return buf;
}

// The contacts of one probe, after preparing for its neighbourhood.
std::vector<SurfaceContact> probe(BulletSurfaces& s, const Vector3d& c, double r, double margin = 0,
                                  std::uint64_t group = 1, std::uint64_t mask = kAllBits,
                                  const std::string& material = "") {
  Vector3d reach = Vector3d::Constant(r + margin + 0.01);
  s.prepare(Eigen::AlignedBox3d(c - reach, c + reach), group, mask, material);
  std::vector<SurfaceContact> out;
  s.contacts(c, r, margin, out);
  return out;
}

void expectContact(const SurfaceContact& c, const Vector3d& point, const Vector3d& normal, double depth,
                   double tol = 1e-12) {
  EXPECT_NEAR((c.point - point).norm(), 0, tol) << "point " << c.point.transpose() << " want " << point.transpose();
  EXPECT_NEAR((c.normal - normal).norm(), 0, tol) << "normal " << c.normal.transpose() << " want " << normal.transpose();
  EXPECT_NEAR(c.depth, depth, tol);
}

BodyState state(const World& w, const std::string& path) {
  for (const BodyState& s : w.states())
    if (s.path == path) return s;
  ADD_FAILURE() << "no body " << path;
  return {};
}

}  // namespace

TEST(BulletSurfaces, GroundPlane) {
  auto r = make("gravity 0 0 0\n" + object("/World/Ground", "ground", {0, 0, 0.25}));
  auto c = probe(*r->surfaces, {1, 2, 0.3}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {1, 2, 0.25}, Vector3d::UnitZ(), 0.05);
  EXPECT_EQ(c[0].body, -1);
  // Within the margin: a contact of negative depth; beyond it none.
  c = probe(*r->surfaces, {1, 2, 0.38}, 0.1, 0.05);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth, -0.03, 1e-12);
  EXPECT_TRUE(probe(*r->surfaces, {1, 2, 0.38}, 0.1, 0.01).empty());
  // Under the ground: still pushed up, deeper than the radius.
  c = probe(*r->surfaces, {1, 2, 0.05}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {1, 2, 0.25}, Vector3d::UnitZ(), 0.3);
}

TEST(BulletSurfaces, BoxFaceEdgeCornerAndInside) {
  // Half extents 1, 0.5, 0.25 about (0, 0, 5).
  auto r = make("gravity 0 0 0\n" + object("/World/Box", "box", {0, 0, 5}, "1 0 0 0", "2 1 0.5"));
  BulletSurfaces& s = *r->surfaces;
  auto c = probe(s, {1.05, 0.1, 5}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {1, 0.1, 5}, Vector3d::UnitX(), 0.05);
  c = probe(s, {1.03, 0.54, 5.1}, 0.1);  // off the +x +y edge by (0.03, 0.04): 0.05
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {1, 0.5, 5.1}, {0.6, 0.8, 0}, 0.05);
  double a = 0.04;  // off the corner by a on each axis: a sqrt(3)
  c = probe(s, {1 + a, -0.5 - a, 5.25 + a}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {1, -0.5, 5.25}, Vector3d(1, -1, 1).normalized(), 0.1 - a * std::sqrt(3.0));
  // Inside, nearest the +x face (0.1 away; the y faces are 0.4, z 0.15).
  c = probe(s, {0.9, 0.1, 5.1}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {1, 0.1, 5.1}, Vector3d::UnitX(), 0.2);
  // Inside, nearest the -z face.
  c = probe(s, {0.2, 0, 4.8}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {0.2, 0, 4.75}, -Vector3d::UnitZ(), 0.15);
}

TEST(BulletSurfaces, RotatedBox) {
  // The same box turned 90 degrees about z: its long axis along y.
  const double h = std::sqrt(0.5);
  char quat[64];
  std::snprintf(quat, sizeof quat, "%.17g 0 0 %.17g", h, h);
  auto r = make("gravity 0 0 0\n" + object("/World/Box", "box", {3, 0, 5}, quat, "2 1 0.5"));
  auto c = probe(*r->surfaces, {3, 1.05, 5}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {3, 1, 5}, Vector3d::UnitY(), 0.05);
  c = probe(*r->surfaces, {3.55, 0, 5}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {3.5, 0, 5}, Vector3d::UnitX(), 0.05);
}

TEST(BulletSurfaces, Sphere) {
  auto r = make("gravity 0 0 0\n" + object("/World/Ball", "sphere", {3, 0, 5}, "1 0 0 0", "1 1 1", 0.5));
  auto c = probe(*r->surfaces, {3, 0.3, 5.4}, 0.1);  // 0.5 from the centre: on the surface
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {3, 0.3, 5.4}, {0, 0.6, 0.8}, 0.1);
  c = probe(*r->surfaces, {3, 0, 5.3}, 0.1);  // inside, 0.2 under the top
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {3, 0, 5.5}, Vector3d::UnitZ(), 0.3);
}

TEST(BulletSurfaces, CapsuleSideAndCap) {
  // Radius 0.2, a 1 m segment between its caps' centres along z (world.cpp's btCapsuleShapeZ).
  auto r = make("gravity 0 0 0\n" + object("/World/Cap", "capsule", {0, 0, 5}, "1 0 0 0", "1 1 1", 0.2, 1));
  auto c = probe(*r->surfaces, {0.25, 0, 5.3}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {0.2, 0, 5.3}, Vector3d::UnitX(), 0.05);
  c = probe(*r->surfaces, {0.15, 0, 5.5 + 0.2}, 0.1);  // over the top cap: 0.25 from its centre
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], Vector3d(0, 0, 5.5) + 0.2 * Vector3d(0.6, 0, 0.8), {0.6, 0, 0.8}, 0.05);
  c = probe(*r->surfaces, {0, 0.15, 4.8}, 0.1);  // inside, 0.05 from the side
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {0, 0.2, 4.8}, Vector3d::UnitY(), 0.15);
}

TEST(BulletSurfaces, CylinderSideCapRimAndInside) {
  // Radius 0.3, height 1 along z.
  auto r = make("gravity 0 0 0\n" + object("/World/Cyl", "cylinder", {0, 0, 5}, "1 0 0 0", "1 1 1", 0.3, 1));
  BulletSurfaces& s = *r->surfaces;
  auto c = probe(s, {0, -0.35, 5.2}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {0, -0.3, 5.2}, -Vector3d::UnitY(), 0.05);
  c = probe(s, {0.1, 0.1, 5.55}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {0.1, 0.1, 5.5}, Vector3d::UnitZ(), 0.05);
  c = probe(s, {0.33, 0, 5.54}, 0.1);  // off the rim by (0.03, 0.04)
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {0.3, 0, 5.5}, {0.6, 0, 0.8}, 0.05);
  c = probe(s, {0.25, 0, 5}, 0.1);  // inside: 0.05 from the side, 0.5 from the caps
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {0.3, 0, 5}, Vector3d::UnitX(), 0.15);
  c = probe(s, {0, 0, 4.55}, 0.1);  // inside: 0.05 from the bottom cap
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {0, 0, 4.5}, -Vector3d::UnitZ(), 0.15);
}

TEST(BulletSurfaces, ConvexHullOfACubeMesh) {
  // A kinematic mesh object is a convex hull (world.cpp) of the unit cube,
  // with Bullet's 0.001 collision margin around it.  GJK/EPA converge to
  // 1e-6 here (their tolerances are relative to the shape's size).
  std::string cube = std::string(RSCENE_TEST_DATA) + "/render_assets/crate.obj";
  auto r = make("gravity 0 0 0\n" +
                object("/World/Hull", "mesh", {0, 0, 5}, "1 0 0 0", "1 1 1", 0.5, 1, 1, "kinematic", cube));
  BulletSurfaces& s = *r->surfaces;
  auto c = probe(s, {0.6, 0.1, 5.2}, 0.2);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {0.501, 0.1, 5.2}, Vector3d::UnitX(), 0.2 - 0.099, 1e-6);
  EXPECT_GE(c[0].body, 0);  // kinematic: a handle, for its velocity
  EXPECT_NEAR(s.velocity(c[0].body, c[0].point).norm(), 0, 1e-15);
  c = probe(s, {0.3, 0, 5.1}, 0.2);  // inside, 0.201 from the +x face
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {0.501, 0, 5.1}, Vector3d::UnitX(), 0.2 + 0.201, 1e-6);
  // Off the +x +z edge by (0.03, 0.04): 0.05 from the edge, the margin
  // rounding it (GJK/EPA here; the faces' planes answer the cases above).
  c = probe(s, {0.53, 0.2, 5.54}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], Vector3d(0.5, 0.2, 5.5) + 0.001 * Vector3d(0.6, 0, 0.8), {0.6, 0, 0.8}, 0.1 - 0.049, 1e-6);
  // Off a corner.
  c = probe(s, {-0.54, -0.54, 4.46}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  const Vector3d out = Vector3d(-1, -1, -1).normalized();
  expectContact(c[0], Vector3d(-0.5, -0.5, 4.5) + 0.001 * out, out, 0.1 - (0.04 * std::sqrt(3.0) - 0.001), 1e-6);
}

TEST(BulletSurfaces, StaticTriangleMeshPlaneGivesOneContactPerTouch) {
  // A 2 x 2 grid of squares (8 triangles) in z = 0 from -1 to 1: a static
  // mesh object is a two-sided BVH triangle mesh.
  fs::path dir = fs::path(testing::TempDir()) / "bullet_surfaces_mesh";
  fs::create_directories(dir);
  fs::path obj = dir / "grid.obj";
  {
    std::ofstream f(obj);
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 3; ++x) f << "v " << x - 1 << ' ' << y - 1 << " 0\n";
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x) {
        int a = 1 + y * 3 + x, b = a + 1, c = a + 4, d = a + 3;
        f << "f " << a << ' ' << b << ' ' << c << "\nf " << a << ' ' << c << ' ' << d << "\n";
      }
  }
  auto r = make("gravity 0 0 0\n" +
                object("/World/Mesh", "mesh", {0, 0, 2}, "1 0 0 0", "1 1 1", 0.5, 1, 0, "static", obj.string()));
  BulletSurfaces& s = *r->surfaces;
  for (const Vector3d& at : {Vector3d(0.3, 0.2, 0), Vector3d(0.5, 0, 0), Vector3d(0, 0, 0), Vector3d(0.5, 0.5, 0)}) {
    auto c = probe(s, Vector3d(at.x(), at.y(), 2.05), 0.1);  // over a face, an edge, a vertex, a diagonal
    ASSERT_EQ(c.size(), 1u) << "over " << at.transpose();
    expectContact(c[0], Vector3d(at.x(), at.y(), 2), Vector3d::UnitZ(), 0.05);
  }
  auto c = probe(s, {0.3, 0.2, 1.95}, 0.1);  // from below: pushed back down
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {0.3, 0.2, 2}, -Vector3d::UnitZ(), 0.05);
  c = probe(s, {1.03, 0.2, 2.04}, 0.1);  // past the border: its edge
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {1, 0.2, 2}, {0.6, 0, 0.8}, 0.05);
}

TEST(BulletSurfaces, TerrainHeightFieldOfAKnownSlope) {
  // Heights z = 0.5 x over x in [-1, 1], y in [-0.5, 0.5], centred at (0, 0, 1).
  auto r = make("gravity 0 0 0\nterrain_region /World/T 3 2 2 1 0 0 1 heights=-0.5,0,0.5,-0.5,0,0.5\n");
  BulletSurfaces& s = *r->surfaces;
  const Vector3d n = Vector3d(-0.5, 0, 1).normalized();
  const Vector3d foot(0.2, 0.1, 1.1);  // on the surface
  auto c = probe(s, foot + 0.05 * n, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], foot, n, 0.05);
  c = probe(s, foot - 0.03 * n, 0.1);  // under the surface: pushed out along the normal
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], foot, n, 0.13);
  c = probe(s, foot - 0.5 * n, 0.1);  // deeper than the probe's box reaches
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], foot, n, 0.6);
}

TEST(BulletSurfaces, CompoundChild) {
  // One child, a unit box 2 m along x from the compound's frame; the
  // compound simulates about its centre of mass (the child's centre).
  auto r = make("gravity 0 0 0\ncompound /World/C 0 0 5 1 0 0 0 1 1 1 1 static true true\n"
                "compound_child /World/C box 2 0 0 1 0 0 0 1 1 1 size=1,1,1\n"
                "compound_child /World/C sphere -2 0 0 1 0 0 0 1 1 1 radius=0.25\n");
  auto c = probe(*r->surfaces, {2.55, 0.2, 5}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {2.5, 0.2, 5}, Vector3d::UnitX(), 0.05);
  EXPECT_EQ(c[0].body, -1);
  c = probe(*r->surfaces, {-2, 0, 5.3}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {-2, 0, 5.25}, Vector3d::UnitZ(), 0.05);
}

TEST(BulletSurfaces, GroupMaskFiltering) {
  auto r = make("gravity 0 0 0\n" +
                object("/World/A", "box", {0, 0, 5}, "1 0 0 0", "1 1 1", 0.5, 1, 1, "static", "-", "default", "2") +
                object("/World/B", "box", {3, 0, 5}, "1 0 0 0", "1 1 1", 0.5, 1, 1, "static", "-", "default", "1", "1"));
  BulletSurfaces& s = *r->surfaces;
  const Vector3d nearA(0, 0, 5.55), nearB(3, 0, 5.55);
  EXPECT_EQ(probe(s, nearA, 0.1, 0, 1, kAllBits).size(), 1u);  // A's group 2 is in the mask
  EXPECT_TRUE(probe(s, nearA, 0.1, 0, 1, 1).empty());           // not in mask 1
  EXPECT_EQ(probe(s, nearA, 0.1, 0, 1, 2).size(), 1u);
  EXPECT_EQ(probe(s, nearB, 0.1, 0, 1, kAllBits).size(), 1u);  // B's mask 1 takes group 1
  EXPECT_TRUE(probe(s, nearB, 0.1, 0, 4, kAllBits).empty());    // and not group 4
}

TEST(BulletSurfaces, FrictionFromAContactMaterialPair) {
  auto r = make("gravity 0 0 0\ncontact_material rubber sand 0.33 0 0 0.33 0 0 0\n" +
                object("/World/Box", "box", {0, 0, 5}, "1 0 0 0", "1 1 1", 0.5, 1, 1, "static", "-", "rubber"));
  auto c = probe(*r->surfaces, {0, 0, 5.55}, 0.1, 0, 1, kAllBits, "sand");
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].friction, 0.33);
  c = probe(*r->surfaces, {0, 0, 5.55}, 0.1, 0, 1, kAllBits, "");  // no material: the solver's default
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].friction, r->scene.solver.defaultFriction);
  c = probe(*r->surfaces, {0, 0, 5.55}, 0.1, 0, 1, kAllBits, "felt");  // no such pair
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].friction, r->scene.solver.defaultFriction);
}

TEST(BulletSurfaces, ForceAndTorqueMoveAFreeBodyByTheirClosedForms) {
  // A 2 kg box of 1 x 1 x 1 m, no gravity, dt 0.01: a force F at the
  // centre moves it F/m dt^2 in one semi-implicit Euler step; a force off
  // the centre adds torque r x F, angular velocity I^-1 (r x F) dt.
  auto r = make("time_step 0.01\ngravity 0 0 0\n" +
                object("/World/Box", "box", {0, 0, 5}, "1 0 0 0", "1 1 1", 0.5, 1, 2, "dynamic"));
  BulletSurfaces& s = *r->surfaces;
  auto c = probe(s, {0, 0, 5.55}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  int body = c[0].body;
  ASSERT_GE(body, 0);
  s.addForce(body, {0, 0, 5}, {4, 0, 0});
  r->world->step();  // World::step applies the forces before Bullet's step
  BodyState b = state(*r->world, "/World/Box");
  const double dt = 0.01;
  EXPECT_NEAR(b.position.x(), 4.0 / 2 * dt * dt, 1e-15);
  EXPECT_NEAR(b.linearVelocity.x(), 4.0 / 2 * dt, 1e-15);
  r->world->step();  // Bullet cleared the force: the velocity stays
  b = state(*r->world, "/World/Box");
  EXPECT_NEAR(b.linearVelocity.x(), 4.0 / 2 * dt, 1e-15);
  EXPECT_NEAR(b.position.x(), 2 * 4.0 / 2 * dt * dt, 1e-15);

  s.prepare(Eigen::AlignedBox3d(Vector3d(-1, -1, 4), Vector3d(1, 1, 6)), 1, kAllBits, "");
  Vector3d com = b.position;
  s.addForce(body, com + Vector3d(0, 1, 0), {3, 0, 0});  // torque (0, 1, 0) x (3, 0, 0) = (0, 0, -3)
  s.addForce(body, com + Vector3d(0, -1, 0), {1, 0, 0});  // (0, 0, 1): summed, -2 about z
  r->world->step();
  b = state(*r->world, "/World/Box");
  const double izz = 2.0 / 12 * (1 + 1);
  EXPECT_NEAR(b.angularVelocity.z(), -2 / izz * dt, 1e-12);
  EXPECT_NEAR(b.linearVelocity.x(), 4.0 / 2 * dt + 4.0 / 2 * dt, 1e-12);
  // Its velocity at a point: v + w x (p - com).
  s.prepare(Eigen::AlignedBox3d(Vector3d(-1, -1, 4), Vector3d(1, 1, 6)), 1, kAllBits, "");
  Vector3d p = b.position + Vector3d(0.5, 0, 0);
  Vector3d want = b.linearVelocity + b.angularVelocity.cross(p - b.position);
  EXPECT_NEAR((s.velocity(body, p) - want).norm(), 0, 1e-12);
}

TEST(BulletSurfaces, ASleepingBodyWakesForAPushAndSleepsUnderALightLoad) {
  // A 1 kg box resting on the ground falls asleep (sleeping is on by
  // default).  A load that would change its velocity by less than its
  // sleeping threshold (0.002 m/s) within a step leaves it asleep; a
  // push above it wakes it and moves it.
  auto r = make("time_step 0.01\ngravity 0 0 -9.81\n" + object("/World/Ground", "ground", {0, 0, 0}) +
                object("/World/Box", "box", {0, 0, 0.5}, "1 0 0 0", "1 1 1", 0.5, 1, 1, "dynamic"));
  for (int i = 0; i < 500 && !state(*r->world, "/World/Box").sleeping; ++i) r->world->step();
  ASSERT_TRUE(state(*r->world, "/World/Box").sleeping);
  BulletSurfaces& s = *r->surfaces;
  auto c = probe(s, {0, 0, 1.05}, 0.1);
  ASSERT_EQ(c.size(), 1u);  // the box's top
  int body = c[0].body;
  ASSERT_GE(body, 0);
  Vector3d before = state(*r->world, "/World/Box").position;
  s.addForce(body, {0, 0, 1}, {0.1, 0, -0.1});  // 0.1 N x 0.01 s / 1 kg = 0.001 m/s
  r->world->step();
  EXPECT_TRUE(state(*r->world, "/World/Box").sleeping);
  EXPECT_EQ(state(*r->world, "/World/Box").position, before);
  s.addForce(body, {0, 0, 0.5}, {50, 0, 0});  // 0.5 m/s within the step: wakes, slides
  r->world->step();
  BodyState b = state(*r->world, "/World/Box");
  EXPECT_FALSE(b.sleeping);
  EXPECT_GT(b.linearVelocity.x(), 0.1);
}

TEST(BulletSurfaces, ABodyThatLeftTheWorldIsNoCandidate) {
  // A box falls past the floor margin (10 m under the lowest static) and
  // leaves the world; it is no longer met nor pushed.
  auto r = make("time_step 0.01\ngravity 0 0 -9.81\n" + object("/World/Floor", "box", {50, 0, 0}) +
                object("/World/Box", "box", {0, 0, 0}, "1 0 0 0", "1 1 1", 0.5, 1, 1, "dynamic"));
  BulletSurfaces& s = *r->surfaces;
  auto c = probe(s, {0, 0, 0.55}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  int body = c[0].body;
  for (int i = 0; i < 300 && r->world->departures().empty(); ++i) r->world->step();
  ASSERT_EQ(r->world->departures().size(), 1u);
  Vector3d at = state(*r->world, "/World/Box").position;
  s.prepare(Eigen::AlignedBox3d(Vector3d::Constant(-1e9), Vector3d::Constant(1e9)), 1, kAllBits, "");
  std::vector<SurfaceContact> out;
  s.contacts(at, 0.1, 0, out);
  EXPECT_TRUE(out.empty());
  s.addForce(body, at, {1e6, 0, 0});
  r->world->step();
  EXPECT_EQ(state(*r->world, "/World/Box").position, at);
}

TEST(BulletSurfaces, PushesARobotLinkAndGivesItsVelocity) {
  // The quadruped of examples/robot_cell.rscene floating in zero gravity,
  // moving.  A force on its base changes the robot's momentum by F dt in
  // one step (Featherstone conserves it otherwise); the velocity of a
  // link's point is what World::robotPointVelocity says.
  std::string urdf = std::string(RSCENE_SOURCE_DIR) + "/examples/robots/quadruped/quadruped.urdf";
  std::string text = "time_step 0.001\ngravity 0 0 0\narticulated_resource res Robot " + urdf +
                     "\narticulated /World/Robot res 0 0 1 1 0 0 0 true true "
                     "generalizedCoordinate=0,0,1,1,0,0,0,0,0.6,-1.2,0,0.6,-1.2,0,-0.6,1.2,0,-0.6,1.2 "
                     "generalizedVelocity=0.1,0.2,0.3,0.4,-0.2,0.5,0.3,0.3,0.3,0.3,0.3,0.3,0.3,0.3,0.3,0.3,0.3,0.3\n";
  auto r = make(text, true);
  ASSERT_TRUE(r->world);
  BulletSurfaces& s = *r->surfaces;
  // The base box (0.5 x 0.22 x 0.12) from above.
  std::vector<SurfaceContact> c = probe(s, {0, 0, 1 + 0.06 + 0.05}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], {0, 0, 1.06}, Vector3d::UnitZ(), 0.05, 1e-9);  // the initial pose, through Bullet's frames
  int base = c[0].body;
  ASSERT_GE(base, 0);
  Vector3d v, w, p(0.1, 0.05, 1.06);
  ASSERT_TRUE(r->world->robotPointVelocity("/World/Robot", 0, p, v, w));
  EXPECT_NEAR((s.velocity(base, p) - v).norm(), 0, 1e-12);

  const robot::Model& model = *r->robots[0].model;
  int shank = -1;
  for (std::size_t i = 0; i < model.links.size(); ++i)
    if (model.links[i].name == "LF_SHANK") shank = static_cast<int>(i);
  ASSERT_GE(shank, 0);
  std::optional<Pose> linkPose = r->world->robotLinkPose("/World/Robot", shank);
  ASSERT_TRUE(linkPose);
  Vector3d mid = (*linkPose * Pose{Vector3d(0, 0, -0.11), Eigen::Quaterniond::Identity()}).position;  // its capsule's centre
  c = probe(s, mid, 0.001);
  ASSERT_GE(c.size(), 1u);
  const SurfaceContact* inside = nullptr;
  for (const SurfaceContact& x : c)
    if (x.depth > 0.015) inside = &x;  // inside the shank's capsule (radius 0.02)
  ASSERT_TRUE(inside);
  EXPECT_NEAR(inside->depth, 0.001 + 0.02, 1e-9);
  ASSERT_TRUE(r->world->robotPointVelocity("/World/Robot", shank, mid, v, w));
  EXPECT_NEAR((s.velocity(inside->body, mid) - v).norm(), 0, 1e-12);

  // The push, on the same robot at rest.  Its momentum is measured at the
  // pose after the step, which the push itself moved, with the joints'
  // damping acting on the motion it started: F dt to 1e-5 of itself, not
  // to round-off.
  std::string still = text.substr(0, text.find(" generalizedVelocity=")) + "\n";
  auto rest = make(still, true);
  BulletSurfaces& s2 = *rest->surfaces;
  c = probe(s2, {0, 0, 1 + 0.06 + 0.05}, 0.1);
  ASSERT_EQ(c.size(), 1u);
  RobotLayout layout = makeLayout(model);
  auto momentum = [&](const World& world) {
    Vector3d m = Vector3d::Zero();
    RobotState st = world.robotStates()[0];
    for (std::size_t b = 0; b < layout.bodies.size(); ++b) m += layout.bodies[b].mass * st.bodyLinearVelocities[b];
    return m;
  };
  s2.addForce(c[0].body, {0, 0, 1.06}, {0, 0, 30});
  rest->world->step();
  Vector3d change = momentum(*rest->world);
  EXPECT_NEAR((change - Vector3d(0, 0, 30 * 0.001)).norm(), 0, 3e-7);
}

TEST(BulletSurfaces, SameQueriesSameResultsInTheSameOrder) {
  std::string scene = "gravity 0 0 0\n" + object("/World/Ground", "ground", {0, 0, 0}) +
                      object("/World/A", "box", {0, 0, 0.3}, "1 0 0 0", "1 1 0.6") +
                      object("/World/B", "sphere", {0.4, 0, 0.3}, "1 0 0 0", "1 1 1", 0.3, 1, 1, "dynamic") +
                      object("/World/C", "capsule", {-0.3, 0.2, 0.4}, "0.9 0.1 0.3 0.2", "1 1 1", 0.2, 0.5, 1, "dynamic");
  auto collect = [&](BulletSurfaces& s) {
    std::vector<SurfaceContact> out;
    s.prepare(Eigen::AlignedBox3d(Vector3d(-1, -1, -1), Vector3d(1, 1, 1)), 1, kAllBits, "");
    for (int i = 0; i < 400; ++i) {
      Vector3d c(-0.8 + 0.004 * i, 0.3 * std::sin(i * 0.1), 0.1 + 0.002 * i);
      s.contacts(c, 0.15, 0.01, out);
    }
    return out;
  };
  auto r1 = make(scene), r2 = make(scene);
  auto a = collect(*r1->surfaces), b = collect(*r2->surfaces), again = collect(*r1->surfaces);
  ASSERT_GT(a.size(), 400u);  // more than the ground alone
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), again.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (const auto* x : {&b[i], &again[i]}) {
      EXPECT_EQ(a[i].point, x->point);
      EXPECT_EQ(a[i].normal, x->normal);
      EXPECT_EQ(a[i].depth, x->depth);
      EXPECT_EQ(a[i].body, x->body);
    }
  }
}

TEST(BulletSurfaces, ScaledAndShiftedHeightField) {
  // Heights z = 0.25 x + 0.5 (relative to the centre) over x in [-2, 2]
  // (3 samples: 2 m apart, Bullet's local scaling 2) and y in [-1, 1]
  // (5 samples, 0.5 apart), centred at (10, -3, 2): the field's box is
  // not centred on its record's centre (Bullet's origin shift).
  auto r = make("gravity 0 0 0\nterrain_region /World/T 3 5 4 2 10 -3 2 "
                "heights=0,0.5,1,0,0.5,1,0,0.5,1,0,0.5,1,0,0.5,1\n");
  BulletSurfaces& s = *r->surfaces;
  const Vector3d n = Vector3d(-0.25, 0, 1).normalized();
  const Vector3d foot(10 + 1.3, -3 + 0.2, 2 + 0.5 + 0.25 * 1.3);
  auto c = probe(s, foot + 0.04 * n, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], foot, n, 0.06);
  c = probe(s, foot - 0.2 * n, 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], foot, n, 0.3);
}

TEST(BulletSurfaces, AGrooveInAMeshGivesOneContactPerSide) {
  // Two faces meeting at 90 degrees along the y axis (a V of slopes +-1):
  // a probe low in the groove touches both.
  fs::path dir = fs::path(testing::TempDir()) / "bullet_surfaces_groove";
  fs::create_directories(dir);
  fs::path obj = dir / "groove.obj";
  {
    std::ofstream f(obj);
    f << "v -1 -1 1\nv 0 -1 0\nv 1 -1 1\nv -1 1 1\nv 0 1 0\nv 1 1 1\n"
         "f 1 2 5\nf 1 5 4\nf 2 3 6\nf 2 6 5\n";
  }
  auto r = make("gravity 0 0 0\n" +
                object("/World/V", "mesh", {0, 0, 0}, "1 0 0 0", "1 1 1", 0.5, 1, 0, "static", obj.string()));
  const double h = std::sqrt(0.5);
  auto c = probe(*r->surfaces, {0, 0.3, 0.1 / h}, 0.12);  // 0.1 from each face
  ASSERT_EQ(c.size(), 2u);
  for (const SurfaceContact& x : c) {
    EXPECT_NEAR(x.depth, 0.02, 1e-12);
    EXPECT_NEAR(std::abs(x.normal.x()), h, 1e-12);
    EXPECT_NEAR(x.normal.z(), h, 1e-12);
  }
  EXPECT_NEAR(c[0].normal.x() + c[1].normal.x(), 0, 1e-12);  // one per side
}

TEST(BulletSurfaces, HostileValuesGiveNothingRatherThanGarbage) {
  auto r = make("gravity 0 0 0\n" + object("/World/Ground", "ground", {0, 0, 0}) +
                object("/World/Box", "box", {0, 0, 0.5}, "1 0 0 0", "1 1 1", 0.5, 1, 1, "dynamic"));
  BulletSurfaces& s = *r->surfaces;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  std::vector<SurfaceContact> out;
  // A region with NaN or infinite corners considers every body.
  s.prepare(Eigen::AlignedBox3d(Vector3d(nan, 0, 0), Vector3d(1, 1, inf)), 1, kAllBits, "");
  s.contacts({0, 0, 1.05}, 0.1, 0, out);
  EXPECT_EQ(out.size(), 1u);
  out.clear();
  s.contacts({nan, 0, 1}, 0.1, 0, out);
  s.contacts({0, 0, 1}, nan, 0, out);
  s.contacts({0, 0, 1}, -1, 0, out);  // a negative reach touches nothing
  s.contacts({0, 0, 1}, 0.1, -inf, out);
  EXPECT_TRUE(out.empty());
  // A huge probe meets both, finitely.
  s.contacts({0, 0, 1}, 1e300, 0, out);
  ASSERT_EQ(out.size(), 2u);
  for (const SurfaceContact& x : out) EXPECT_TRUE(x.point.allFinite() && x.normal.allFinite());
  // An empty region (a system with no particles) prepares nothing.
  s.prepare(Eigen::AlignedBox3d(), 1, kAllBits, "");
  out.clear();
  s.contacts({0, 0, 1.05}, 0.1, 0, out);
  EXPECT_TRUE(out.empty());
  // Non-finite forces, and handles that are no body's, are dropped.
  s.prepare(Eigen::AlignedBox3d(Vector3d(-1, -1, -1), Vector3d(2, 2, 2)), 1, kAllBits, "");
  s.contacts({0, 0, 1.05}, 0.1, 0, out);
  ASSERT_EQ(out.size(), 1u);
  s.addForce(out[0].body, {0, 0, 1}, {nan, 0, 0});
  s.addForce(out[0].body, {inf, 0, 1}, {1, 0, 0});
  s.addForce(12345, {0, 0, 1}, {1, 0, 0});
  s.addForce(-7, {0, 0, 1}, {1, 0, 0});
  EXPECT_EQ(s.velocity(12345, {0, 0, 0}), Vector3d::Zero());
  r->world->step();
  EXPECT_EQ(state(*r->world, "/World/Box").linearVelocity, Vector3d::Zero());
}

TEST(BulletSurfaces, AFastBodyIsMetWhereItIsNotWhereTheBroadphaseLastSawIt) {
  // 100 m/s with dt 0.01: 1 m a step, far past the broadphase's padding
  // (Bullet updates its boxes before it integrates a step).
  auto r = make("time_step 0.01\ngravity 0 0 0\n" +
                object("/World/Box", "box", {0, 0, 5}, "1 0 0 0", "1 1 1", 0.5, 1, 1, "dynamic"));
  ASSERT_TRUE(r->world->setLinearVelocity("/World/Box", {100, 0, 0}));
  r->world->step();
  Vector3d at = state(*r->world, "/World/Box").position;
  ASSERT_NEAR(at.x(), 1, 1e-12);
  auto c = probe(*r->surfaces, at + Vector3d(0, 0, 0.55), 0.1);
  ASSERT_EQ(c.size(), 1u);
  expectContact(c[0], at + Vector3d(0, 0, 0.5), Vector3d::UnitZ(), 0.05);
  EXPECT_NEAR((r->surfaces->velocity(c[0].body, c[0].point) - Vector3d(100, 0, 0)).norm(), 0, 1e-12);
  EXPECT_TRUE(probe(*r->surfaces, Vector3d(0, 0, 5.55), 0.1).empty());  // not where it was
}

TEST(BulletSurfaces, NonCollidableBodiesAreNoSurfaces) {
  // collidable=false: an object is visual only (no body); a robot's
  // colliders get group 0, which meets nothing.
  std::string urdf = std::string(RSCENE_SOURCE_DIR) + "/examples/robots/quadruped/quadruped.urdf";
  std::string objectOff = object("/World/Box", "box", {3, 0, 1}, "1 0 0 0", "1 1 1", 0.5, 1, 1, "static");
  objectOff.replace(objectOff.find(" static true "), 13, " static false ");
  auto r = make("gravity 0 0 0\narticulated_resource res Robot " + urdf +
                    "\narticulated /World/Robot res 0 0 1 1 0 0 0 true false "
                    "generalizedCoordinate=0,0,1,1,0,0,0,0,0.6,-1.2,0,0.6,-1.2,0,-0.6,1.2,0,-0.6,1.2\n" + objectOff,
                true);
  EXPECT_TRUE(probe(*r->surfaces, {0, 0, 1.11}, 0.1).empty());  // the robot's base
  EXPECT_TRUE(probe(*r->surfaces, {3, 0, 1.55}, 0.1).empty());  // the box
}
