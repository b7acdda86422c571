// The plumbing between the particle systems and the rigid world: World
// builds the particles' view of its bodies only when the scene has
// particle systems, and the reactions a system adds during World::step
// act in that same step (applied after the systems stepped, before
// Bullet's step) and only in it.  The solvers' own end-to-end tests live
// beside the solvers.
#include <gtest/gtest.h>

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

namespace {

constexpr std::uint64_t kAllBits = ~std::uint64_t{0};
const std::string kBox =
    "object /World/Box box 0 0 5 1 0 0 0 1 1 1 0.5 1 2 default engine_default false true false - dynamic true 1 "
    "18446744073709551615\n";
const std::string kGrain = "granular /World/Grain particles 0 0 0 1 0 0 0 1 1 1 positions=0,0,90 radii=0.01\n";

std::unique_ptr<test::WorldRun> make(const std::string& body, bool withRobots = false) {
  test::WorldRunOptions options;
  options.robots = withRobots;
  std::unique_ptr<test::WorldRun> r = test::buildWorld("time_step 0.01\ngravity 0 0 0\n" + body, options);
  EXPECT_TRUE(r->world) << test::firstMessage(r->diags);
  return r;
}

Vector3d boxVelocity(const World& w) {
  for (const BodyState& s : w.states())
    if (s.path == "/World/Box") return s.linearVelocity;
  ADD_FAILURE() << "no box";
  return Vector3d::Zero();
}

// The handle of the body whose surface is just under `at`.
int handleUnder(BulletSurfaces& s, const Vector3d& at) {
  s.prepare(Eigen::AlignedBox3d(at - Vector3d::Constant(0.2), at + Vector3d::Constant(0.2)), 1, kAllBits, "");
  std::vector<SurfaceContact> out;
  s.contacts(at, 0.1, 0, out);
  EXPECT_EQ(out.size(), 1u);
  return out.empty() ? -1 : out[0].body;
}

}  // namespace

TEST(ParticlesWorld, NoParticleSystemsNoSurfaces) {
  auto r = make(kBox);
  EXPECT_EQ(r->world->particleSurfaces(), nullptr);
  r->world->step();  // and stepping does not need them
  EXPECT_TRUE(r->world->particleStates().empty());
  auto g = make(kBox + kGrain);
  EXPECT_NE(g->world->particleSurfaces(), nullptr);
  ASSERT_EQ(g->world->particleStates().size(), 1u);
  EXPECT_TRUE(g->world->particleStates()[0].granular);
}

TEST(ParticlesWorld, ReactionsActInTheStepTheyWereAddedInAndOnlyThere) {
  auto r = make(kBox + kGrain);
  BulletSurfaces& s = *r->world->particleSurfaces();
  int box = handleUnder(s, {0, 0, 5.55});
  ASSERT_GE(box, 0);
  // Added before World::step as a system adds it during the step: the
  // world applies it before Bullet's step, so the first step already has
  // v = F/m dt (applied after Bullet's step, it would still be 0 here).
  s.addForce(box, {0, 0, 5}, {6, 0, 0});
  r->world->step();
  EXPECT_NEAR(boxVelocity(*r->world).x(), 6.0 / 2 * 0.01, 1e-15);
  // Summed forces are cleared once applied, and Bullet clears its own.
  r->world->step();
  r->world->step();
  EXPECT_NEAR(boxVelocity(*r->world).x(), 6.0 / 2 * 0.01, 1e-15);
  // Forces on one body add up.
  s.addForce(box, {0, 0, 5}, {1, 0, 0});
  s.addForce(box, {0, 0, 5}, {1, 0, 0});
  r->world->step();
  EXPECT_NEAR(boxVelocity(*r->world).x(), 6.0 / 2 * 0.01 + 2.0 / 2 * 0.01, 1e-15);
}

TEST(ParticlesWorld, ARobotLinkPushIsClearedAfterItsStep) {
  std::string urdf = std::string(RSCENE_SOURCE_DIR) + "/examples/robots/quadruped/quadruped.urdf";
  auto r = make("articulated_resource res Robot " + urdf +
                    "\narticulated /World/Robot res 0 0 1 1 0 0 0 true true "
                    "generalizedCoordinate=0,0,1,1,0,0,0,0,0.6,-1.2,0,0.6,-1.2,0,-0.6,1.2,0,-0.6,1.2\n" + kGrain,
                true);
  BulletSurfaces& s = *r->world->particleSurfaces();
  int base = handleUnder(s, {0, 0, 1.11});
  ASSERT_GE(base, 0);
  RobotLayout layout = makeLayout(*r->robots[0].model);
  auto momentum = [&] {
    Vector3d m = Vector3d::Zero();
    RobotState st = r->world->robotStates()[0];
    for (std::size_t b = 0; b < layout.bodies.size(); ++b) m += layout.bodies[b].mass * st.bodyLinearVelocities[b];
    return m;
  };
  s.addForce(base, {0, 0, 1.06}, {0, 0, 30});
  r->world->step();
  Vector3d once = momentum();
  EXPECT_NEAR(once.z(), 30 * 0.01, 1e-4);  // the pose moved under the measure (see bullet_surfaces_test)
  r->world->step();
  // No second push: in zero gravity the momentum stays (to what the
  // moving pose and the joints' damping make of the measure).
  EXPECT_NEAR((momentum() - once).norm(), 0, 1e-4);
}
