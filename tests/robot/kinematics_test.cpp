// Generalized coordinates and forward kinematics on models built in code,
// checked against poses worked out by hand.
#include "robot/kinematics.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rscene::robot {
namespace {

// base --(revolute about y, 1 m below)--> arm --(fixed)--> tip
//      \--(spherical at +x)--> ball
Model twoBranches(bool floating) {
  Model m;
  m.name = "t";
  m.floatingBase = floating;
  m.links.resize(4);
  m.links[0].name = "base";
  m.links[1].name = "arm";
  m.links[2].name = "tip";
  m.links[3].name = "ball";
  auto join = [&](const char* name, JointType type, int parent, int child, Eigen::Vector3d at) {
    Joint j;
    j.name = name;
    j.type = type;
    j.parentLink = parent;
    j.childLink = child;
    j.origin.position = at;
    j.axis = Eigen::Vector3d::UnitY();
    m.joints.push_back(j);
    int index = static_cast<int>(m.joints.size()) - 1;
    m.links[static_cast<std::size_t>(parent)].childJoints.push_back(index);
    m.links[static_cast<std::size_t>(child)].parentJoint = index;
  };
  join("hinge", JointType::Revolute, 0, 1, {0, 0, -1});
  join("weld", JointType::Fixed, 1, 2, {0, 0, -0.5});
  join("socket", JointType::Spherical, 0, 3, {1, 0, 0});
  return m;
}

TEST(Coordinates, RaiSimOrderAndDimensions) {
  Model m = twoBranches(true);
  Coordinates c;
  EXPECT_TRUE(makeCoordinates(m, {}, c).empty());
  ASSERT_EQ(c.joints.size(), 2u);
  EXPECT_EQ(m.joints[static_cast<std::size_t>(c.joints[0])].name, "hinge");
  EXPECT_EQ(m.joints[static_cast<std::size_t>(c.joints[1])].name, "socket");
  EXPECT_EQ(c.coordinateDim, 7 + 1 + 4);
  EXPECT_EQ(c.velocityDim, 6 + 1 + 3);
  EXPECT_EQ(c.coordinateIndex[2], 8);
  EXPECT_EQ(c.velocityIndex[2], 7);
  EXPECT_EQ(c.coordinateIndex[1], -1);  // fixed
  std::vector<std::string> names = coordinateNames(m, c, false);
  ASSERT_EQ(names.size(), 12u);
  EXPECT_EQ(names[7], "hinge");
  EXPECT_EQ(names[8], "socket_qw");
  EXPECT_EQ(coordinateNames(m, c, true)[9], "socket_wz");
}

TEST(Coordinates, JointOrderReordersAndReportsProblems) {
  Model m = twoBranches(false);
  Coordinates c;
  EXPECT_TRUE(makeCoordinates(m, {"socket", "hinge"}, c).empty());
  EXPECT_EQ(c.coordinateIndex[2], 0);
  EXPECT_EQ(c.coordinateIndex[0], 4);
  auto problems = makeCoordinates(m, {"socket", "weld", "hnge", "socket"}, c);
  ASSERT_EQ(problems.size(), 4u);
  EXPECT_EQ(problems[0].kind, JointOrderProblem::Fixed);
  EXPECT_EQ(problems[1].kind, JointOrderProblem::Unknown);
  EXPECT_EQ(problems[2].kind, JointOrderProblem::Repeated);
  EXPECT_EQ(problems[3].kind, JointOrderProblem::Missing);
  EXPECT_EQ(problems[3].name, "hinge");
  EXPECT_EQ(c.coordinateIndex[0], 0);  // the default order after problems
}

TEST(ForwardKinematics, RevoluteFixedAndSphericalByHand) {
  Model m = twoBranches(false);
  Coordinates c;
  makeCoordinates(m, {}, c);
  Pose base;
  base.position = {10, 0, 0};
  Eigen::VectorXd q = neutralCoordinate(m, c, base);
  q[0] = M_PI / 2;  // hinge: +90 degrees about y turns -z into -x
  // socket: 90 degrees about z
  Eigen::Quaterniond s(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  q.segment<4>(1) << s.w(), s.x(), s.y(), s.z();
  std::vector<Pose> p = linkPoses(m, c, base, q);
  EXPECT_TRUE(p[1].position.isApprox(Eigen::Vector3d(10, 0, -1)));
  // the tip hangs 0.5 m along the arm's -z, which the hinge turned to -x
  EXPECT_TRUE(p[2].position.isApprox(Eigen::Vector3d(9.5, 0, -1), 1e-12));
  EXPECT_TRUE(p[3].position.isApprox(Eigen::Vector3d(11, 0, 0)));
  EXPECT_TRUE((p[3].orientation * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
}

TEST(ForwardKinematics, FloatingBaseFromCoordinate) {
  Model m = twoBranches(true);
  Coordinates c;
  makeCoordinates(m, {}, c);
  Eigen::VectorXd q = neutralCoordinate(m, c, Pose{});
  q.head<3>() << 1, 2, 3;
  Eigen::Quaterniond yaw(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()));
  q.segment<4>(3) << yaw.w(), yaw.x(), yaw.y(), yaw.z();
  std::vector<Pose> p = linkPoses(m, c, Pose{}, q);
  EXPECT_TRUE(p[0].position.isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE(p[3].position.isApprox(Eigen::Vector3d(0, 2, 3), 1e-12));  // +x turned to -x
  EXPECT_EQ(frameLink(m, "socket"), 3);
  EXPECT_EQ(frameLink(m, "tip"), 2);
  EXPECT_EQ(frameLink(m, "nothing"), -1);
}

}  // namespace
}  // namespace rscene::robot
