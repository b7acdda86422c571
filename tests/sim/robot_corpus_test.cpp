// Real robots in rscene-sim's world: ANYmal C and RaiSim's chain robot from
// ../shared/corpus/robots (skipped where ../shared is absent) and the
// project's own quadruped (examples/robots).  Tolerances are the issue's.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/loader.hpp"
#include "robot/load.hpp"
#include "scene/scene.hpp"
#include "sim/robot_layout.hpp"
#include "sim/world.hpp"

using namespace rscene;
using namespace rscene::sim;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;
const std::string kAnymalPose = "0,0,0.54,1,0,0,0,0.03,0.4,-0.8,-0.03,0.4,-0.8,0.03,-0.4,0.8,-0.03,-0.4,0.8";
const std::string kGround =
    "object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 0.5 1 0 default engine_default false true false - static "
    "true 1 18446744073709551615\n";

struct Cell {
  Document doc;
  Scene scene;
  Diagnostics diags;
  std::vector<robot::RobotInstance> robots;
  std::unique_ptr<World> world;
};

// A scene of one robot file (absolute path) at generalizedCoordinate `q`.
std::unique_ptr<Cell> load(const std::string& urdf, const std::string& q, const std::string& more,
                          const PdGains& pd = {}) {
  auto r = std::make_unique<Cell>();
  std::string text = "raisim_engine_scene 1\ntime_step 0.0025\ngravity 0 0 -9.81\n"
                     "articulated_resource res Robot " + urdf + "\n" + more +
                     "articulated /World/Robot res 0 0 0 1 0 0 0 true true generalizedCoordinate=" + q + "\n";
  LoadResult loaded = parse(text);
  EXPECT_TRUE(loaded.ok());
  r->doc = std::move(loaded.document);
  EXPECT_TRUE(buildScene(r->doc, {}, r->scene, r->diags));
  EXPECT_TRUE(makeRobots(r->doc, r->scene, r->robots, r->diags)) << (r->diags.empty() ? "" : r->diags[0].message);
  WorldOptions wo;
  wo.robots = &r->robots;
  wo.pd = pd;
  wo.document = &r->doc;
  r->world = World::create(r->scene, r->diags, wo);
  EXPECT_TRUE(r->world) << (r->diags.empty() ? "" : r->diags[0].message);
  return r;
}

std::string anymal() {
  fs::path f = fs::path(RSCENE_SHARED_DIR) / "corpus/robots/anymal_c/urdf/anymal.urdf";
  return fs::exists(f) ? f.string() : std::string();
}

double tiltDegrees(const Eigen::Quaterniond& q) {
  Eigen::Vector3d up = q * Eigen::Vector3d::UnitZ();
  return std::acos(std::clamp(up.z(), -1.0, 1.0)) * 180 / kPi;
}

// The lowest point of every primitive collision shape of a robot (meshes
// are left out: none in these models).
double lowestPoint(const RobotState& s) {
  const robot::Model& model = *s.instance->model;
  RobotLayout layout = makeLayout(model);
  double lowest = 1e9;
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    const RobotBody& body = layout.bodies[b];
    for (std::size_t k = 0; k < body.links.size(); ++k) {
      for (const robot::Collision& c : model.links[static_cast<std::size_t>(body.links[k])].collisions) {
        Pose at = s.bodyPoses[b] * body.linkInBody[k] * c.origin;
        const robot::Geometry& g = c.geometry;
        auto point = [&](const Eigen::Vector3d& p) { lowest = std::min(lowest, (at.orientation * p + at.position).z()); };
        switch (g.kind) {
          case robot::GeometryKind::Sphere: lowest = std::min(lowest, at.position.z() - g.radius); break;
          case robot::GeometryKind::Box:
            for (int i = 0; i < 8; ++i)
              point(0.5 * Eigen::Vector3d((i & 1 ? 1 : -1) * g.size.x(), (i & 2 ? 1 : -1) * g.size.y(),
                                          (i & 4 ? 1 : -1) * g.size.z()));
            break;
          case robot::GeometryKind::Capsule:
            for (double e : {-0.5, 0.5}) lowest = std::min(lowest, (at * Pose{{0, 0, e * g.length}, {}}).position.z() - g.radius);
            break;
          case robot::GeometryKind::Cylinder:
            for (double e : {-0.5, 0.5})
              for (int a = 0; a < 64; ++a)
                point({g.radius * std::cos(a * kPi / 32), g.radius * std::sin(a * kPi / 32), e * g.length});
            break;
          case robot::GeometryKind::Mesh: break;
        }
      }
    }
  }
  return lowest;
}

}  // namespace

// ANYmal C held by PD (kp 100, kd 2) in its standing pose stands for 10 s:
// the base stays within 3 cm of the height it settles at (after 1 s) and
// tilts less than 3 degrees.
TEST(RobotCorpus, AnymalHeldByPdStandsTenSeconds) {
  std::string urdf = anymal();
  if (urdf.empty()) GTEST_SKIP() << "../shared/corpus/robots/anymal_c not present";
  PdGains pd;
  pd.enabled = true;
  pd.kp = 100;
  pd.kd = 2;
  auto r = load(urdf, kAnymalPose, kGround, pd);
  ASSERT_TRUE(r->world);
  for (int k = 0; k < 400; ++k) r->world->step();
  double settled = r->world->robotStates()[0].q[2];
  EXPECT_GT(settled, 0.4);  // on its feet
  double worstHeight = 0, worstTilt = 0;
  for (int k = 400; k < 4000; ++k) {
    r->world->step();
    if (k % 20) continue;
    RobotState s = r->world->robotStates()[0];
    worstHeight = std::max(worstHeight, std::abs(s.q[2] - settled));
    worstTilt = std::max(worstTilt, tiltDegrees(s.base.orientation));
  }
  EXPECT_LT(worstHeight, 0.03);
  EXPECT_LT(worstTilt, 3.0);
}

// Without PD it collapses onto the ground and comes to rest with no link
// more than 1 cm inside it.
TEST(RobotCorpus, AnymalWithoutPdCollapsesAndRestsOnTheGround) {
  std::string urdf = anymal();
  if (urdf.empty()) GTEST_SKIP() << "../shared/corpus/robots/anymal_c not present";
  auto r = load(urdf, kAnymalPose, kGround);
  ASSERT_TRUE(r->world);
  double deepest = 1e9;
  for (int k = 0; k < 4000; ++k) {
    r->world->step();
    if (k % 20 == 0) deepest = std::min(deepest, lowestPoint(r->world->robotStates()[0]));
  }
  RobotState s = r->world->robotStates()[0];
  EXPECT_LT(s.q[2], 0.3);            // collapsed
  EXPECT_GT(deepest, -0.01);         // never more than 1 cm into the ground
  EXPECT_LT(s.u.norm(), 0.05);       // at rest
}

// RaiSim's chain robot (spherical joints, no damping) keeps its total
// energy within 2% of the energy of its motion over 5 s, started tilted,
// at time_step 0.0005 (the integrator's deviation is first order in the
// step: 2.1% at 0.001).
TEST(RobotCorpus, ChainRobotKeepsItsEnergy) {
  fs::path f = fs::path(RSCENE_SHARED_DIR) / "corpus/robots/chain/robot.urdf";
  if (!fs::exists(f)) GTEST_SKIP() << "../shared/corpus/robots/chain not present";
  // Every spherical joint tilted 0.5 rad about x.
  double c = std::cos(0.25), s = std::sin(0.25);
  std::string q;
  robot::Model chain;
  Diagnostics ds;
  ASSERT_TRUE(robot::loadModel(f.string(), {}, chain, ds));
  robot::Coordinates layoutOfQ;
  robot::makeCoordinates(chain, {}, layoutOfQ);
  int n = layoutOfQ.coordinateDim / 4;  // spherical joints only
  ASSERT_GT(n, 0);
  for (int i = 0; i < n; ++i) q += (i ? "," : "") + std::to_string(c) + "," + std::to_string(s) + ",0,0";
  auto r = load(f.string(), q, "time_step 0.0005\n");
  ASSERT_TRUE(r->world);
  const robot::Model& model = *r->robots[0].model;
  RobotLayout layout = makeLayout(model);
  auto energy = [&](const RobotState& st) {
    double e = 0;
    for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
      Pose com = st.bodyPoses[b] * layout.bodies[b].com;
      Eigen::Matrix3d rot = com.orientation.toRotationMatrix();
      Eigen::Matrix3d inertia = rot * layout.bodies[b].inertia.asDiagonal() * rot.transpose();
      const Eigen::Vector3d &v = st.bodyLinearVelocities[b], &w = st.bodyAngularVelocities[b];
      e += 0.5 * layout.bodies[b].mass * v.squaredNorm() + 0.5 * w.dot(inertia * w) +
           layout.bodies[b].mass * 9.81 * com.position.z();
    }
    return e;
  };
  double e0 = energy(r->world->robotStates()[0]);
  // 2% of the energy of the motion: e0 above the chain hanging at rest.
  std::string rest;
  for (int i = 0; i < n; ++i) rest += (i ? "," : "") + std::string("1,0,0,0");
  double swing = e0 - energy(load(f.string(), rest, "")->world->robotStates()[0]);
  ASSERT_GT(swing, 0.1);
  double worst = 0;
  for (int k = 0; k < 10000; ++k) {
    r->world->step();
    if (k % 10 == 0) worst = std::max(worst, std::abs(energy(r->world->robotStates()[0]) - e0));
  }
  EXPECT_LT(worst, 0.02 * swing) << "energy of the motion " << swing;
}

// The project's own quadruped (examples/robots, what `make demo` runs)
// stands with PD as ANYmal does.
TEST(RobotCorpus, ExampleQuadrupedStandsWithPd) {
  fs::path f = fs::path(RSCENE_SOURCE_DIR) / "examples/robots/quadruped/quadruped.urdf";
  ASSERT_TRUE(fs::exists(f));
  PdGains pd;
  pd.enabled = true;
  pd.kp = 100;
  pd.kd = 2;
  auto r = load(f.string(), "0,0,0.3882,1,0,0,0,0,0.6,-1.2,0,0.6,-1.2,0,-0.6,1.2,0,-0.6,1.2", kGround, pd);
  ASSERT_TRUE(r->world);
  for (int k = 0; k < 400; ++k) r->world->step();
  double settled = r->world->robotStates()[0].q[2];
  EXPECT_GT(settled, 0.3);
  for (int k = 400; k < 4000; ++k) r->world->step();
  RobotState s = r->world->robotStates()[0];
  EXPECT_NEAR(s.q[2], settled, 0.03);
  EXPECT_LT(tiltDegrees(s.base.orientation), 3.0);
}
