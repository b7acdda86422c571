// A deformable record through World: read from scene text, its mesh from
// an in-memory disk, stepped before Bullet against the scene's bodies.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "asset/cache.hpp"
#include "core/loader.hpp"
#include "scene/scene.hpp"
#include "sim/deformable_test_util.hpp"
#include "sim/limits.hpp"
#include "sim/world.hpp"
#include "sim/world_test_scene.hpp"

using namespace rscene;
using namespace rscene::sim;

namespace {

using test::kGround;

std::unique_ptr<test::WorldRun> make(const std::string& body, asset::AssetCache& assets) {
  test::WorldRunOptions options;
  options.assets = &assets;
  options.baseDir = "/s";
  return test::buildWorld("time_step 0.005\n" + body, options);
}

// The Bullet queries were an interim placeholder (no contacts) until the
// surfaces work landed: the contact assertion waits for them.
bool surfacesArePlaceholders() {
  std::ifstream in(RSCENE_SOURCE_DIR "/lib/sim/bullet_surfaces.cpp");
  std::stringstream text;
  text << in.rdbuf();
  return text.str().find("INTERIM") != std::string::npos;
}

}  // namespace

TEST(DeformableWorld, AClothFallsAndRestsOnTheGround) {
  MemoryFileSystem fs;
  fs.addFile("/s/cloth.obj", test::gridObj(9, 1));
  asset::AssetCache cache(fs);
  auto r = make(kGround +
                    "deformable /World/Cloth cloth cloth.obj 0 0 0.5 1 0 0 0 1 1 1 totalMass=0.2 "
                    "bendCompliance=1000 damping=0.05 collisionRadius=0.01\n",
                cache);
  ASSERT_TRUE(r->world) << (r->diags.empty() ? "" : r->diags[0].message);
  ASSERT_EQ(r->world->particleStates().size(), 1u);
  EXPECT_EQ(r->world->particleStates()[0].points->size(), 81u);
  EXPECT_EQ(r->world->particleStates()[0].path, "/World/Cloth");
  for (int i = 0; i < 400; ++i) r->world->step();  // 2 s: 0.5 m of fall takes 0.32 s
  const std::vector<Eigen::Vector3d>& p = *r->world->particleStates()[0].points;
  EXPECT_TRUE(std::all_of(p.begin(), p.end(), [](const auto& x) { return x.allFinite(); }));
  if (surfacesArePlaceholders()) GTEST_SKIP() << "BulletSurfaces is still the interim placeholder (no contacts)";
  // Flat on the ground at its collision radius: within 2 mm, the contact
  // slop of a resting particle (its gravity step is undone by the contact
  // within the substep) plus what 20 iterations leave.
  for (const auto& x : p) EXPECT_NEAR(x.z(), 0.01, 2e-3);
  EXPECT_TRUE(r->world->atRest());
}

TEST(DeformableWorld, ARefusedRecordIsAnErrorAtItsKey) {
  MemoryFileSystem fs;
  fs.addFile("/s/cloth.obj", test::gridObj(3, 1));
  asset::AssetCache cache(fs);
  auto r = make(kGround + "deformable /World/Cloth cloth cloth.obj 0 0 0.5 1 0 0 0 1 1 1 pinnedVertices=0,9\n",
                cache);
  EXPECT_FALSE(r->world);
  ASSERT_FALSE(r->diags.empty());
  const Diagnostic& d = r->diags.back();
  EXPECT_EQ(d.code, "RS7081");
  EXPECT_EQ(d.line, 4u);
  EXPECT_GT(d.column, 0u);
  EXPECT_NE(d.message.find("pinnedVertices 9 is not a vertex of /s/cloth.obj (it has 9)"), std::string::npos)
      << d.message;
}

// Issue 24, case 7: a deformable starting inside the ground or a body is
// refused as grains starting in overlap are (RS7077), at its position.
TEST(DeformableWorld, AClothStartingBelowTheGroundIsRefusedAtItsPosition) {
  MemoryFileSystem fs;
  fs.addFile("/s/cloth.obj", test::gridObj(5, 1));
  asset::AssetCache cache(fs);
  auto r = make(kGround + "deformable /World/Cloth cloth cloth.obj 0 0 -0.2 1 0 0 0 1 1 1 collisionRadius=0.01\n", cache);
  EXPECT_FALSE(r->world);
  ASSERT_FALSE(r->diags.empty());
  const Diagnostic& d = r->diags.back();
  EXPECT_EQ(d.code, "RS7077");
  EXPECT_EQ(d.line, 4u);
  EXPECT_NE(d.message.find("starts 0.2 m inside the ground or another body"), std::string::npos) << d.message;
  // Resting on the ground (its centres at the radius) is no overlap.
  auto ok = make(kGround + "deformable /World/Cloth cloth cloth.obj 0 0 0.01 1 0 0 0 1 1 1 collisionRadius=0.01\n", cache);
  EXPECT_TRUE(ok->world) << test::firstMessage(ok->diags);
}

// Hostile input round two, trial: a cloth whose particle spheres start up
// to half their radius inside the ground (allowed by RS7077) failed at its
// first step as diverged (RS7024): the first substep pushed them out at
// up to 5 m/s.  They are moved out before the first step, with a warning
// (RS7016) at the record's position, and the cloth rests.
TEST(DeformableWorld, AClothStartingSlightlyInTheGroundIsMovedOutAndRests) {
  MemoryFileSystem fs;
  fs.addFile("/s/cloth.obj", test::gridObj(9, 1));
  asset::AssetCache cache(fs);
  // Spheres 4.5 mm and 0.5 mm into the ground (radius 1 cm); laid on it
  // (centres on the surface); centres 4 mm inside.  A fresh-user trial
  // found a cloth laid on the ground refused.
  for (const char* z : {"0.0055", "0.0095", "0", "-0.004"}) {
    SCOPED_TRACE(z);
    auto r = make(kGround + "deformable /World/Cloth cloth cloth.obj 0 0 " + z +
                      " 1 0 0 0 1 1 1 totalMass=0.3 collisionRadius=0.01 iterations=8\n",
                  cache);
    ASSERT_TRUE(r->world) << test::firstMessage(r->diags);
    ASSERT_EQ(r->diags.size(), 1u) << test::firstMessage(r->diags);
    const Diagnostic& d = r->diags[0];
    EXPECT_EQ(d.code, "RS7016");
    EXPECT_EQ(d.severity, Severity::Warning);
    EXPECT_EQ(d.line, 4u);
    EXPECT_GT(d.column, 0u);
    EXPECT_NE(d.message.find("deformable '/World/Cloth': 81 particles start inside the ground or another body, up to "),
              std::string::npos)
        << d.message;
    // Where the first step starts: every sphere on the ground, none in it.
    for (const Eigen::Vector3d& x : *r->world->particleStates()[0].points) EXPECT_GE(x.z(), 0.01);
    for (int i = 0; i < 500; ++i) {
      r->world->step();
      ASSERT_FALSE(r->world->nonFinite()) << "step " << i + 1 << ": " << r->world->nonFinite()->cause;
    }
    EXPECT_TRUE(r->world->atRest());
    for (const Eigen::Vector3d& x : *r->world->particleStates()[0].points) EXPECT_NEAR(x.z(), 0.01, 2e-3);
  }
  // Resting on it, or clear of it: no warning.
  auto clear = make(kGround + "deformable /World/Cloth cloth cloth.obj 0 0 0.0100001 1 0 0 0 1 1 1 collisionRadius=0.01\n", cache);
  ASSERT_TRUE(clear->world);
  EXPECT_TRUE(clear->diags.empty()) << test::firstMessage(clear->diags);
}

TEST(DeformableWorld, AClothStartingInsideABoxIsRefused) {
  MemoryFileSystem fs;
  fs.addFile("/s/cloth.obj", test::gridObj(9, 1));
  asset::AssetCache cache(fs);
  auto r = make(kGround +
                    "object /World/Box box 0.2 0.1 0.3 1 0 0 0 0.4 0.4 0.4 0 0 1 default - false true false - dynamic "
                    "true 1 18446744073709551615\n"
                    "deformable /World/Cloth cloth cloth.obj 0 0 0.2 1 0 0 0 1 1 1 collisionRadius=0.01\n",
                cache);
  EXPECT_FALSE(r->world);
  ASSERT_FALSE(r->diags.empty());
  EXPECT_EQ(r->diags.back().code, "RS7077");
  EXPECT_EQ(r->diags.back().line, 5u);
}

// A deformable far heavier than a dynamic body it may touch (RS7078):
// 100 kg of cloth landing on a 1 kg box threw it 1.4 km.
TEST(DeformableWorld, AClothFarHeavierThanABodyIsRefusedAtTotalMass) {
  MemoryFileSystem fs;
  fs.addFile("/s/cloth.obj", test::gridObj(9, 1));
  asset::AssetCache cache(fs);
  const std::string box =
      "object /World/Box box 0.2 0.1 0.3 1 0 0 0 0.4 0.4 0.4 0 0 1 default - false true false - dynamic "
      "true 1 18446744073709551615\n";
  auto r = make(kGround + box + "deformable /World/Cloth cloth cloth.obj 0 0 0.6 1 0 0 0 1 1 1 totalMass=100\n", cache);
  EXPECT_FALSE(r->world);
  ASSERT_FALSE(r->diags.empty());
  EXPECT_EQ(r->diags.back().code, "RS7078");
  EXPECT_NE(r->diags.back().message.find("dynamic body '/World/Box' (1 kg)"), std::string::npos)
      << r->diags.back().message;
  auto ok = make(kGround + box + "deformable /World/Cloth cloth cloth.obj 0 0 0.6 1 0 0 0 1 1 1 totalMass=10\n", cache);
  EXPECT_TRUE(ok->world) << test::firstMessage(ok->diags);
}

// RS7078 asks only about bodies the cloth can meet: a box whose collision
// mask leaves out the cloth's group 1 is no reason to refuse it.
TEST(DeformableWorld, AHeavyClothIsNotRefusedForABodyItsGroupsNeverMeet) {
  MemoryFileSystem fs;
  fs.addFile("/s/cloth.obj", test::gridObj(9, 1));
  asset::AssetCache cache(fs);
  const std::string apart =
      "object /World/Box box 3 0 0.3 1 0 0 0 0.4 0.4 0.4 0 0 1 default - false true false - dynamic "
      "true 2 2\n";
  auto r = make(kGround + apart + "deformable /World/Cloth cloth cloth.obj 0 0 0.6 1 0 0 0 1 1 1 totalMass=100\n",
                cache);
  EXPECT_TRUE(r->world) << test::firstMessage(r->diags);
}

// The per-run cap on the deformables' work (RS7075), with the warning
// below it (RS7076), at the record's iterations.
TEST(DeformableWorld, TheRunsSolverWorkIsCappedUpFrontWithItsCost) {
  MemoryFileSystem fs;
  fs.addFile("/s/cloth.obj", test::gridObj(9, 1));
  asset::AssetCache cache(fs);
  auto r = make(kGround + "deformable /World/Cloth cloth cloth.obj 0 0 0.5 1 0 0 0 1 1 1 iterations=1000 substeps=10\n",
                cache);
  ASSERT_TRUE(r->world) << test::firstMessage(r->diags);
  const double perStep = r->world->particleSystems().deformableCosts().at(0).workPerStep;
  // (constraints + particles) x 1000 x 10: 81 particles, 208 edges, 176 bends.
  EXPECT_EQ(perStep, (81.0 + 208 + 176) * 1e4);
  Diagnostics ds;
  EXPECT_TRUE(checkDeformableWork(r->doc, *r->world, 100, ds));  // 4.65e8, under 5e8: nothing said
  EXPECT_TRUE(ds.empty());
  EXPECT_TRUE(checkDeformableWork(r->doc, *r->world, 1000, ds));  // 4.65e9: the cost, a warning
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS7076");
  EXPECT_EQ(ds[0].severity, Severity::Warning);
  ds.clear();
  EXPECT_FALSE(checkDeformableWork(r->doc, *r->world, 10000, ds));  // 4.65e10: refused
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS7075");
  EXPECT_EQ(ds[0].line, 4u);
  EXPECT_NE(ds[0].message.find("= 4.65e+10 updates"), std::string::npos) << ds[0].message;
  EXPECT_NE(ds[0].message.find("about 16 min of one core"), std::string::npos) << ds[0].message;
  // Like with like: the run's figure against the per-run limit.
  EXPECT_NE(ds[0].message.find("the run's 4.65e+10 updates are more than the limit of 3e+10 updates a run"),
            std::string::npos)
      << ds[0].message;
}

// A scene written back with deformables says once that they keep their
// start pose (RS7079), naming each.
TEST(DeformableWorld, WritingBackDeformablesIsOneWarningNamingThem) {
  MemoryFileSystem fs;
  fs.addFile("/s/cloth.obj", test::gridObj(3, 1));
  asset::AssetCache cache(fs);
  auto r = make(kGround + "deformable /World/A cloth cloth.obj 0 0 0.5 1 0 0 0 1 1 1\n" +
                    "deformable /World/B cloth cloth.obj 0 0 1.5 1 0 0 0 1 1 1\n",
                cache);
  ASSERT_TRUE(r->world);
  std::optional<Diagnostic> w = deformablesAtStartPose(r->doc, r->scene);
  ASSERT_TRUE(w);
  EXPECT_EQ(w->code, "RS7079");
  EXPECT_EQ(w->severity, Severity::Warning);
  EXPECT_EQ(w->line, 4u);
  EXPECT_NE(w->message.find("deformables '/World/A', '/World/B' are written back at the start pose"),
            std::string::npos)
      << w->message;
  auto none = make(kGround, cache);
  EXPECT_FALSE(deformablesAtStartPose(none->doc, none->scene));
}
