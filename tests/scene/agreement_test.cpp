// Validate, sim and render read one scene model, so they agree: over every
// fixture, example and corpus scene (missing assets allowed: they only have
// to be refused the same way), a scene rscene-validate --check-files finds
// no error in is accepted by the simulator and by the renderer's scene
// build, and every error those two report is one validate reports, with the
// same code on the same line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "core/io.hpp"
#include "core/loader.hpp"
#include "render/render_scene.hpp"
#include "scene/check.hpp"
#include "scene/validate.hpp"
#include "sim/world.hpp"

namespace rscene {
namespace {

namespace fs = std::filesystem;

struct Verdicts {
  Diagnostics validate, sim, render;
  bool simOk = false, renderOk = false;
};

// What each tool says about `text`, as its driver runs it.
Verdicts judge(const std::string& text, const std::string& sceneDir) {
  Verdicts v;
  CheckOptions co;
  co.checkFiles = true;
  co.sceneDir = sceneDir;
  Document doc;
  v.validate = validateScene(text, co, doc);
  LoadResult loaded = parse(text);
  if (!loaded.ok()) return v;  // no tool gets further; validate reports the loader's errors
  SceneOptions so;
  so.sceneDir = sceneDir;
  Scene scene;
  v.simOk = buildScene(loaded.document, so, scene, v.sim) && sim::checkPhysics(loaded.document, scene, v.sim) &&
            sim::World::create(scene, v.sim) != nullptr;
  render::RenderScene rs;
  v.renderOk = render::buildRenderScene(loaded.document, so, rs, v.render);
  return v;
}

bool hasError(const Diagnostics& ds) {
  return std::any_of(ds.begin(), ds.end(), [](const Diagnostic& d) { return d.severity == Severity::Error; });
}

std::string describe(const Diagnostics& ds) {
  std::string s;
  for (const Diagnostic& d : ds) s += "  " + d.code + " line " + std::to_string(d.line) + ": " + d.message + "\n";
  return s;
}

void expectAgreement(const std::string& name, const Verdicts& v) {
  SCOPED_TRACE(name);
  if (!hasError(v.validate)) {
    EXPECT_TRUE(v.simOk) << "validate is clean, sim refuses:\n" << describe(v.sim);
    EXPECT_TRUE(v.renderOk) << "validate is clean, render refuses:\n" << describe(v.render);
  }
  for (const Diagnostics* tool : {&v.sim, &v.render})
    for (const Diagnostic& d : *tool) {
      if (d.severity != Severity::Error) continue;
      bool found = std::any_of(v.validate.begin(), v.validate.end(), [&](const Diagnostic& w) {
        return w.code == d.code && w.line == d.line && w.severity == Severity::Error;
      });
      EXPECT_TRUE(found) << (tool == &v.sim ? "sim" : "render") << " reports " << d.code << " on line " << d.line
                         << " (" << d.message << "); validate says:\n"
                         << describe(v.validate);
    }
}

std::vector<fs::path> scenesUnder(const fs::path& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().extension() == ".rscene") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// Checks every file; returns how many all three tools accept, so a test
// can tell that it compared real verdicts, not only refusals.
int checkAll(const std::vector<fs::path>& files) {
  int accepted = 0;
  for (const fs::path& f : files) {
    std::string text, error;
    EXPECT_TRUE(readFile(f.string(), text, &error)) << error;
    Verdicts v = judge(text, f.parent_path().string());
    expectAgreement(f.string(), v);
    accepted += !hasError(v.validate) && v.simOk && v.renderOk;
  }
  return accepted;
}

TEST(Agreement, FixturesAndExamples) {
  std::vector<fs::path> files = scenesUnder(fs::path(RSCENE_SOURCE_DIR) / "tests/data");
  std::vector<fs::path> examples = scenesUnder(fs::path(RSCENE_SOURCE_DIR) / "examples");
  files.insert(files.end(), examples.begin(), examples.end());
  ASSERT_GT(files.size(), 20u);
  EXPECT_GE(checkAll(files), 8);
}

TEST(Agreement, Corpus) {
  std::vector<fs::path> files = scenesUnder(fs::path(RSCENE_SHARED_DIR) / "corpus");
  if (files.empty()) GTEST_SKIP() << "../shared/corpus is absent";
  checkAll(files);
  // The corpus ships without its meshes and images: those (RS5001) are the
  // only reason any tool refuses a real file.
  for (const fs::path& f : files) {
    std::string text, error;
    EXPECT_TRUE(readFile(f.string(), text, &error)) << error;
    for (const Diagnostic& d : judge(text, f.parent_path().string()).validate)
      EXPECT_TRUE(d.severity != Severity::Error || d.code == "RS5001") << f << ": " << d.code << " " << d.message;
  }
}

// The disagreements of issue 9, each now one verdict in all three tools.
TEST(Agreement, IssueCases) {
  const std::string H = "raisim_engine_scene 2\n";
  auto object = [](const std::string& prim, const std::string& scale, const std::string& mass) {
    return "object /World/a " + prim + " 0 0 1 1 0 0 0 " + scale + " 0.5 1 " + mass +
           " default engine_default false true false - dynamic true 1 18446744073709551615\n";
  };
  const std::string k = "compound /World/k 0 0 1 1 0 0 0 1 1 1 2 dynamic true true\n";
  struct Case {
    std::string text;
    const char* code;  // nullptr: every tool accepts
  };
  const Case cases[] = {
      {H + object("half_space", "1 1 1", "0"), nullptr},
      {H + object("box", "-1 1 1", "1"), "RS7003"},
      {H + object("box", "1 0 1", "1"), "RS7003"},
      {H + "time_step 0\n" + object("box", "1 1 1", "1"), "RS7008"},
      {H + k + "compound_child /World/k sphere 0 0 0 1 0 0 0 1 1 1\n", "RS7003"},
      {H + object("box", "1 1 1", "0"), "RS4008"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    Verdicts v = judge(c.text, ".");
    expectAgreement("case", v);
    EXPECT_EQ(v.simOk, c.code == nullptr) << describe(v.sim);
    EXPECT_EQ(v.renderOk, c.code == nullptr) << describe(v.render);
    EXPECT_EQ(hasError(v.validate), c.code != nullptr) << describe(v.validate);
    if (!c.code) continue;
    for (const Diagnostics* ds : {&v.validate, &v.sim, &v.render}) {
      EXPECT_TRUE(std::any_of(ds->begin(), ds->end(), [&](const Diagnostic& d) { return d.code == c.code; }))
          << describe(*ds);
    }
  }
}

// A wire to an articulated system is simulated (at its body localIndexA):
// no tool warns that it is skipped.
TEST(Agreement, RobotCellWireToTheRobotIsNotSkipped) {
  fs::path f = fs::path(RSCENE_SOURCE_DIR) / "examples/robot_cell.rscene";
  std::string text, error;
  ASSERT_TRUE(readFile(f.string(), text, &error)) << error;
  Verdicts v = judge(text, f.parent_path().string());
  auto warned = [](const Diagnostics& ds) {
    return std::any_of(ds.begin(), ds.end(), [](const Diagnostic& d) { return d.code == "RS7011"; });
  };
  EXPECT_FALSE(warned(v.sim)) << describe(v.sim);
  EXPECT_FALSE(warned(v.validate)) << describe(v.validate);
}

}  // namespace
}  // namespace rscene
