// validateScene() streams: core's findings pass through a sink with the
// scene model's merged in, instead of being gathered and merged at the end.
// The answer must be the old one: a reference here merges the gathered
// findings the way validate.cpp did, and random scenes mixing core and
// model findings (some the same condition seen by both) are compared.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <tuple>

#include "core/loader.hpp"
#include "scene/check.hpp"
#include "scene/scene.hpp"
#include "scene/validate.hpp"

namespace rscene {
namespace {

// The merge as it was before the sink: `out` gathered whole, `extra` sorted
// by line and column and merged in, dropping one whose code `out` has on
// that line, and the model's own rules on a line its reader could not parse.
Diagnostics referenceValidate(const std::string& text, const CheckOptions& options) {
  LoadResult loaded = parse(text);
  if (!loaded.ok()) return loaded.diagnostics;
  Diagnostics out = loaded.diagnostics;
  Diagnostics found = check(loaded.document, options);
  hintContinuations(loaded.continuedLines, found);
  out.insert(out.end(), found.begin(), found.end());
  SceneOptions so;
  so.sceneDir = options.sceneDir;
  so.exists = options.fileExists;
  so.bodiesOnly = true;
  Scene scene;
  Diagnostics extra;
  buildScene(loaded.document, so, scene, extra);
  SceneCheckOptions sc;
  sc.checkFiles = options.checkFiles;
  sc.exists = options.fileExists;
  checkScene(loaded.document, scene, sc, extra);
  hintContinuations(loaded.continuedLines, extra);
  std::set<std::pair<std::uint32_t, std::string>> seen;
  for (const Diagnostic& d : out) seen.emplace(d.line, d.code);
  // A line whose value the model's reader could not parse is not judged
  // by the model again (issue 23: one typo, one error).
  std::set<std::uint32_t> unparsed;
  for (const Diagnostic& d : extra)
    if (d.severity == Severity::Error && d.code.rfind("RS2", 0) == 0) unparsed.insert(d.line);
  std::stable_sort(extra.begin(), extra.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::tie(a.line, a.column) < std::tie(b.line, b.column);
  });
  Diagnostics merged;
  std::size_t i = 0;
  for (const Diagnostic& d : extra) {
    if (seen.count({d.line, d.code})) continue;
    if (unparsed.count(d.line) && d.code.rfind("RS2", 0) != 0) continue;
    while (i < out.size() && (out[i].line < d.line || (out[i].line == d.line && out[i].column <= d.column)))
      merged.push_back(out[i++]);
    merged.push_back(d);
  }
  while (i < out.size()) merged.push_back(out[i++]);
  return merged;
}

std::string describe(const Diagnostics& ds) {
  std::string s;
  for (const Diagnostic& d : ds)
    s += d.code + " " + std::to_string(d.line) + ":" + std::to_string(d.column) + " " + d.message + " | " + d.hint +
         "\n";
  return s;
}

// Lines that give core findings, model findings or both.
const std::vector<std::string> kLines = {
    "time_step 0\n",
    "time_step -0.01\n",
    "time_step 1e-12\n",
    "time_step x\n",
    "time_step 0.001\n",
    "gravity 0 0 \\\n",
    "frob 1\n",
    "object /World/a box 0 0 1 1 0 0 0 1 1 1 0.5 1 0 default engine_default false true false - dynamic true 1 1\n",
    "object /World/b box 0 0 1 1 0 0 0 1 0 1 0.5 1 1 default engine_default false true false - dynamic true 1 1\n",
    "object /World/c mesh 0 0 1 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - dynamic true 1 1\n",
    "object /World/a box 0 0 1 1 0 0 0 1 1 1 0.5 1 1 nomat engine_default false true false - dynamic true 1 1 colour=1\n",
    "point_cloud /World/p points=0,0,0;1,1,1 colors=1,0,0\n",
    "group /World/g parent=/World/h\n",
    "group /World/h parent=/World/g\n",
    "wire /World/w stiff /World/a /World/zz 1\n",
};

struct Keep : DiagnosticSink {
  std::size_t limit = 0, count = 0;
  Diagnostics kept;
  void add(Diagnostic d) override {
    ++count;
    if (kept.size() < limit) kept.push_back(std::move(d));
  }
};

TEST(ValidateStream, GivesTheFindingsOfTheGatheringMergeOnRandomScenes) {
  std::mt19937 rng(4);
  std::size_t withModel = 0;
  for (int round = 0; round < 300; ++round) {
    std::string text = "raisim_engine_scene 2\n";
    for (int i = static_cast<int>(rng() % 12); i > 0; --i) text += kLines[rng() % kLines.size()];
    CheckOptions o;
    o.profile = round % 3 == 0 ? Profile::RaiSim : Profile::Engine2;
    o.checkFiles = round % 2 == 0;
    o.fileExists = [](const std::string&) { return false; };
    Diagnostics want = referenceValidate(text, o);
    Document doc;
    ASSERT_EQ(describe(validateScene(text, o, doc)), describe(want)) << text;
    for (const Diagnostic& d : want) withModel += d.code.rfind("RS7", 0) == 0 || d.code == "RS4008";
    // A sink that keeps the first N gets the first N, and sees them all.
    Keep keep;
    keep.limit = rng() % 4;
    validateScene(text, o, doc, keep);
    EXPECT_EQ(keep.count, want.size());
    ASSERT_EQ(describe(keep.kept), describe(Diagnostics(want.begin(), want.begin() + std::min(keep.limit, want.size()))));
  }
  EXPECT_GT(withModel, 100u);  // the scenes did exercise the merge
}

}  // namespace
}  // namespace rscene
