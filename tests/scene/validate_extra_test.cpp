// validateScene()'s ExtraSceneCheck: findings of a layer above lib/scene
// (the robot checks) merge with the others by the scene line they belong
// to; one inside another file is listed after its record's own findings and
// never taken for a repeat of a core finding.
#include <gtest/gtest.h>

#include "scene/scene.hpp"
#include "scene/validate.hpp"

using namespace rscene;

namespace {

const char* kScene =
    "raisim_engine_scene 1\n"
    "articulated_resource arm_res Arm arm.urdf\n"
    "articulated /World/Arm arm_res 0 0 0 1 0 0 0 true true id=arm bogusKey=1\n"
    "object /World/Box box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 2.5 default - false true false - dynamic true 1 "
    "18446744073709551615 id=box colr=1\n";

Diagnostic at(const char* code, std::uint32_t line, std::uint32_t column, std::string file = {}) {
  Diagnostic d;
  d.code = code;
  d.line = line;
  d.column = column;
  d.severity = Severity::Warning;
  d.file = std::move(file);
  return d;
}

TEST(ValidateExtra, FindingsMergeByTheirSceneLine) {
  CollectDiagnostics all;
  Document doc;
  bool sawScene = false;
  validateScene(kScene, CheckOptions{}, doc, all,
                [&](const Document& d, const Scene& s, std::vector<SceneFinding>& out) {
                  sawScene = &d == &doc && s.articulated.size() == 1;
                  // Line 9 of the URDF, listed with the scene's line 2; it has
                  // the code and line of a core finding (RS3002 on line 9 of
                  // nothing) and must not be dropped as a repeat.
                  out.push_back({2, at("RS3002", 3, 5, "arm.urdf")});
                  out.push_back({3, at("RS7040", 3, 1)});
                });
  EXPECT_TRUE(sawScene);
  std::vector<std::string> order;
  for (const Diagnostic& d : all.all) order.push_back(d.code + "@" + std::to_string(d.line) + (d.file.empty() ? "" : ":" + d.file));
  // Core's unknown keys are RS3002 on lines 3 and 4.
  std::vector<std::string> want{"RS3002@3:arm.urdf", "RS7040@3", "RS3002@3", "RS3002@4"};
  EXPECT_EQ(order, want);
}

TEST(ValidateExtra, AFindingThatRepeatsACoreOneIsDropped) {
  CollectDiagnostics all;
  Document doc;
  validateScene(kScene, CheckOptions{}, doc, all,
                [&](const Document&, const Scene&, std::vector<SceneFinding>& out) {
                  out.push_back({3, at("RS3002", 3, 70)});
                });
  std::size_t rs3002 = 0;
  for (const Diagnostic& d : all.all) rs3002 += d.code == "RS3002";
  EXPECT_EQ(rs3002, 2u);
}

}  // namespace
