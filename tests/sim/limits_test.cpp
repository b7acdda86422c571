// The simulator's limits (sim/limits.hpp): up-front refusals with their
// field, the step count without overflow, the state check after a step,
// and the broadphase filter that keeps static pairs out of the pair cache.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <limits>

#include "core/loader.hpp"
#include "scene/scene.hpp"
#include "scene/limits.hpp"
#include "sim/limits.hpp"
#include "sim/world.hpp"

using namespace rscene;
using namespace rscene::sim;

namespace {

struct Loaded {
  Document doc;
  Scene scene;
  Diagnostics diags;
};

std::unique_ptr<Loaded> load(const std::string& body) {
  auto r = std::make_unique<Loaded>();
  LoadResult loaded = parse("raisim_engine_scene 1\n" + body);
  EXPECT_TRUE(loaded.ok());
  r->doc = std::move(loaded.document);
  EXPECT_TRUE(buildScene(r->doc, {}, r->scene, r->diags));
  return r;
}

std::string box(const std::string& path, const std::string& pose, const std::string& mass, const std::string& mode,
                const std::string& size = "0.4 0.4 0.4") {
  return "object " + path + " box " + pose + " " + size + " 0.5 1 " + mass +
         " default engine_default false true false - " + mode + " true 1 18446744073709551615\n";
}

const std::string kGround = box("/World/Ground", "0 0 0 1 0 0 0", "0", "static", "10 10 1");

}  // namespace

TEST(StepsFor, RoundsAndRefusesWhatDoesNotFit) {
  EXPECT_EQ(stepsFor(1, 0.001, kDefaultMaxSteps), 1000u);
  EXPECT_EQ(stepsFor(0, 0.001, kDefaultMaxSteps), 0u);
  EXPECT_EQ(stepsFor(1.4, 0.1, kDefaultMaxSteps), 14u);  // 13.999999999999998 rounds, not truncates
  EXPECT_EQ(stepsFor(10, 1e-6, 10'000'000), 10'000'000u);  // exactly at the cap
  EXPECT_EQ(stepsFor(10.00001, 1e-6, 10'000'000), std::nullopt);
  // Quotients past the integer range are refused before any conversion.
  EXPECT_EQ(stepsFor(1e300, 0.001, kDefaultMaxSteps), std::nullopt);
  EXPECT_EQ(stepsFor(1, 5e-324, kDefaultMaxSteps), std::nullopt);
  EXPECT_EQ(stepsFor(1, 1e-12, kDefaultMaxSteps), std::nullopt);
  EXPECT_EQ(stepsFor(std::numeric_limits<double>::quiet_NaN(), 0.001, kDefaultMaxSteps), std::nullopt);
  EXPECT_EQ(stepsFor(1e300, 0.001, std::numeric_limits<std::uint64_t>::max()), std::nullopt);
}

TEST(CheckLimits, RefusesASubnormalMassAtItsField) {
  auto r = load("time_step 0.001\n" + kGround + box("/World/Box", "0 0 1 1 0 0 0", "4.9e-324", "dynamic"));
  EXPECT_FALSE(checkNumericLimits(r->doc, r->scene, r->diags));
  ASSERT_EQ(r->diags.size(), 1u);
  EXPECT_EQ(r->diags[0].code, scene_code::kBadMassValue);
  EXPECT_EQ(r->diags[0].line, 4u);
  EXPECT_EQ(r->diags[0].column, 55u);
}

TEST(CheckLimits, AcceptsSmallNormalMassesAndStaticBodies) {
  auto r = load(kGround + box("/World/Light", "0 0 1 1 0 0 0", "1e-300", "dynamic") +
                box("/World/Wall", "3 0 1 1 0 0 0", "4.9e-324", "static"));
  EXPECT_TRUE(checkNumericLimits(r->doc, r->scene, r->diags));
  EXPECT_TRUE(r->diags.empty());
}

TEST(CheckLimits, RefusesAnOrientationThatDoesNotNormalise) {
  auto r = load(kGround + box("/World/Box", "0 0 1 1e308 1e308 0 0", "2", "dynamic"));
  EXPECT_FALSE(checkNumericLimits(r->doc, r->scene, r->diags));
  ASSERT_FALSE(r->diags.empty());
  EXPECT_EQ(r->diags.back().code, scene_code::kBadPose);
  EXPECT_EQ(r->diags.back().field, "orientation");
}

TEST(CheckLimits, RefusesATimeStepBelowTheMinimum) {
  for (const char* dt : {"1e-12", "5e-324"}) {  // 0 and -1 are RS7008 (checkScene)
    auto r = load(std::string("time_step ") + dt + "\n" + kGround);
    EXPECT_FALSE(checkNumericLimits(r->doc, r->scene, r->diags)) << dt;
    ASSERT_FALSE(r->diags.empty()) << dt;
    EXPECT_EQ(r->diags.back().code, scene_code::kTinyTimeStep) << dt;
    EXPECT_EQ(r->diags.back().line, 2u) << dt;
  }
  auto ok = load("time_step 1e-9\n" + kGround);
  EXPECT_TRUE(checkNumericLimits(ok->doc, ok->scene, ok->diags));
}

TEST(TooManySteps, PointsAtTheTimeStepWhenThereIsOne) {
  auto r = load("time_step 0.001\n" + kGround);
  Diagnostic d = tooManySteps(r->doc, "--steps 11", 10);
  EXPECT_EQ(d.code, limit_code::kTooManySteps);
  EXPECT_EQ(d.line, 2u);
  EXPECT_EQ(d.message, "--steps 11, more than the limit of 10 steps");
  auto none = load(kGround);
  EXPECT_EQ(tooManySteps(none->doc, "--steps 11", 10).line, 0u);
}

TEST(NonFinite, AStateThatOverflowsIsFoundWithItsBody) {
  auto r = load("time_step 0.001\n" + kGround + box("/World/Heavy", "0 0 0.25 1 0 0 0", "1e300", "dynamic"));
  // Refused up front (RS7020, issue 10: validate and sim agree); a program
  // that builds the world anyway still has the watchdog.
  Diagnostics refused;
  EXPECT_FALSE(checkNumericLimits(r->doc, r->scene, refused));
  auto world = World::create(r->scene, r->diags);
  ASSERT_TRUE(world);
  EXPECT_EQ(world->nonFinite(), std::nullopt);
  std::optional<NonFinite> bad;
  for (int i = 0; i < 100 && !bad; ++i) {
    world->step();
    bad = world->nonFinite();
  }
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->path, "/World/Heavy");
  EXPECT_EQ(bad->recordIndex, 3);
  Diagnostic d = nonFiniteError(r->doc, *bad);
  EXPECT_EQ(d.code, limit_code::kNonFinite);
  EXPECT_EQ(d.line, 4u);
}

// Past kMaxLength a body has left the world, with or without static
// geometry to fall below (Bullet itself drops only bodies faster than
// 10^6 m per step, which the shell tests cover).
TEST(Departure, ABodyFartherThanTheLargestLengthHasLeft) {
  auto r = load("time_step 1\ngravity 0 0 0\n" + box("/World/Probe", "0 0 0 1 0 0 0", "1", "dynamic"));
  auto world = World::create(r->scene, r->diags);
  ASSERT_TRUE(world);
  ASSERT_TRUE(world->setLinearVelocity("/World/Probe", {9e5, 0, 0}));
  for (int i = 0; i < 1200000 && world->departures().empty(); ++i) world->step();
  ASSERT_EQ(world->departures().size(), 1u);
  const Departure& d = world->departures()[0];
  EXPECT_EQ(d.reason, "went more than 1e+12 m from the origin");
  EXPECT_GT(d.position.x(), kMaxLength);
  EXPECT_LT(d.position.x(), kMaxLength + 1e6);
}

TEST(NonFinite, AnOrdinaryDropStaysFinite) {
  auto r = load("time_step 0.001\n" + kGround + box("/World/Box", "0 0 1 1 0 0 0", "2", "dynamic"));
  auto world = World::create(r->scene, r->diags);
  ASSERT_TRUE(world);
  for (int i = 0; i < 1000; ++i) world->step();
  EXPECT_EQ(world->nonFinite(), std::nullopt);
}

// With a cap of one pair, any pair the filter lets through beyond the first
// overflows: co-located static and kinematic bodies must make none.
TEST(PairFilter, StaticAndKinematicBodiesNeverPair) {
  std::string body = "time_step 0.001\n";
  for (int i = 0; i < 200; ++i)
    body += box("/World/S" + std::to_string(i), "0 0 0 1 0 0 0", "1", i % 2 ? "static" : "kinematic");
  auto r = load(body);
  WorldOptions wo;
  wo.maxPairs = 1;
  auto world = World::create(r->scene, r->diags, wo);
  ASSERT_TRUE(world);
  world->step();
  EXPECT_EQ(world->pairOverflow(), std::nullopt);
}

TEST(PairFilter, CoLocatedDynamicBodiesHitTheCap) {
  std::string body = "time_step 0.001\n";
  for (int i = 0; i < 10; ++i) body += box("/World/D" + std::to_string(i), "0 0 0 1 0 0 0", "1", "dynamic");
  auto r = load(body);
  WorldOptions wo;
  wo.maxPairs = 44;  // 10 bodies in one spot make 45 pairs
  auto capped = World::create(r->scene, r->diags, wo);
  ASSERT_TRUE(capped);
  capped->step();
  ASSERT_TRUE(capped->pairOverflow());
  EXPECT_GE(*capped->pairOverflow(), 1);  // one of the body records
  EXPECT_LE(*capped->pairOverflow(), 10);
  Diagnostic d = tooManyPairs(r->doc, *capped->pairOverflow(), capped->steps(), 44);
  EXPECT_EQ(d.code, limit_code::kTooManyPairs);
  EXPECT_EQ(d.line, static_cast<std::uint32_t>(*capped->pairOverflow() + 1));
  wo.maxPairs = 45;
  auto fits = World::create(r->scene, r->diags, wo);
  fits->step();
  EXPECT_EQ(fits->pairOverflow(), std::nullopt);
}

// RS7094: what the LiDAR scans of a run take on disk, at most.
TEST(SimLimits, LidarOutputIsEstimatedBeforeTheRunAndWarnedPastOneGiB) {
  auto l = load("time_step 0.01\nsensor /World/Lidar lidar - 0 0 1 1 0 0 0 updateRate=5 lidarChannels=64 lidarSamples=2048\n");
  RecordedSensor lidar;
  lidar.spec.kind = robot::SensorKind::Lidar;
  lidar.spec.name = "/World/Lidar";
  lidar.spec.recordIndex = 2;
  lidar.spec.params.updateRate = 5;
  lidar.directions.assign(64 * 2048, Eigen::Vector3d::UnitX());
  // One scan at 0, then one each 0.2 s: 10 s at 0.01 s a step is 51.
  EXPECT_EQ(lidarScansInRun(lidar, 1000, 0.01), 51u);
  EXPECT_EQ(lidarScansInRun(lidar, 0, 0.01), 1u);
  RecordedSensor everyStep = lidar;
  everyStep.spec.params.updateRate = 0;
  EXPECT_EQ(lidarScansInRun(everyStep, 1000, 0.01), 1001u);
  RecordedSensor fast = lidar;  // faster than the steps: one a step at most
  fast.spec.params.updateRate = 1e6;
  EXPECT_EQ(lidarScansInRun(fast, 1000, 0.01), 1001u);
  EXPECT_EQ(lidarScanBytes(lidar, PcdEncoding::Binary), 131072 * 12 + kPcdHeaderBytes);
  EXPECT_EQ(lidarScanBytes(lidar, PcdEncoding::Ascii), 131072 * kAsciiPcdPointBytes + kPcdHeaderBytes);
  // 51 scans of 1.5 MiB: nothing said.
  EXPECT_FALSE(lidarOutputWarning(l->doc, {lidar}, 1000, 0.01, PcdEncoding::Binary, -1));
  // 1001 scans: 1.47 GiB, a warning at lidarSamples with the figures.
  auto w = lidarOutputWarning(l->doc, {lidar}, 20000, 0.01, PcdEncoding::Binary, 1e9);
  ASSERT_TRUE(w);
  EXPECT_EQ(w->code, "RS7094");
  EXPECT_EQ(w->severity, Severity::Warning);
  EXPECT_EQ(w->line, 3u);
  EXPECT_NE(w->message.find("up to 1.47 GiB"), std::string::npos) << w->message;
  EXPECT_NE(w->message.find("131072 points a scan x 12 bytes (binary PCD)"), std::string::npos) << w->message;
  EXPECT_NE(w->message.find("x 1001 scans"), std::string::npos) << w->message;
  EXPECT_NE(w->message.find("has 954 MiB free"), std::string::npos) << w->message;  // past the free space: said
  // Two of them: the total, at the costlier.
  RecordedSensor small = lidar;
  small.directions.resize(16);
  auto two = lidarOutputWarning(l->doc, {small, lidar}, 20000, 0.01, PcdEncoding::Binary, -1);
  ASSERT_TRUE(two);
  EXPECT_NE(two->message.find("LiDAR '/World/Lidar' takes 131072"), std::string::npos) << two->message;
  EXPECT_NE(two->message.find("; the other LiDAR the rest"), std::string::npos) << two->message;
  EXPECT_EQ(two->message.find("free"), std::string::npos) << two->message;
}
