// Articulated systems in Bullet's Featherstone multibody, against closed-form
// answers and against lib/robot's forward kinematics.  Models are built in
// code (tests/sim/robot_corpus_test.cpp runs the robots of ../shared).
// Each tolerance is stated where it is asserted.
#include <gtest/gtest.h>

#include <cmath>

#include "core/loader.hpp"
#include "robot/kinematics.hpp"
#include "scene/scene.hpp"
#include "sim/robot_layout.hpp"
#include "sim/world.hpp"

using namespace rscene;
using namespace rscene::sim;
using robot::JointType;

namespace {

constexpr double kPi = 3.14159265358979323846;

robot::Inertial inertial(double mass, const Eigen::Vector3d& at, double i) {
  robot::Inertial in;
  in.mass = mass;
  in.origin.position = at;
  in.inertia = i * Eigen::Matrix3d::Identity();
  return in;
}

// Appends a link (and the joint to it from `parent`, unless it is the root).
int addLink(robot::Model& m, const std::string& name, const robot::Inertial& in, int parent = -1,
            JointType type = JointType::Fixed, const Pose& origin = {}, const Eigen::Vector3d& axis = Eigen::Vector3d::UnitX()) {
  robot::Link l;
  l.name = name;
  l.inertial = in;
  int index = static_cast<int>(m.links.size());
  if (parent >= 0) {
    robot::Joint j;
    j.name = name + "_joint";
    j.type = type;
    j.parentLink = parent;
    j.childLink = index;
    j.origin = origin;
    j.axis = axis.normalized();
    l.parentJoint = static_cast<int>(m.joints.size());
    m.links[static_cast<std::size_t>(parent)].childJoints.push_back(l.parentJoint);
    m.joints.push_back(j);
  }
  m.links.push_back(l);
  return index;
}

Pose at(double x, double y, double z) {
  Pose p;
  p.position = {x, y, z};
  return p;
}

robot::Collision sphere(double r, const Eigen::Vector3d& where = Eigen::Vector3d::Zero()) {
  robot::Collision c;
  c.geometry.kind = robot::GeometryKind::Sphere;
  c.geometry.radius = r;
  c.origin.position = where;
  return c;
}

robot::Collision box(const Eigen::Vector3d& size, const Eigen::Vector3d& where = Eigen::Vector3d::Zero()) {
  robot::Collision c;
  c.geometry.kind = robot::GeometryKind::Box;
  c.geometry.size = size;
  c.origin.position = where;
  return c;
}

// A scene with one articulated record per model, at the origin, simulated.
struct Run {  // NOLINT
  Document doc;
  Scene scene;
  Diagnostics diags;
  std::vector<robot::RobotInstance> robots;
  std::unique_ptr<World> world;
};

std::unique_ptr<Run> make(const std::string& body, const std::vector<std::shared_ptr<robot::Model>>& models,
                          const std::vector<Eigen::VectorXd>& q = {}, const std::vector<Eigen::VectorXd>& u = {},
                          const PdGains& pd = {}, const std::vector<std::string>& order = {}) {
  auto r = std::make_unique<Run>();
  std::string text = "raisim_engine_scene 1\ngravity 0 0 -9.81\n" + body;
  for (std::size_t i = 0; i < models.size(); ++i)
    text += "articulated /World/R" + std::to_string(i) + " res 0 0 0 1 0 0 0 true true\n";
  LoadResult loaded = parse(text);
  EXPECT_TRUE(loaded.ok());
  r->doc = std::move(loaded.document);
  EXPECT_TRUE(buildScene(r->doc, {}, r->scene, r->diags));
  r->robots.resize(models.size());
  for (std::size_t i = 0; i < models.size(); ++i) {
    robot::RobotInstance& in = r->robots[i];
    in.record = &r->scene.articulated[i];
    in.model = models[i];
    EXPECT_TRUE(robot::makeCoordinates(*in.model, order, in.coordinates).empty());
    in.base = in.record->world;
    in.q = i < q.size() ? q[i] : robot::neutralCoordinate(*in.model, in.coordinates, in.base);
    in.u = i < u.size() ? u[i] : Eigen::VectorXd::Zero(in.coordinates.velocityDim);
    if (in.model->floatingBase)
      in.base = {in.q.head<3>(), Eigen::Quaterniond(in.q[3], in.q[4], in.q[5], in.q[6]).normalized()};
  }
  WorldOptions wo;
  wo.robots = &r->robots;
  wo.pd = pd;
  wo.document = &r->doc;
  r->world = World::create(r->scene, r->diags, wo);
  EXPECT_TRUE(r->world) << (r->diags.empty() ? "" : r->diags[0].message);
  return r;
}

// A rod of mass m whose centre of mass hangs d below a hinge about y at
// height 2, fixed to the world; the rod's own inertia about its centre is i.
std::shared_ptr<robot::Model> pendulum(double m, double d, double i, bool limits = false, double lower = 0,
                                       double upper = 0) {
  auto model = std::make_shared<robot::Model>();
  model->name = "pendulum";
  model->floatingBase = false;
  addLink(*model, "world", {});
  int arm = addLink(*model, "arm", inertial(m, {0, 0, -d}, i), 0, JointType::Revolute, at(0, 0, 2), Eigen::Vector3d::UnitY());
  model->joints[0].hasLimits = limits;
  model->joints[0].lower = lower;
  model->joints[0].upper = upper;
  (void)arm;
  return model;
}

double run(World& w, double seconds) {
  long n = std::lround(seconds / w.timeStep());
  for (long k = 0; k < n; ++k) w.step();
  return w.time();
}

// Total energy (kinetic + potential, g along -z) of a robot's bodies.
double energy(const RobotState& s, const RobotLayout& layout, double g) {
  double e = 0;
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    const RobotBody& body = layout.bodies[b];
    Pose com = s.bodyPoses[b] * body.com;
    Eigen::Matrix3d r = com.orientation.toRotationMatrix();
    Eigen::Matrix3d inertia = r * body.inertia.asDiagonal() * r.transpose();
    const Eigen::Vector3d &v = s.bodyLinearVelocities[b], &w = s.bodyAngularVelocities[b];
    e += 0.5 * body.mass * v.squaredNorm() + 0.5 * w.dot(inertia * w) + body.mass * g * com.position.z();
  }
  return e;
}

}  // namespace

TEST(RobotLayout, FixedLinksMergeByTheParallelAxisTheorem) {
  robot::Model m;
  m.floatingBase = true;
  addLink(m, "base", inertial(2, {0, 0, 0}, 0.1));
  addLink(m, "payload", inertial(1, {0, 0, 0}, 0.05), 0, JointType::Fixed, at(0.3, 0, 0));
  addLink(m, "leg", inertial(1, {0, 0, -0.1}, 0.01), 0, JointType::Revolute, at(0, 0, -0.2));
  RobotLayout l = makeLayout(m);
  ASSERT_EQ(l.bodies.size(), 2u);
  EXPECT_EQ(l.bodyOfLink[1], 0);
  EXPECT_EQ(l.bodyOfLink[2], 1);
  EXPECT_DOUBLE_EQ(l.bodies[0].mass, 3);
  EXPECT_NEAR(l.bodies[0].com.position.x(), 0.1, 1e-15);
  // About the common centre (x = 0.1): y and z gain 2 (0.1)^2 + 1 (0.2)^2 = 0.06.
  Eigen::Vector3d sorted = l.bodies[0].inertia;
  std::sort(sorted.data(), sorted.data() + 3);
  EXPECT_NEAR(sorted[0], 0.15, 1e-12);
  EXPECT_NEAR(sorted[1], 0.21, 1e-12);
  EXPECT_NEAR(sorted[2], 0.21, 1e-12);
}

TEST(RobotLayout, RotorInertiaIsAddedAboutTheJointAxis) {
  robot::Model m;
  m.floatingBase = false;
  addLink(m, "world", {});
  addLink(m, "arm", inertial(1, {0, 0, 0}, 0.01), 0, JointType::Revolute, {}, Eigen::Vector3d::UnitZ());
  m.joints[0].rotorInertia = 0.5;
  RobotLayout l = makeLayout(m);
  Eigen::Vector3d sorted = l.bodies[1].inertia;
  std::sort(sorted.data(), sorted.data() + 3);
  EXPECT_NEAR(sorted[2], 0.51, 1e-12);  // only about z
  EXPECT_NEAR(sorted[1], 0.01, 1e-12);
}

// Bullet's bodies must sit where lib/robot's forward kinematics puts the
// links, for every joint type, a floating base, fixed links, tilted and
// off-centre inertials; and the state must read back as it was set.
TEST(RobotSim, BodiesAgreeWithForwardKinematicsAndStateRoundTrips) {
  auto m = std::make_shared<robot::Model>();
  m->floatingBase = true;
  robot::Inertial tilted = inertial(1.5, {0.05, -0.02, 0.1}, 0.02);
  tilted.origin.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
  tilted.inertia << 0.03, 0.004, -0.002, 0.004, 0.02, 0.001, -0.002, 0.001, 0.01;
  addLink(*m, "base", tilted);
  Pose o1 = at(0.2, 0.1, 0);
  o1.orientation = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ());
  int a = addLink(*m, "hinge", tilted, 0, JointType::Revolute, o1, Eigen::Vector3d(0.2, 1, 0.1));
  int f = addLink(*m, "fixed", inertial(0.3, {0.1, 0, 0}, 0.001), a, JointType::Fixed, at(0, 0, -0.3));
  int s = addLink(*m, "ball", tilted, f, JointType::Spherical, at(0.1, 0, -0.1));
  addLink(*m, "slider", inertial(0.5, {0, 0.05, 0}, 0.002), s, JointType::Prismatic, at(0, 0.2, 0), Eigen::Vector3d(1, 0, 1));
  addLink(*m, "second", inertial(0.7, {0, 0, -0.1}, 0.003), 0, JointType::Continuous, at(-0.2, 0, 0), Eigen::Vector3d::UnitY());
  Eigen::VectorXd q(7 + 1 + 4 + 1 + 1), u(6 + 1 + 3 + 1 + 1);
  Eigen::Quaterniond base(Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.3, -1, 0.2).normalized()));
  Eigen::Quaterniond ball(Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 1, 0).normalized()));
  q << 0.1, 0.2, 3, base.w(), base.x(), base.y(), base.z(), 0.6, ball.w(), ball.x(), ball.y(), ball.z(), 0.15, -1.1;
  u << 0.1, -0.2, 0.3, 0.4, -0.5, 0.6, 0.7, -0.8, 0.9, 1.0, -0.3, 0.2;
  auto r = make("", {m}, {q}, {u});
  ASSERT_TRUE(r->world);
  std::vector<RobotState> states = r->world->robotStates();
  ASSERT_EQ(states.size(), 1u);
  const RobotState& st = states[0];
  for (Eigen::Index i = 0; i < q.size(); ++i) EXPECT_NEAR(st.q[i], q[i], 1e-12) << "q[" << i << "]";  // round-off
  for (Eigen::Index i = 0; i < u.size(); ++i) EXPECT_NEAR(st.u[i], u[i], 1e-12) << "u[" << i << "]";
  std::vector<Pose> fk = robot::linkPoses(r->robots[0]);
  RobotLayout layout = makeLayout(*m);
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    const Pose& want = fk[static_cast<std::size_t>(layout.bodies[b].links[0])];
    EXPECT_LT((st.bodyPoses[b].position - want.position).norm(), 1e-12) << "body " << b;
    EXPECT_LT(st.bodyPoses[b].orientation.angularDistance(want.orientation), 1e-9) << "body " << b;
  }
}

// The floating base's angular velocity is in the world frame (RaiSim's
// convention): a base tilted 90 degrees about x spinning at 1 rad/s about
// world z turns about world z, and its frame origin (off the centre of
// mass) circles the centre of mass.
TEST(RobotSim, FloatingBaseVelocitiesAreInTheWorldFrame) {
  auto m = std::make_shared<robot::Model>();
  addLink(*m, "base", inertial(1, {0.3, 0, 0}, 0.01));
  Eigen::Quaterniond tilt(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitX()));
  Eigen::VectorXd q(7), u(6);
  q << 0, 0, 1, tilt.w(), tilt.x(), tilt.y(), tilt.z();
  Eigen::Vector3d com(0.3, 0, 1);  // tilt about x leaves the x offset alone
  u << Eigen::Vector3d::UnitZ().cross(Eigen::Vector3d(0, 0, 1) - com), 0, 0, 1;
  auto r = make("gravity 0 0 0\ntime_step 0.001\n", {m}, {q}, {u});
  ASSERT_TRUE(r->world);
  double t = run(*r->world, 1.0);
  RobotState s = r->world->robotStates()[0];
  Eigen::Quaterniond want = Eigen::AngleAxisd(t, Eigen::Vector3d::UnitZ()) * tilt;
  Eigen::Quaterniond got(s.q[3], s.q[4], s.q[5], s.q[6]);
  EXPECT_LT(got.angularDistance(want), 1e-6);  // a spherical body: no precession, integrator error only
  Eigen::Vector3d origin = com + Eigen::AngleAxisd(t, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d(-0.3, 0, 0);
  EXPECT_LT((s.q.head<3>() - origin).norm(), 1e-4);  // ~dt^2 per step of position integration
  EXPECT_NEAR(s.u[5], 1, 1e-9);
}

// Small-angle period of a physical pendulum: T = 2 pi sqrt(I_pivot / (m g d)).
TEST(RobotSim, PendulumPeriodMatchesThePhysicalPendulumWithinOnePercent) {
  const double m = 2, d = 0.5, ic = 0.02, g = 9.81;
  Eigen::VectorXd q0(1);
  q0 << 0.05;
  auto r = make("time_step 0.001\n", {pendulum(m, d, ic)}, {q0});
  ASSERT_TRUE(r->world);
  // Period from the times of upward zero crossings (linearly interpolated).
  std::vector<double> crossings;
  double last = q0[0];
  for (int k = 0; k < 10000 && crossings.size() < 6; ++k) {
    r->world->step();
    double now = r->world->robotStates()[0].q[0];
    if (last < 0 && now >= 0) crossings.push_back(r->world->time() - 0.001 * now / (now - last));
    last = now;
  }
  ASSERT_EQ(crossings.size(), 6u);
  double period = (crossings.back() - crossings.front()) / 5;
  double expected = 2 * kPi * std::sqrt((ic + m * d * d) / (m * g * d));
  EXPECT_NEAR(period, expected, 0.01 * expected);  // the issue's 1%
}

// Three spheres on spherical joints (RaiSim's chain robot, built here),
// started tilted and spinning, with no damping: total energy within 2% of
// the energy of the motion over 5 s, at time_step 0.0005.  The deviation
// is the integrator's (semi-implicit Euler) and first order in the step:
// started at 1 rad and spinning at 2 rad/s it is 7% at 0.001, 3% at 0.0005
// and under 2% at 0.0002.
TEST(RobotSim, UndampedChainKeepsItsEnergyWithinTwoPercent) {
  auto m = std::make_shared<robot::Model>();
  m->floatingBase = false;
  addLink(*m, "world", {});
  int l1 = addLink(*m, "link1", inertial(1, {0, 0, -0.12}, 0.002), 0, JointType::Fixed, at(0, 0, 2));
  int l2 = addLink(*m, "link2", inertial(1, {0, 0, -0.12}, 0.002), l1, JointType::Spherical, at(0, 0, -0.24));
  addLink(*m, "link3", inertial(1, {0, 0, -0.12}, 0.002), l2, JointType::Spherical, at(0, 0, -0.24));
  Eigen::Quaterniond a(Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 0.5, 0).normalized()));
  Eigen::Quaterniond b(Eigen::AngleAxisd(-0.5, Eigen::Vector3d(0, 1, 0.3).normalized()));
  Eigen::VectorXd q(8), u(6);
  q << a.w(), a.x(), a.y(), a.z(), b.w(), b.x(), b.y(), b.z();
  u << 0, 0, 0.5, 0, 0, 0;
  auto r = make("time_step 0.0005\n", {m}, {q}, {u});
  ASSERT_TRUE(r->world);
  RobotLayout layout = makeLayout(*m);
  double e0 = energy(r->world->robotStates()[0], layout, 9.81);
  // 2% of the energy of the motion: e0 above the chain hanging at rest
  // (link2's centre at 2 - 0.24 - 0.12, link3's 0.24 lower; link1 does not move).
  double rest = 1 * 9.81 * (2 - 0.12) + 1 * 9.81 * (2 - 0.36) + 1 * 9.81 * (2 - 0.60);
  double swing = e0 - rest;
  ASSERT_GT(swing, 0.3);
  double worst = 0;
  for (int k = 0; k < std::lround(5 / r->world->timeStep()); ++k) {
    r->world->step();
    if (k % 10 == 0) worst = std::max(worst, std::abs(energy(r->world->robotStates()[0], layout, 9.81) - e0));
  }
  EXPECT_LT(worst, 0.02 * swing) << "energy of the motion " << swing;
}

// A joint limit is a hard stop: a pendulum released far from it swings
// into it and rests against it, never more than 0.01 rad past.
TEST(RobotSim, JointLimitHoldsWithinOneHundredthOfARadian) {
  Eigen::VectorXd q0(1);
  q0 << -1.2;
  auto r = make("time_step 0.0025\n", {pendulum(2, 0.5, 0.02, true, -1.5, -0.3)}, {q0});
  ASSERT_TRUE(r->world);
  double most = -10;
  for (int k = 0; k < 2000; ++k) {
    r->world->step();
    most = std::max(most, r->world->robotStates()[0].q[0]);
  }
  EXPECT_LE(most, -0.3 + 0.01);
  EXPECT_NEAR(r->world->robotStates()[0].q[0], -0.3, 0.01);  // at rest against it
}

// A joint that starts exactly at its limit, pressed into it by gravity, is
// held from the first step (its limit's constraint is in the world while
// the joint is at or past a bound: robot_sim.hpp), and one released from
// it swings away freely (out of the world again) and comes back.
TEST(RobotSim, JointLimitHoldsFromTheFirstStepAtTheLimit) {
  Eigen::VectorXd q0(1);
  q0 << -0.3;
  auto r = make("time_step 0.0025\n", {pendulum(2, 0.5, 0.02, true, -1.5, -0.3)}, {q0});
  ASSERT_TRUE(r->world);
  double most = -10;
  for (int k = 0; k < 400; ++k) {
    r->world->step();
    most = std::max(most, r->world->robotStates()[0].q[0]);
  }
  EXPECT_LE(most, -0.3 + 1e-3);
  EXPECT_NEAR(r->world->robotStates()[0].q[0], -0.3, 1e-3);
  // Kicked away from the limit: it leaves it, then swings back against it.
  Eigen::VectorXd q1(1), u1(1);
  q1 << -0.3;
  u1 << -4;
  auto kicked = make("time_step 0.0025\n", {pendulum(2, 0.5, 0.02, true, -1.5, -0.3)}, {q1}, {u1});
  ASSERT_TRUE(kicked->world);
  double least = 10;
  most = -10;
  for (int k = 0; k < 2000; ++k) {
    kicked->world->step();
    least = std::min(least, kicked->world->robotStates()[0].q[0]);
    most = std::max(most, kicked->world->robotStates()[0].q[0]);
  }
  EXPECT_LT(least, -0.6);  // it swung away
  EXPECT_LE(most, -0.3 + 0.01);
  EXPECT_NEAR(kicked->world->robotStates()[0].q[0], -0.3, 0.01);
}

// Viscous damping brings a swinging pendulum to rest.
TEST(RobotSim, JointDampingStopsThePendulum) {
  auto m = pendulum(2, 0.5, 0.02);
  m->joints[0].damping = 2;
  Eigen::VectorXd q0(1);
  q0 << 1.0;
  auto r = make("time_step 0.0025\n", {m}, {q0});
  ASSERT_TRUE(r->world);
  run(*r->world, 10);
  RobotState s = r->world->robotStates()[0];
  EXPECT_NEAR(s.q[0], 0, 1e-3);
  EXPECT_NEAR(s.u[0], 0, 1e-3);
}

// A spring toward spring_mount balances gravity: k (q - mount) = -m g d sin q.
TEST(RobotSim, SpringRestsWhereItBalancesGravity) {
  auto m = pendulum(2, 0.5, 0.02);
  m->joints[0].stiffness = 50;
  m->joints[0].damping = 3;
  m->joints[0].springMount = {0.5};
  auto r = make("time_step 0.0025\n", {m});
  ASSERT_TRUE(r->world);
  run(*r->world, 10);
  double q = r->world->robotStates()[0].q[0];
  // The per-joint implicit spring holds with stiffness s k, s = m/(m + dt c + dt^2 k) (robot_sim.hpp).
  double inertia = 0.02 + 2 * 0.25, dt = 0.0025, s = inertia / (inertia + dt * 3 + dt * dt * 50);
  EXPECT_NEAR(s * 50 * (q - 0.5), -2 * 9.81 * 0.5 * std::sin(q), 1e-6);
  EXPECT_GT(q, 0.2);
}

// --pd-gains holds the initial pose against gravity, and stays stable at
// gains far beyond what an explicit PD survives at this step.
TEST(RobotSim, PdHoldsThePoseAndIsStableAtHugeGains) {
  Eigen::VectorXd q0(1);
  q0 << 0.5;
  for (double kp : {100.0, 1e7}) {
    PdGains pd;
    pd.enabled = true;
    pd.kp = kp;
    pd.kd = kp > 1000 ? 1000 : 2;
    auto r = make("time_step 0.0025\n", {pendulum(2, 0.5, 0.02)}, {q0}, {}, pd);
    ASSERT_TRUE(r->world);
    run(*r->world, 10);
    RobotState s = r->world->robotStates()[0];
    // Static error: m g d sin(q) / (s kp) (robot_sim.hpp): 0.05 rad at kp
    // 100, 6e-5 at 1e7 (s kp = 79,000 there: the joint inertia over dt^2).
    EXPECT_NEAR(s.q[0], 0.5, kp > 1000 ? 1e-4 : 0.06) << "kp " << kp;
    EXPECT_NEAR(s.u[0], 0, 1e-5) << "kp " << kp;
  }
}

// Coulomb friction holds a joint whose gravity torque is below it.
TEST(RobotSim, CoulombFrictionHoldsBelowItsTorque) {
  auto m = pendulum(2, 0.5, 0.02);
  m->joints[0].friction = 6;  // gravity torque at 0.5 rad: 2 * 9.81 * 0.5 * sin 0.5 = 4.7 N m
  Eigen::VectorXd q0(1);
  q0 << 0.5;
  auto r = make("time_step 0.0025\n", {m}, {q0});
  ASSERT_TRUE(r->world);
  run(*r->world, 2);
  EXPECT_NEAR(r->world->robotStates()[0].q[0], 0.5, 1e-6);
  m = pendulum(2, 0.5, 0.02);
  m->joints[0].friction = 3;  // below the gravity torque: it falls
  r = make("time_step 0.0025\n", {m}, {q0});
  run(*r->world, 2);
  EXPECT_LT(r->world->robotStates()[0].q[0], 0.3);
}

// A ball dropped on a fixed-base arm bounces off its link (restitution 0.8
// by the solver's default), and the arm keeps its pose.
TEST(RobotSim, BallBouncesOffAFixedArm) {
  auto m = std::make_shared<robot::Model>();
  m->floatingBase = false;
  addLink(*m, "world", {});
  int base = addLink(*m, "pedestal", inertial(5, {0, 0, 0}, 0.1), 0, JointType::Fixed, at(0, 0, 0.5));
  m->links[static_cast<std::size_t>(base)].collisions.push_back(box({0.2, 0.2, 1}));
  int arm = addLink(*m, "arm", inertial(2, {0.5, 0, 0}, 0.05), base, JointType::Revolute, at(0, 0, 0.55),
                    Eigen::Vector3d::UnitZ());
  m->links[static_cast<std::size_t>(arm)].collisions.push_back(box({1, 0.2, 0.1}, {0.5, 0, 0}));
  std::string ball =
      "solver 80 1e-07 0.2 accurate defaultRestitution=0.8 defaultRestitutionThreshold=0.1\n"
      "time_step 0.001\n"
      "object /World/Ball sphere 0.7 0 1.5 1 0 0 0 1 1 1 0.05 0.1 0.5 default engine_default false true false - "
      "dynamic true 1 18446744073709551615\n";
  auto r = make(ball, {m});
  ASSERT_TRUE(r->world);
  double lowest = 10, risingAt = -1;
  for (int k = 0; k < 1500; ++k) {
    r->world->step();
    BodyState s = r->world->states()[0];
    lowest = std::min(lowest, s.position.z());
    if (risingAt < 0 && s.linearVelocity.z() > 1) risingAt = s.position.z();
  }
  // The arm's top is at 0.5 + 0.55 + 0.05 = 1.1; the ball (radius 0.05) stops at 1.15.
  EXPECT_GT(lowest, 1.1);
  EXPECT_GT(risingAt, 1.1) << "the ball never bounced";
  EXPECT_NEAR(r->world->robotStates()[0].q[0], 0, 1e-6);  // pushed along z, the z hinge does not turn
}

// Two runs of the same scene are bit-identical.
TEST(RobotSim, RunsAreBitIdentical) {
  auto m = std::make_shared<robot::Model>();
  addLink(*m, "base", inertial(3, {0, 0, 0}, 0.05));
  m->links[0].collisions.push_back(box({0.4, 0.3, 0.1}));
  for (int leg = 0; leg < 2; ++leg) {
    int l = addLink(*m, "leg" + std::to_string(leg), inertial(0.5, {0, 0, -0.15}, 0.002), 0, JointType::Revolute,
                    at(leg ? 0.15 : -0.15, 0, -0.05), Eigen::Vector3d::UnitY());
    m->links[static_cast<std::size_t>(l)].collisions.push_back(sphere(0.03, {0, 0, -0.3}));
  }
  Eigen::VectorXd q(9);
  q << 0, 0, 0.6, 1, 0, 0, 0, 0.3, -0.3;
  const std::string ground =
      "object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 0.5 1 0 default engine_default false true false - static "
      "true 1 18446744073709551615\ntime_step 0.0025\n";
  auto once = [&] {
    PdGains pd;
    pd.enabled = true;
    pd.kp = 50;
    pd.kd = 1;
    auto r = make(ground, {m}, {q}, {}, pd);
    run(*r->world, 2);
    return r->world->robotStates()[0];
  };
  RobotState a = once(), b = once();
  ASSERT_EQ(a.q.size(), b.q.size());
  for (Eigen::Index i = 0; i < a.q.size(); ++i) EXPECT_EQ(a.q[i], b.q[i]) << i;  // bitwise
  for (Eigen::Index i = 0; i < a.u.size(); ++i) EXPECT_EQ(a.u[i], b.u[i]) << i;
  EXPECT_GT(a.q[2], 0.2);  // it stands on its feet
}

// A stiff wire from a point in the world to a robot's body holds it up
// (a rope: never longer than its length); a compliant one lets it sag to
// where the spring carries its weight.
TEST(RobotSim, WiresHoldARobotAtItsBody) {
  auto m = std::make_shared<robot::Model>();
  addLink(*m, "base", inertial(2, {0, 0, 0}, 0.01));
  addLink(*m, "tail", inertial(1, {0, 0, -0.1}, 0.01), 0, JointType::Revolute, at(0, 0, -0.1), Eigen::Vector3d::UnitY());
  Eigen::VectorXd q(8);
  q << 0, 0, 1.1, 1, 0, 0, 0, 0;
  // Body 1 (the tail) hangs from (0, 0, 2) by its joint origin, at z = 1.
  auto stiff = make("time_step 0.001\nwire /World/W stiff - /World/R0 1 localIndexB=1 localPositionA=0,0,2\n", {m}, {q});
  ASSERT_TRUE(stiff->world);
  double longest = 0;
  for (int k = 0; k < 2000; ++k) {
    stiff->world->step();
    RobotState s = stiff->world->robotStates()[0];
    longest = std::max(longest, (s.bodyPoses[1].position - Eigen::Vector3d(0, 0, 2)).norm());
  }
  EXPECT_LT(longest, 1 + 2e-3);  // the solver's residual over 2 s of a 3 kg load
  EXPECT_GT(longest, 1 - 1e-3);  // taut
  auto soft = make("time_step 0.001\nwire /World/W compliant - /World/R0 1 localIndexB=1 localPositionA=0,0,2 "
                   "stiffness=3000 damping=100\n",
                   {m}, {q});
  ASSERT_TRUE(soft->world);
  run(*soft->world, 5);
  RobotState s = soft->world->robotStates()[0];
  double d = (s.bodyPoses[1].position - Eigen::Vector3d(0, 0, 2)).norm();
  EXPECT_NEAR(d, 1 + 3 * 9.81 / 3000, 1e-4);  // k (d - L) = m g, at rest
}

// localIndexB past the robot's last body is refused at the wire's field.
TEST(RobotSim, WireToABodyTheRobotDoesNotHaveIsAnError) {
  auto m = std::make_shared<robot::Model>();
  addLink(*m, "base", inertial(2, {0, 0, 0}, 0.01));
  Eigen::VectorXd q(7);
  q << 0, 0, 1, 1, 0, 0, 0;
  auto r = std::make_unique<::Run>();
  LoadResult loaded = parse("raisim_engine_scene 1\narticulated /World/R0 res 0 0 0 1 0 0 0 true true\n"
                            "wire /World/W stiff - /World/R0 1 localIndexB=3\n");
  ASSERT_TRUE(loaded.ok());
  ASSERT_TRUE(buildScene(loaded.document, {}, r->scene, r->diags));
  r->robots.resize(1);
  robot::RobotInstance& in = r->robots[0];
  in.record = &r->scene.articulated[0];
  in.model = m;
  robot::makeCoordinates(*m, {}, in.coordinates);
  in.q = q;
  in.u = Eigen::VectorXd::Zero(6);
  WorldOptions wo;
  wo.robots = &r->robots;
  wo.document = &loaded.document;
  EXPECT_FALSE(World::create(r->scene, r->diags, wo));
  ASSERT_FALSE(r->diags.empty());
  EXPECT_EQ(r->diags.back().code, "RS7046");  // validate's code for it
  EXPECT_EQ(r->diags.back().line, 3u);
  EXPECT_NE(r->diags.back().message.find("localIndexB 3 is not a body of articulated system '/World/R0' (it has 1, 0 to 0)"),
            std::string::npos)
      << r->diags.back().message;
}

// jointOrder= reorders the coordinates, not the bodies: the state still
// reads back entry for entry and the bodies sit where the FK puts them.
TEST(RobotSim, JointOrderReordersTheCoordinatesOnly) {
  auto m = std::make_shared<robot::Model>();
  m->floatingBase = false;
  addLink(*m, "world", {});
  int a = addLink(*m, "upper", inertial(1, {0, 0, -0.2}, 0.01), 0, JointType::Revolute, at(0, 0, 2), Eigen::Vector3d::UnitY());
  addLink(*m, "lower", inertial(1, {0, 0, -0.2}, 0.01), a, JointType::Prismatic, at(0, 0, -0.4), Eigen::Vector3d::UnitZ());
  Eigen::VectorXd q(2), u(2);
  q << -0.05, 0.7;  // lower_joint first, then upper_joint
  u << 0.3, -0.4;
  auto r = make("", {m}, {q}, {u}, {}, {"lower_joint", "upper_joint"});
  ASSERT_TRUE(r->world);
  r->world->step();
  RobotState s = r->world->robotStates()[0];
  double dt = r->world->timeStep();
  EXPECT_NEAR(s.q[1], 0.7 - 0.4 * dt, 1e-3);  // the revolute joint, moving at -0.4 rad/s
  EXPECT_NEAR(s.q[0], -0.05 + 0.3 * dt, 1e-3);
  std::vector<Pose> fk = robot::linkPoses(*m, r->robots[0].coordinates, r->robots[0].base, s.q);
  EXPECT_LT((s.bodyPoses[2].position - fk[2].position).norm(), 1e-12);
  EXPECT_LT((s.bodyPoses[1].position - fk[1].position).norm(), 1e-12);
}

// A robot whose state stops being finite is named by World::nonFinite()
// (rscene-sim stops with RS7024), as a body is.
TEST(RobotSim, NonFiniteStateIsReported) {
  Eigen::VectorXd q0(1), u0(1);
  q0 << 0.5;
  u0 << 1e308;
  auto r = make("time_step 0.0025\n", {pendulum(2, 0.5, 0.02)}, {q0}, {u0});
  ASSERT_TRUE(r->world);
  // 1e308 rad/s is past the joint speed cap: diverged before any step.
  std::optional<NonFinite> first = r->world->nonFinite();
  ASSERT_TRUE(first);
  EXPECT_TRUE(first->diverged);
  for (int k = 0; k < 3 && !r->world->nonFinite(); ++k) r->world->step();
  std::optional<NonFinite> bad = r->world->nonFinite();
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->path, "/World/R0");
  EXPECT_TRUE(bad->what == "generalized coordinate" || bad->what == "generalized velocity") << bad->what;
}

// Robot control for programs that embed lib/sim (World::setRobotPd and
// friends; the Python module's RL loop).  A generalized force on a hanging
// pendulum at rest (no gravity torque there) gives the closed-form
// velocity tau / I dt at step one, and stays in force until changed.
TEST(RobotControl, TorqueGivesTheClosedFormAccelerationAtStepOne) {
  const double m = 2, d = 0.5, ic = 0.02, tau = 3;
  auto r = make("time_step 0.001\n", {pendulum(m, d, ic)});
  ASSERT_TRUE(r->world);
  ASSERT_EQ(r->world->robotIndex("/World/R0"), 0);
  EXPECT_EQ(r->world->robotIndex("/World/Nothing"), -1);
  EXPECT_EQ(r->world->setRobotGeneralizedForce(0, Eigen::VectorXd::Constant(1, tau)), "");
  r->world->step();
  Eigen::VectorXd q, u;
  r->world->robotState(0, q, u);
  EXPECT_NEAR(u[0], tau / (ic + m * d * d) * 0.001, 1e-12);
  r->world->step();
  r->world->robotState(0, q, u);
  EXPECT_NEAR(u[0], 2 * tau / (ic + m * d * d) * 0.001, 1e-6);
}

// PD targets hold the joint near them (against gravity: a sag of
// m g d sin(q) / kp at most); wrong sizes, values that are not finite and
// negative gains change nothing and say why.
TEST(RobotControl, PdTargetHoldsTheJointAndMisuseIsRefused) {
  auto r = make("time_step 0.001\n", {pendulum(2, 0.5, 0.02)});
  ASSERT_TRUE(r->world);
  World& w = *r->world;
  Eigen::VectorXd one = Eigen::VectorXd::Constant(1, 0.5), none;
  EXPECT_NE(w.setRobotPd(0, Eigen::VectorXd::Zero(2), none, one, one), "");
  EXPECT_NE(w.setRobotPd(0, one, none, Eigen::VectorXd::Constant(1, -1), one), "");
  EXPECT_NE(w.setRobotPd(0, Eigen::VectorXd::Constant(1, NAN), none, one, one), "");
  EXPECT_NE(w.setRobotGeneralizedForce(0, Eigen::VectorXd::Constant(1, INFINITY)), "");
  EXPECT_NE(w.setRobotState(0, one, Eigen::VectorXd::Zero(3)), "");
  for (int k = 0; k < 100; ++k) w.step();
  Eigen::VectorXd q, u;
  w.robotState(0, q, u);
  EXPECT_NEAR(q[0], 0, 1e-12);  // nothing of that acted
  ASSERT_EQ(w.setRobotPd(0, one, none, Eigen::VectorXd::Constant(1, 1000), Eigen::VectorXd::Constant(1, 20)), "");
  for (int k = 0; k < 3000; ++k) w.step();
  w.robotState(0, q, u);
  EXPECT_NEAR(q[0], 0.5, 2 * 9.81 * 0.5 * std::sin(0.5) / 1000 + 1e-3);
  EXPECT_NEAR(u[0], 0, 1e-3);
}

// A state set before the first step is the one read back and written
// back (robotStates() gives the record's only while nothing was set).
TEST(RobotControl, SetStateIsReadBackBeforeTheFirstStep) {
  auto r = make("time_step 0.001\n", {pendulum(2, 0.5, 0.02)});
  ASSERT_TRUE(r->world);
  ASSERT_EQ(r->world->setRobotState(0, Eigen::VectorXd::Constant(1, 0.25), Eigen::VectorXd::Constant(1, -1)), "");
  RobotState s = r->world->robotStates()[0];
  EXPECT_NEAR(s.q[0], 0.25, 1e-12);
  EXPECT_NEAR(s.u[0], -1, 1e-12);
}

// contacts(): a 1 kg box resting on the ground touches it at its four
// corners, the ground's normal up, the normal impulses carrying its weight.
TEST(WorldContacts, RestingBoxCarriesItsWeight) {
  LoadResult loaded = parse(
      "raisim_engine_scene 1\ntime_step 0.001\ngravity 0 0 -9.81\n"
      "object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 1 0 0 default engine_default false true false - static "
      "true 1 18446744073709551615\n"
      "object /World/Box box 0 0 0.1 1 0 0 0 0.2 0.2 0.2 1 1 1 default engine_default false true false - dynamic "
      "true 1 18446744073709551615\n");
  ASSERT_TRUE(loaded.ok());
  Scene scene;
  Diagnostics ds;
  ASSERT_TRUE(buildScene(loaded.document, {}, scene, ds));
  auto w = World::create(scene, ds);
  ASSERT_TRUE(w);
  EXPECT_TRUE(w->contacts().empty());
  for (int k = 0; k < 500; ++k) w->step();
  std::vector<World::Contact> cs = w->contacts();
  ASSERT_EQ(cs.size(), 4u);
  double impulse = 0;
  for (const World::Contact& c : cs) {
    EXPECT_EQ(c.recordA, scene.objects[1].recordIndex);
    EXPECT_EQ(c.recordB, scene.objects[0].recordIndex);
    EXPECT_TRUE(c.linkA.empty() && c.linkB.empty());
    EXPECT_NEAR(c.normal.z(), 1, 1e-9);
    EXPECT_NEAR(c.position.z(), 0, 1e-6);
    EXPECT_GT(c.depth, 0);
    impulse += c.impulse;
  }
  EXPECT_NEAR(impulse / 0.001, 9.81, 0.02 * 9.81);
}
