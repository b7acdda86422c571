// An object's custom inertia (customInertia=true inertiaDiagonal=xx,yy,zz,
// what rscene-from-xml writes for RaiSim's <inertia>) against closed form:
// a spring pulling sideways at a lever arm turns a box at torque / Izz.
#include <gtest/gtest.h>

#include <string>

#include "scene/limits.hpp"
#include "sim/world_test_scene.hpp"

using namespace rscene;
using namespace rscene::sim;
using namespace rscene::sim::test;

namespace {

constexpr double kDt = 0.001;

// A 1 kg unit box at the origin, no gravity, and a compliant wire of rest
// length 1 from the box's point (0, 0.5, 0) to a static anchor at
// (2, 0.5, 0): stretched by 1 m, it pulls with k = 10 N along +x, so the
// torque about z is r x F = -0.5 * 10 = -5 N m.  Group 2 / mask 0 keep the
// anchor out of contact.  `inertia` is the box's extra keys.
std::string springScene(const std::string& inertia) {
  return "time_step 0.001\ngravity 0 0 0\n"
         "object /World/Anchor sphere 2 0.5 0 1 0 0 0 1 1 1 0.05 0 1 default engine_default false true false - "
         "static true 2 0\n"
         "object /World/Box box 0 0 0 1 0 0 0 1 1 1 0 0 1 default engine_default false true false - dynamic true 2 0" +
         (inertia.empty() ? "" : " " + inertia) +
         "\n"
         "wire /World/W compliant /World/Box /World/Anchor 1 localPositionA=0,0.5,0 stiffness=10\n";
}

double spinAfterOneStep(const std::string& inertia) {
  WorldRunOptions options;
  options.checkPhysics = true;
  auto run = buildWorld(springScene(inertia), options);
  EXPECT_TRUE(run->world) << firstMessage(run->diags);
  if (!run->world) return 0;
  run->world->step();
  for (const BodyState& s : run->world->states())
    if (s.path == "/World/Box") return s.angularVelocity.z();
  ADD_FAILURE() << "no /World/Box";
  return 0;
}

}  // namespace

TEST(CustomInertia, AngularAccelerationIsTorqueOverIzz) {
  // Semi-implicit Euler: after one step w = tau * dt / Izz exactly (the
  // orientation is the identity, so the world inverse inertia is 1/Izz).
  const double tau = -5;
  EXPECT_NEAR(spinAfterOneStep("customInertia=true inertiaDiagonal=0.4,0.4,2"), tau * kDt / 2, 1e-12);
  EXPECT_NEAR(spinAfterOneStep("customInertia=true inertiaDiagonal=1,1,0.25"), tau * kDt / 0.25, 1e-12);
}

TEST(CustomInertia, WithoutTheFlagTheShapesInertiaIsUsed) {
  // A 1 kg unit cube: Izz = m (x^2 + y^2) / 12 = 1/6.  The diagonal alone,
  // or customInertia=true without a diagonal, changes nothing.
  const double expected = -5 * kDt / (1.0 / 6);
  EXPECT_NEAR(spinAfterOneStep(""), expected, 1e-9);
  EXPECT_NEAR(spinAfterOneStep("inertiaDiagonal=0.4,0.4,2"), expected, 1e-9);
  EXPECT_NEAR(spinAfterOneStep("customInertia=true"), expected, 1e-9);
  EXPECT_NEAR(spinAfterOneStep("customInertia=false inertiaDiagonal=0.4,0.4,2"), expected, 1e-9);
}

TEST(CustomInertia, NonPositiveOrHugeMomentsAreRefusedAtTheKey) {
  // (nan and inf are refused earlier, by the vec3 type itself.)
  for (const char* diagonal : {"0,1,1", "1,-1,1", "1,1,1e16", "1e-320,1,1"}) {
    SCOPED_TRACE(diagonal);
    LoadResult loaded = parse("raisim_engine_scene 1\n" + springScene(std::string("customInertia=true inertiaDiagonal=") + diagonal));
    ASSERT_TRUE(loaded.ok());
    Scene scene;
    Diagnostics diags;
    ASSERT_TRUE(buildScene(loaded.document, {}, scene, diags));
    EXPECT_FALSE(checkNumericLimits(loaded.document, scene, diags));
    bool found = false;
    for (const Diagnostic& d : diags)
      if (d.code == "RS7090") {
        found = true;
        EXPECT_EQ(d.line, 5);  // the box's record
        EXPECT_NE(d.message.find("'/World/Box'"), std::string::npos) << d.message;
      }
    EXPECT_TRUE(found) << firstMessage(diags);
  }
}

TEST(CustomInertia, OnlyADynamicBodysInertiaIsChecked) {
  // A static body never turns: its diagonal is not used, so not refused.
  std::string text = springScene("customInertia=true inertiaDiagonal=0,0,0");
  text.replace(text.find("dynamic"), 7, "static");
  LoadResult loaded = parse("raisim_engine_scene 1\n" + text);
  ASSERT_TRUE(loaded.ok());
  Scene scene;
  Diagnostics diags;
  ASSERT_TRUE(buildScene(loaded.document, {}, scene, diags));
  EXPECT_TRUE(checkNumericLimits(loaded.document, scene, diags)) << firstMessage(diags);
}

TEST(CustomInertia, ACompoundsDiagonalIsCheckedToo) {
  LoadResult loaded = parse(
      "raisim_engine_scene 1\n"
      "compound /World/C 0 0 1 1 0 0 0 1 1 1 1 dynamic true true inertiaDiagonal=1,0,1\n"
      "compound_child /World/C box 0 0 0 1 0 0 0 1 1 1 size=1,1,1\n");
  ASSERT_TRUE(loaded.ok());
  Scene scene;
  Diagnostics diags;
  ASSERT_TRUE(buildScene(loaded.document, {}, scene, diags));
  EXPECT_FALSE(checkNumericLimits(loaded.document, scene, diags));
  ASSERT_FALSE(diags.empty());
  EXPECT_EQ(diags.back().code, "RS7090");
}
