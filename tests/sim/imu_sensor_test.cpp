// IMU readings (lib/sim/imu.cpp, sensor_recorder.cpp) against closed-form
// motion: at rest, in free fall, spinning, on a swinging robot link.
#include <gtest/gtest.h>

#include <cmath>

#include "robot/kinematics.hpp"
#include "sim/imu.hpp"
#include "sim/lidar_geometry.hpp"
#include "sim/sensor_test_scene.hpp"

using namespace rscene;
using namespace rscene::sim;
using namespace rscene::sim::test;
using Eigen::Vector3d;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Steps `seconds` and returns every IMU reading.
std::vector<ImuReading> readings(SensorRun& r, double seconds, std::size_t sensor = 0) {
  SensorRecorder rec(r.scene, *r.world, r.sensors);
  Collected c;
  EXPECT_TRUE(rec.sample(c));
  for (long i = 0, n = std::lround(seconds / r.world->timeStep()); i < n; ++i) {
    r.world->step();
    EXPECT_TRUE(rec.sample(c));
  }
  std::vector<ImuReading> out;
  for (auto& [s, reading] : c.imu)
    if (s == sensor) out.push_back(reading);
  return out;
}

const std::string kGround = object("/World/Ground", "ground", {0, 0, 0}, "20 20 1", 0.5, 1, 0, "static");

}  // namespace

TEST(Imu, AtRestOnTheGroundReadsGravityUpAndNoRotation) {
  // Two IMUs on a crate resting on the ground: one level, one rolled 90
  // degrees about x (its +y then points down... its +z points along world -y,
  // its +y along world +z: it reads +g on y).
  auto r = makeSensorRun(kGround + box("/World/Crate", {0, 0, 0.25}, {1, 1, 0.5}, "dynamic", 2, "id=crate") +
                         "sensor /World/Imu imu crate 0.3 0.2 0.1 1 0 0 0\n"
                         "sensor /World/Rolled imu crate 0 0 0 0.70710678118654757 0.70710678118654757 0 0\n");
  ASSERT_EQ(r->sensors.size(), 2u);
  std::vector<ImuReading> level = readings(*r, 1.0, 0);
  r = makeSensorRun(kGround + box("/World/Crate", {0, 0, 0.25}, {1, 1, 0.5}, "dynamic", 2, "id=crate") +
                    "sensor /World/Imu imu crate 0.3 0.2 0.1 1 0 0 0\n"
                    "sensor /World/Rolled imu crate 0 0 0 0.70710678118654757 0.70710678118654757 0 0\n");
  std::vector<ImuReading> rolled = readings(*r, 1.0, 1);
  ASSERT_EQ(level.size(), std::size_t(std::lround(1.0 / r->world->timeStep())));  // one per step from the first
  EXPECT_NEAR(level.front().time, r->world->timeStep(), 1e-15);
  // After it settles (contact solver jitter: 1e-3 m/s^2 allowed).
  const ImuReading& a = level.back();
  EXPECT_NEAR(a.specificForce.x(), 0, 1e-3);
  EXPECT_NEAR(a.specificForce.y(), 0, 1e-3);
  EXPECT_NEAR(a.specificForce.z(), 9.81, 1e-3);
  EXPECT_LT(a.angularVelocity.norm(), 1e-3);
  const ImuReading& b = rolled.back();
  EXPECT_NEAR(b.specificForce.y(), 9.81, 1e-3);
  EXPECT_NEAR(b.specificForce.z(), 0, 1e-3);
}

TEST(Imu, InFreeFallReadsZero) {
  auto r = makeSensorRun(box("/World/Crate", {0, 0, 100}, {1, 1, 1}, "dynamic", 1, "id=crate") +
                         "sensor /World/Imu imu crate 0.4 0 0 1 0 0 0\n");
  std::vector<ImuReading> rs = readings(*r, 0.5);
  ASSERT_FALSE(rs.empty());
  for (const ImuReading& x : rs) {
    EXPECT_LT(x.specificForce.norm(), 1e-9);
    EXPECT_LT(x.angularVelocity.norm(), 1e-12);
  }
}

TEST(Imu, OnASpinningBodyReadsItsRateAndTheCentripetalAcceleration) {
  // No gravity; a ball spinning at 2 rad/s about z; the IMU 0.5 m out on x.
  auto r = makeSensorRun("gravity 0 0 0\n" +
                         object("/World/Ball", "sphere", {0, 0, 1}, "1 1 1", 0.5, 1, 1, "dynamic", "id=ball") +
                         "sensor /World/Imu imu ball 0.5 0 0 1 0 0 0\n");
  ASSERT_TRUE(r->world->setAngularVelocity("ball", {0, 0, 2}));
  std::vector<ImuReading> rs = readings(*r, 0.5);
  ASSERT_FALSE(rs.empty());
  for (const ImuReading& x : rs) {
    EXPECT_NEAR(x.angularVelocity.z(), 2, 1e-9);
    EXPECT_LT(x.angularVelocity.head<2>().norm(), 1e-9);
    // w^2 r = 2 m/s^2 toward the axis: -x in the sensor frame, which turns
    // with the ball.  A finite difference over one step sees the chord of
    // the velocity's turn: within (w dt)^2 of it, and half a step's turn
    // (w dt / 2) off the radial direction.
    EXPECT_NEAR(x.specificForce.norm(), 2, 1e-3);
    EXPECT_NEAR(x.specificForce.x(), -2, 1e-2);
  }
}

TEST(Imu, NoiseIsSeededAndLimitsSaturate) {
  Pose level{{0, 0, 0}, Eigen::Quaterniond::Identity()};
  SensorParams p;
  p.noiseStddev = 0.1;
  p.noiseSeed = 5;
  Vector3d g(0, 0, -9.81), z = Vector3d::Zero();
  ImuReading a = imuReading(0.1, level, z, z, z, g, 0.01, p, 3), b = imuReading(0.1, level, z, z, z, g, 0.01, p, 3),
             c = imuReading(0.1, level, z, z, z, g, 0.01, p, 4);
  EXPECT_EQ(a.specificForce, b.specificForce);
  EXPECT_EQ(a.angularVelocity, b.angularVelocity);
  EXPECT_NE(a.specificForce, c.specificForce);
  EXPECT_NEAR(a.specificForce.z(), 9.81, 0.6);  // 6 sigma
  p.noiseStddev = 0;
  p.accelerationLimit = 5;
  p.angularVelocityLimit = 1;
  ImuReading s = imuReading(0.1, level, z, z, Vector3d(0, 3, -0.5), g, 0.01, p, 0);
  EXPECT_EQ(s.specificForce, Vector3d(0, 0, 5));
  EXPECT_EQ(s.angularVelocity, Vector3d(0, 1, -0.5));
}

TEST(Imu, CsvAndJsonLines) {
  ImuReading r;
  r.time = 0.25;
  r.specificForce = {0, 0.5, 9.81};
  r.angularVelocity = {1, -2, 0.125};
  std::string csv = imuHeader(ImuFormat::Csv), jsonl = imuHeader(ImuFormat::Jsonl);
  appendImu(csv, ImuFormat::Csv, r);
  appendImu(jsonl, ImuFormat::Jsonl, r);
  EXPECT_EQ(csv, "time,ax,ay,az,wx,wy,wz\n0.25,0,0.5,9.81,1,-2,0.125\n");
  EXPECT_EQ(jsonl, "{\"time\":0.25,\"acceleration\":[0,0.5,9.81],\"angularVelocity\":[1,-2,0.125]}\n");
}

namespace {

// A pendulum fixed to the world: a hinge about y at height 2, an arm whose
// centre of mass hangs 0.5 below it; link "arm" carries the sensors.
std::shared_ptr<robot::Model> pendulum() {
  auto m = std::make_shared<robot::Model>();
  m->name = "pendulum";
  m->floatingBase = false;
  robot::Link world, arm;
  world.name = "world";
  arm.name = "arm";
  arm.inertial.mass = 1;
  arm.inertial.origin.position = {0, 0, -0.5};
  arm.inertial.inertia = 0.01 * Eigen::Matrix3d::Identity();
  robot::Collision c;
  c.geometry.kind = robot::GeometryKind::Box;
  c.geometry.size = {0.1, 0.1, 1};
  c.origin.position = {0, 0, -0.5};
  arm.collisions.push_back(c);
  arm.parentJoint = 0;
  world.childJoints.push_back(0);
  robot::Joint j;
  j.name = "hinge";
  j.type = robot::JointType::Revolute;
  j.parentLink = 0;
  j.childLink = 1;
  j.origin.position = {0, 0, 2};
  j.axis = Vector3d::UnitY();
  m->joints.push_back(j);
  m->links.push_back(world);
  m->links.push_back(arm);
  m->root = 0;
  return m;
}

}  // namespace

TEST(Imu, ASensorOnARobotLinkMovesWithTheLink) {
  // Started 0.3 rad off vertical: the arm swings; the IMU at the arm's tip
  // (1 m below the hinge) follows the link's forward kinematics and reads
  // the hinge's rate about its y axis.
  auto model = pendulum();
  auto r = makeSensorRun(
      "sensor /World/R0/Tip imu /World/R0 0 0 -1 1 0 0 0 parentLink=arm\n"
      "sensor /World/R0/Scan lidar /World/R0 0 0 -1 1 0 0 0 parentLink=arm lidarChannels=1 "
      "lidarSamples=8 updateRate=50\n",
      nullptr, {model});
  ASSERT_EQ(r->sensors.size(), 2u);
  ASSERT_EQ(r->sensors[0].spec.link, 1);
  // Tilt the arm: a new world whose robot starts at q = 0.3.
  r->robots[0].q[0] = 0.3;
  r->world = World::create(r->scene, r->diags, [&] {
    WorldOptions wo;
    wo.robots = &r->robots;
    wo.document = &r->doc;
    return wo;
  }());
  ASSERT_TRUE(r->world);
  SensorRecorder rec(r->scene, *r->world, r->sensors);
  Collected c;
  ASSERT_TRUE(rec.sample(c));
  std::vector<Vector3d> tips;
  for (int i = 0; i < 200; ++i) {
    r->world->step();
    ASSERT_TRUE(rec.sample(c));
    RobotState s = r->world->robotStates()[0];
    std::vector<Pose> links = robot::linkPoses(*model, r->robots[0].coordinates, r->robots[0].base, s.q);
    Pose expected = links[1] * Pose{{0, 0, -1}, Eigen::Quaterniond::Identity()};
    Pose got = robot::sensorPose(r->sensors[0].spec, r->scene, currentPoses(r->scene, *r->world));
    ASSERT_LT((got.position - expected.position).norm(), 1e-12);
    tips.push_back(got.position);
    const ImuReading& last = c.imu.back().second;
    EXPECT_NEAR(last.angularVelocity.y(), s.u[0], 1e-9);
    EXPECT_LT(std::abs(last.angularVelocity.x()) + std::abs(last.angularVelocity.z()), 1e-9);
  }
  // It swung: the tip went from x = -sin(0.3) (+0.3 about y turns -z
  // toward -x) through the bottom.
  EXPECT_NEAR(tips.front().x(), -std::sin(0.3), 0.01);
  double lowest = 10;
  for (const Vector3d& p : tips) lowest = std::min(lowest, p.z());
  EXPECT_NEAR(lowest, 1.0, 0.01);
  // The LiDAR's scans carry the link's pose at their time.
  ASSERT_FALSE(c.scans.empty());
  EXPECT_NEAR(c.scans.front().pose.position.x(), -std::sin(0.3), 1e-9);
  EXPECT_GT(std::abs(c.scans.back().pose.position.x() - c.scans.front().pose.position.x()), 0.05);
}

TEST(SensorSets, ARobotsSensorSetIsRecordedUnderItsPathAndKeepsItsSettings) {
  // RaiSim's sensor sets (lib/robot fills Model::sensors from a URDF): a
  // clockwise LiDAR looking 80 degrees up from just under the arm, and an
  // IMU with limits, both on link "arm".
  auto model = pendulum();
  robot::SensorDef lidar;
  lidar.set = "arm";
  lidar.name = "lidar";
  lidar.kind = "lidar";
  lidar.link = 1;
  lidar.origin.position = {0, 0, -1.1};
  lidar.params.lidarChannels = 1;
  lidar.params.lidarSamples = 4;
  lidar.params.lidarMinPitch = lidar.params.lidarMaxPitch = 80;
  lidar.params.lidarMinRange = 0.05;
  lidar.params.lidarMaxRange = 10;
  lidar.params.lidarClockwise = true;
  robot::SensorDef imu = lidar;
  imu.name = "imu";
  imu.kind = "imu";
  imu.params = {};
  imu.params.accelerationLimit = 5;
  model->sensors = {lidar, imu};
  auto r = makeSensorRun("", nullptr, {model});
  ASSERT_EQ(r->sensors.size(), 2u);
  EXPECT_EQ(r->sensors[0].output, "World+R0+arm+lidar");
  EXPECT_EQ(r->sensors[1].output, "World+R0+arm+imu.csv");
  // Clockwise: the second ray of a turn points to -y.
  EXPECT_LT((r->sensors[0].directions[1] - Vector3d(0, -std::cos(80 * kPi / 180), std::sin(80 * kPi / 180))).norm(),
            1e-12);
  SensorRecorder rec(r->scene, *r->world, r->sensors);
  Collected c;
  ASSERT_TRUE(rec.sample(c));
  r->world->step();
  ASSERT_TRUE(rec.sample(c));
  // The arm's own box, 0.1 m above, is the body the LiDAR rides on: not seen.
  ASSERT_EQ(c.scans.size(), 2u);
  EXPECT_TRUE(c.scans[0].points.empty());
  RayGeometry g(*r->world);
  Vector3d up = c.scans[0].pose.orientation * r->sensors[0].directions[0];
  EXPECT_NEAR(g.cast(c.scans[0].pose.position, up, 10), 0.1 / std::sin(80 * kPi / 180), 1e-9);
  // At rest (hanging straight down) the IMU reads +9.81 up, clamped to 5.
  ASSERT_EQ(c.imu.size(), 1u);
  EXPECT_NEAR(c.imu[0].second.specificForce.z(), 5, 1e-12);
}
