// The IK solver on models built in code: a planar 3-link arm (links of
// 1 m, revolute about z), a chain with a spherical joint, a floating base.
#include "robot/ik.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/loader.hpp"
#include "robot/load.hpp"
#include "scene/scene.hpp"

namespace rscene::robot {
namespace {

void join(Model& m, const char* name, JointType type, int parent, int child, Eigen::Vector3d at,
          Eigen::Vector3d axis = Eigen::Vector3d::UnitZ()) {
  Joint j;
  j.name = name;
  j.type = type;
  j.parentLink = parent;
  j.childLink = child;
  j.origin.position = at;
  j.axis = axis;
  m.joints.push_back(j);
  int index = static_cast<int>(m.joints.size()) - 1;
  m.links[static_cast<std::size_t>(parent)].childJoints.push_back(index);
  m.links[static_cast<std::size_t>(child)].parentJoint = index;
}

// base -j1-> l1 -j2-> l2 -j3-> l3 -tip_joint(fixed)-> tip; each step 1 m along x.
Model arm(bool floating = false) {
  Model m;
  m.name = "arm";
  m.floatingBase = floating;
  for (const char* n : {"base", "l1", "l2", "l3", "tip"}) m.links.emplace_back().name = n;
  join(m, "j1", JointType::Revolute, 0, 1, {0, 0, 0});
  join(m, "j2", JointType::Revolute, 1, 2, {1, 0, 0});
  join(m, "j3", JointType::Revolute, 2, 3, {1, 0, 0});
  join(m, "tip_joint", JointType::Fixed, 3, 4, {1, 0, 0});
  return m;
}

struct Arm {
  Model model;
  Coordinates c;
  Eigen::VectorXd q;
  explicit Arm(Model m) : model(std::move(m)) {
    makeCoordinates(model, {}, c);
    q = neutralCoordinate(model, c, Pose{});
  }
  Eigen::Vector3d at(int link) const { return linkPoses(model, c, Pose{}, q)[static_cast<std::size_t>(link)].position; }
};

IkTarget target(int link, Eigen::Vector3d p, double tolerance = 1e-4) {
  IkTarget t;
  t.link = link;
  t.position = p;
  t.positionTolerance = tolerance;
  return t;
}

IkSettings settings(IkMethod method) {
  IkSettings s;
  s.method = method;
  s.maxIterations = 500;
  return s;
}

class EachMethod : public ::testing::TestWithParam<IkMethod> {};

TEST_P(EachMethod, ReachesAReachableTargetWithinTolerance) {
  Arm a(arm());
  a.q << 0.1, 0.2, 0.1;  // away from the straight (singular) pose
  const Eigen::Vector3d goal(1.5, 1.2, 0);
  IkResult r = solveTargets(a.model, a.c, Pose{}, {target(4, goal)}, settings(GetParam()), a.q);
  EXPECT_TRUE(r.converged) << "after " << r.iterations << " iterations, residual " << r.residuals[0].position;
  EXPECT_TRUE(r.applied);
  EXPECT_LE((a.at(4) - goal).norm(), 1e-4);
  EXPECT_LE(r.residuals[0].position, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(Ik, EachMethod,
                         ::testing::Values(IkMethod::DampedLeastSquares, IkMethod::PseudoInverse, IkMethod::Transpose));

TEST(Ik, UnreachableTargetReportsItsResidualAndAppliesTheBestPose) {
  Arm a(arm());
  a.q << 0.3, 0.3, 0.3;
  IkResult r = solveTargets(a.model, a.c, Pose{}, {target(4, {5, 0, 0})}, settings(IkMethod::DampedLeastSquares), a.q);
  EXPECT_FALSE(r.converged);
  ASSERT_EQ(r.residuals.size(), 1u);
  EXPECT_FALSE(r.residuals[0].reached);
  // The arm reaches 3 m: the best it can do is stretch out towards x.
  EXPECT_NEAR(r.residuals[0].position, 2.0, 1e-2);
  EXPECT_NEAR(a.at(4).x(), 3.0, 1e-2);
}

TEST(Ik, WithoutApplyBestOnFailureTheRecordPoseIsKept) {
  Arm a(arm());
  a.q << 0.3, 0.3, 0.3;
  Eigen::VectorXd before = a.q;
  IkSettings s = settings(IkMethod::DampedLeastSquares);
  s.applyBestOnFailure = false;
  IkResult r = solveTargets(a.model, a.c, Pose{}, {target(4, {5, 0, 0})}, s, a.q);
  EXPECT_FALSE(r.applied);
  EXPECT_EQ(a.q, before);
  EXPECT_GT(r.residuals[0].position, 2.0);  // the residual at the kept pose
}

TEST(Ik, JointLimitsAreEnforced) {
  Arm a(arm());
  a.model.joints[1].hasLimits = true;  // j2: the elbow barely bends
  a.model.joints[1].lower = -0.1;
  a.model.joints[1].upper = 0.1;
  a.q << 0.1, 0.05, 0.1;
  // Reaching (0.5, 0.5) needs a sharply bent elbow.
  IkSettings s = settings(IkMethod::DampedLeastSquares);
  solveTargets(a.model, a.c, Pose{}, {target(4, {0.5, 0.5, 0})}, s, a.q);
  EXPECT_GE(a.q[1], -0.1);
  EXPECT_LE(a.q[1], 0.1);
  // Without enforcement the same solve leaves the limits.
  a.q << 0.1, 0.05, 0.1;
  s.enforceJointLimits = false;
  IkResult free = solveTargets(a.model, a.c, Pose{}, {target(4, {0.5, 0.5, 0})}, s, a.q);
  EXPECT_TRUE(free.converged);
  EXPECT_GT(std::abs(a.q[1]), 0.1);
}

TEST(Ik, OrientationTargetIsReached) {
  Arm goal(arm());
  goal.q << 0.4, 0.6, -0.3;
  Pose want = linkPoses(goal.model, goal.c, Pose{}, goal.q)[4];
  Arm a(arm());
  a.q << 0.1, 0.1, 0.1;
  IkTarget t = target(4, want.position);
  t.useOrientation = true;
  t.orientation = want.orientation;
  t.orientationTolerance = 1e-4;
  IkResult r = solveTargets(a.model, a.c, Pose{}, {t}, settings(IkMethod::DampedLeastSquares), a.q);
  ASSERT_TRUE(r.converged);
  Pose got = linkPoses(a.model, a.c, Pose{}, a.q)[4];
  EXPECT_LE(got.orientation.angularDistance(want.orientation), 1e-4);
  EXPECT_LE(r.residuals[0].orientation, 1e-4);
}

// Six rows for three joints: damped least squares solves the smaller
// (joint-space) system then.
TEST_P(EachMethod, SeveralTargetsOfOneRobotAreSolvedTogether) {
  Arm goal(arm());
  goal.q << -0.5, 0.8, 0.4;
  Eigen::Vector3d elbow = goal.at(2), tip = goal.at(4);
  Arm a(arm());
  a.q << 0.1, 0.1, 0.1;
  IkSettings s = settings(GetParam());
  s.maxIterations = 5000;  // the transpose method crawls
  IkResult r = solveTargets(a.model, a.c, Pose{}, {target(2, elbow), target(4, tip)}, s, a.q);
  ASSERT_TRUE(r.converged) << r.iterations;
  EXPECT_LE((a.at(2) - elbow).norm(), 1e-4);
  EXPECT_LE((a.at(4) - tip).norm(), 1e-4);
  for (int k = 0; k < 3; ++k)  // two points fix this arm's pose (angles modulo a turn)
    EXPECT_LT(std::abs(std::remainder(a.q[k] - goal.q[k], 2 * M_PI)), 1e-3) << k << ": " << a.q.transpose();
}

TEST(Ik, FloatingBaseStaysWhereItIs) {
  Arm a(arm(true));
  a.q.head<3>() << 1, 2, 0.5;
  a.q.tail<3>() << 0.1, 0.2, 0.1;
  Eigen::VectorXd base = a.q.head<7>();
  IkResult r = solveTargets(a.model, a.c, Pose{}, {target(4, {2.5, 3.2, 0.5})}, settings(IkMethod::DampedLeastSquares), a.q);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(a.q.head<7>(), base);
  EXPECT_LE((a.at(4) - Eigen::Vector3d(2.5, 3.2, 0.5)).norm(), 1e-4);
}

TEST(Ik, SphericalJointReachesAPointOffThePlane) {
  Model m;
  m.name = "ball";
  m.floatingBase = false;
  for (const char* n : {"base", "rod", "end"}) m.links.emplace_back().name = n;
  join(m, "socket", JointType::Spherical, 0, 1, {0, 0, 0});
  join(m, "end_joint", JointType::Fixed, 1, 2, {0, 0, 1});
  Arm a(std::move(m));
  Eigen::Vector3d goal = Eigen::Vector3d(0.3, -0.4, 0.5).normalized();
  IkResult r = solveTargets(a.model, a.c, Pose{}, {target(2, goal)}, settings(IkMethod::DampedLeastSquares), a.q);
  ASSERT_TRUE(r.converged);
  EXPECT_LE((a.at(2) - goal).norm(), 1e-4);
  EXPECT_NEAR(a.q.head<4>().norm(), 1.0, 1e-12);  // still a unit quaternion
}

// Nothing can move (fixed joints only, fixed base): every method gives up
// at once with the residual, no empty-matrix arithmetic (an Eigen assertion
// in builds with assertions, found by fuzzing).
TEST_P(EachMethod, ARobotWithNothingToMoveReportsItsResidual) {
  Model m;
  m.name = "rigid";
  m.floatingBase = false;
  for (const char* n : {"base", "tip"}) m.links.emplace_back().name = n;
  join(m, "weld", JointType::Fixed, 0, 1, {1, 0, 0});
  Arm a(std::move(m));
  ASSERT_EQ(a.c.velocityDim, 0);
  IkResult r = solveTargets(a.model, a.c, Pose{}, {target(1, {2, 0, 0})}, settings(GetParam()), a.q);
  EXPECT_FALSE(r.converged);
  EXPECT_NEAR(r.residuals[0].position, 1.0, 1e-12);
}

// The analytic Jacobian against finite differences of forward kinematics,
// on a floating base with a spherical and a prismatic joint.
TEST(Ik, AnalyticJacobianMatchesFiniteDifferences) {
  Model m = arm(true);
  m.joints[1].type = JointType::Spherical;
  m.joints[2].type = JointType::Prismatic;
  m.joints[2].axis = Eigen::Vector3d(0, 0.6, 0.8);
  Arm a(std::move(m));
  a.q.head<3>() << 0.5, -1, 2;
  Eigen::Quaterniond b = Eigen::Quaterniond(0.9, 0.1, -0.3, 0.2).normalized();
  a.q.segment<4>(3) << b.w(), b.x(), b.y(), b.z();
  a.q[7] = 0.4;  // j1
  Eigen::Quaterniond s = Eigen::Quaterniond(0.8, 0.3, 0.2, -0.1).normalized();
  a.q.segment<4>(8) << s.w(), s.x(), s.y(), s.z();
  a.q[12] = 0.25;  // j3, prismatic
  ASSERT_EQ(a.c.velocityDim, 6 + 1 + 3 + 1);
  std::vector<Pose> poses = linkPoses(a.model, a.c, Pose{}, a.q);
  Eigen::MatrixXd J = frameJacobian(a.model, a.c, poses, 4, poses[4].position);
  const double h = 1e-6;
  for (int k = 0; k < a.c.velocityDim; ++k) {
    Eigen::VectorXd du = Eigen::VectorXd::Zero(a.c.velocityDim);
    du[k] = h;
    Eigen::VectorXd qp = a.q, qm = a.q;
    integrate(a.model, a.c, qp, du);
    integrate(a.model, a.c, qm, -du);
    Pose pp = linkPoses(a.model, a.c, Pose{}, qp)[4], pm = linkPoses(a.model, a.c, Pose{}, qm)[4];
    Eigen::Vector3d v = (pp.position - pm.position) / (2 * h);
    Eigen::AngleAxisd w(pp.orientation * pm.orientation.conjugate());
    Eigen::Vector3d omega = w.angle() * w.axis() / (2 * h);
    EXPECT_LT((J.block<3, 1>(0, k) - v).norm(), 1e-6) << "column " << k;
    EXPECT_LT((J.block<3, 1>(3, k) - omega).norm(), 1e-6) << "column " << k;
  }
}

TEST(Ik, SettingsThatCannotBeUsedAreNamed) {
  ArticulatedIk ik;
  ik.maxIterations = 80;
  ik.positionTolerance = 1e-3;
  ik.orientationTolerance = 1e-2;
  ik.orientationWeight = 0.5;
  ik.damping = 0.05;
  ik.stepSize = 0.5;
  ik.maxStep = 0.1;
  ik.svdTolerance = 1e-6;
  ik.finiteDifferenceStep = 1e-4;
  ik.inverseMethod = "damped_least_squares";
  EXPECT_TRUE(ikSettingsProblems(ik).empty());
  ik.maxIterations = 1000000;
  ik.stepSize = 0;
  ik.damping = std::nan("");
  ik.inverseMethod = "newton";
  auto problems = ikSettingsProblems(ik);
  ASSERT_EQ(problems.size(), 4u);
  EXPECT_EQ(problems[0].first, "maxIterations");
  EXPECT_EQ(problems[1].first, "damping");
  EXPECT_EQ(problems[2].first, "stepSize");
  EXPECT_EQ(problems[3].first, "inverseMethod");
}

// solveIk reads the record's knobs and reports at its fields.
TEST(Ik, SolveIkReportsUnreachedTargetsAndUnknownFramesAtTheRecord) {
  LoadResult loaded = parse(
      "raisim_engine_scene 1\n"
      "articulated_resource arm_res Arm arm.urdf\n"
      "articulated /World/Arm arm_res 0 0 0 1 0 0 0 true true id=arm generalizedCoordinate=0.3,0.3,0.3\n"
      "articulated_ik /World/Arm tip 1.5,1.2,0 maxIterations=500 positionTolerance=1e-5\n"
      "articulated_ik /World/Arm l2 9,0,0 enabled=false\n");
  ASSERT_TRUE(loaded.ok());
  Scene scene;
  Diagnostics diags;
  ASSERT_TRUE(buildScene(loaded.document, SceneOptions{}, scene, diags));
  ASSERT_EQ(scene.articulated.size(), 1u);
  ASSERT_EQ(scene.articulated[0].ik.size(), 2u);
  RobotInstance robot;
  robot.record = &scene.articulated[0];
  robot.model = std::make_shared<Model>(arm());
  makeCoordinates(*robot.model, {}, robot.coordinates);
  robot.q = Eigen::Vector3d(0.3, 0.3, 0.3);
  EXPECT_TRUE(solveIk(loaded.document, robot, diags));
  EXPECT_TRUE(diags.empty()) << diags[0].message;  // the disabled target is not solved
  EXPECT_LE((linkPoses(robot)[4].position - Eigen::Vector3d(1.5, 1.2, 0)).norm(), 1e-5);

  scene.articulated[0].ik[0].target = {7, 0, 0};
  EXPECT_TRUE(solveIk(loaded.document, robot, diags));
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, "RS7047");
  EXPECT_EQ(diags[0].severity, Severity::Warning);
  EXPECT_EQ(diags[0].line, 4u);
  EXPECT_NE(diags[0].message.find("position residual 4 m"), std::string::npos) << diags[0].message;

  diags.clear();
  scene.articulated[0].ik[0].frame = "tpi";
  EXPECT_FALSE(solveIk(loaded.document, robot, diags));
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, "RS7044");
  EXPECT_EQ(diags[0].hint, "did you mean 'tip'?");
}

// The corpus ANYmal C in its standing pose: all four feet moved 4 cm at
// once with the record's default knobs; the base and nothing else moves.
TEST(Ik, AnymalFeetWithTheDefaultKnobs) {
  const std::string urdf = std::string(RSCENE_SHARED_DIR) + "/corpus/robots/anymal_c/urdf/anymal.urdf";
  Model model;
  Diagnostics diags;
  if (!loadModel(urdf, LoadOptions{}, model, diags)) GTEST_SKIP() << "no ../shared corpus";
  Coordinates c;
  ASSERT_TRUE(makeCoordinates(model, {}, c).empty());
  Eigen::VectorXd q(19);
  q << 0, 0, 0.54, 1, 0, 0, 0, 0.03, 0.4, -0.8, -0.03, 0.4, -0.8, 0.03, -0.4, 0.8, -0.03, -0.4, 0.8;
  std::vector<Pose> at = linkPoses(model, c, Pose{}, q);
  std::vector<IkTarget> feet;
  for (const char* foot : {"LF_FOOT", "RF_FOOT", "LH_FOOT", "RH_FOOT"}) {
    int link = frameLink(model, foot);
    ASSERT_GE(link, 0) << foot;
    IkTarget t;  // the record's defaults: 1 mm
    t.link = link;
    t.position = at[static_cast<std::size_t>(link)].position + Eigen::Vector3d(0.03, 0, 0.04) * (feet.size() % 2 ? -1 : 1);
    feet.push_back(t);
  }
  Eigen::VectorXd solved = q;
  IkResult r = solveTargets(model, c, Pose{}, feet, IkSettings{}, solved);
  ASSERT_TRUE(r.converged) << r.iterations << " iterations";
  EXPECT_EQ(solved.head<7>(), q.head<7>());
  std::vector<Pose> now = linkPoses(model, c, Pose{}, solved);
  for (const IkTarget& t : feet) EXPECT_LE((now[static_cast<std::size_t>(t.link)].position - t.position).norm(), 1e-3);
}

}  // namespace
}  // namespace rscene::robot
