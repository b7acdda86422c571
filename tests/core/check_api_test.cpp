// The validator's API: locations and messages, did-you-mean, file checks
// through an in-memory file set, the real corpus, and bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <set>

#include "core/check.hpp"
#include "core/io.hpp"
#include "core/suggest.hpp"

namespace rscene {
namespace {

Diagnostics run(const std::string& text, CheckOptions o = {}) {
  Document doc;
  return validateText(text, o, doc);
}

TEST(Suggest, FindsCloseNamesOnly) {
  EXPECT_EQ(editDistance("objcet", "object"), 1u);
  EXPECT_EQ(editDistance("colour", "color"), 1u);
  EXPECT_EQ(closestName("colour", {"color", "colorMode", "castShadow"}), "color");
  EXPECT_EQ(closestName("objcet", {"object", "compound", "group"}), "object");
  EXPECT_EQ(closestName("Color", {"color"}), "color");
  EXPECT_EQ(closestName("banana", {"color", "object"}), "");
}

TEST(Check, UnknownKeyIsAWarningWithLocationAndSuggestion) {
  Diagnostics ds = run("raisim_engine_scene 2\nlight /World/l 0 0 -1 1 colour=1,1,1\n");
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS3002");
  EXPECT_EQ(ds[0].severity, Severity::Warning);
  EXPECT_EQ(ds[0].line, 2u);
  EXPECT_EQ(ds[0].column, 25u);
  EXPECT_EQ(ds[0].tag, "light");
  EXPECT_EQ(ds[0].field, "colour");
  EXPECT_EQ(ds[0].message, "unknown key 'colour' for light");
  EXPECT_EQ(ds[0].hint, "did you mean `color`?");
}

TEST(Check, UnknownTagSuggestsAKind) {
  Diagnostics ds = run("raisim_engine_scene 2\nobjcet /World/a\n");
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].hint, "did you mean `object`?");
}

TEST(Check, EnumNamesIgnoreCaseAndTakeAliases) {
  EXPECT_TRUE(run("raisim_engine_scene 2\nlight /World/l 0 0 -1 1 type=SUN\n").empty());
  Diagnostics ds = run("raisim_engine_scene 2\nlight /World/l 0 0 -1 1 type=spto\n");
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS2006");
  EXPECT_EQ(ds[0].hint, "did you mean `spot`?");
}

TEST(Check, LoadErrorsStopTheCheck) {
  Diagnostics ds = run("raisim_engine_scene 2\nasset_root a%zz\nobjcet x\n");
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS1003");
}

TEST(Check, HugeTerrainClaimsAreRefusedWithoutAllocating) {
  // 16384 x 16384 would be 2 GiB of heights; the check only multiplies.
  Diagnostics ds = run("raisim_engine_scene 2\nterrain_region /World/t 16384 16384 1 1 0 0 0 heights=1,2\n");
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS4002");
  ds = run("raisim_engine_scene 2\nterrain_region /World/t 99999999999 2 1 1 0 0 0\n");
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS2003");
}

TEST(CheckFiles, ResolvesAgainstSceneDirThenAssetRoot) {
  std::set<std::string> files{"/scenes/mesh.obj", "/scenes/assets/tex.png"};
  CheckOptions o;
  o.checkFiles = true;
  o.sceneDir = "/scenes";
  o.fileExists = [&](const std::string& p) { return files.count(p) > 0; };
  std::string scene =
      "raisim_engine_scene 2\nasset_root assets\n"
      "object /World/a mesh 0 0 0 1 0 0 0 1 1 1 1 1 1 default engine_default false true false mesh.obj static true 1 1\n"
      "terrain_texture 2 t T albedo=tex.png normal=missing.png\n";
  Diagnostics ds = run(scene, o);
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS5001");
  EXPECT_EQ(ds[0].line, 4u);
  EXPECT_EQ(ds[0].message, "file 'missing.png' does not exist (resolved to '/scenes/assets/missing.png')");
  o.checkFiles = false;
  EXPECT_TRUE(run(scene, o).empty());
}

TEST(CheckProfiles, RaisimAddsItsRefusals) {
  std::string scene = "raisim_engine_scene 2\npoint_cloud /World/p\n";
  EXPECT_TRUE(run(scene).empty());
  CheckOptions o;
  o.profile = Profile::RaiSim;
  Diagnostics ds = run(scene, o);
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS6001");
}

TEST(CheckTable, CodesAreUniqueAndSummariesFollowTheMessageRule) {
  std::set<std::string_view> seen;
  for (const CheckInfo& c : checkTable()) {
    EXPECT_TRUE(seen.insert(c.code).second) << c.code;
    ASSERT_FALSE(c.summary.empty());
    EXPECT_FALSE(c.summary.back() == '.') << c.code;
    EXPECT_FALSE(c.summary[0] >= 'A' && c.summary[0] <= 'Z') << c.code;
  }
}

// The real files: no errors under the default profile, and no warnings
// either (each would have to be justified in the validator's notes).
TEST(CheckCorpus, RealFilesHaveNoFindings) {
  std::filesystem::path dir = std::filesystem::path(RSCENE_SHARED_DIR) / "corpus";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "no corpus at " << dir;
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".rscene") continue;
    ++files;
    std::string text, err;
    ASSERT_TRUE(readFile(e.path().string(), text, &err)) << err;
    Diagnostics ds = run(text);
    for (const Diagnostic& d : ds) ADD_FAILURE() << e.path() << ":" << d.line << ": " << d.message << " [" << d.code << "]";
  }
  EXPECT_GT(files, 0);
}

// Mutated scenes never crash the validator (the fuzz target goes further).
TEST(CheckRobustness, MutatedScenesDoNotCrash) {
  const std::string base =
      "raisim_engine_scene 2\ngroup /World/g id=g\n"
      "object /World/a box 0 0 0 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - dynamic true 1 2 "
      "parentGroupId=g\nterrain_region /World/t 3 3 2 2 0 0 0 heights=1,2,3,4,5,6,7,8,9 vertexColors=1,0,0\n"
      "terrain_splat_layer /World/t slot=1 weights=1,2\ninstanced_visual /World/i box instances=0,0,0,1,0,0,0,1,1,1\n"
      "camera /World/c 0 0 0 1 0 0 0 60 0.1 100 640 480 rgb true\nwire /World/w stiff g /World/t 1\n";
  const std::string alphabet = " \n=,;%-0123456789.eE/abgxyz#\t";
  std::mt19937 rng(42);
  for (int i = 0; i < 3000; ++i) {
    std::string s = base;
    int edits = 1 + static_cast<int>(rng() % 6);
    for (int k = 0; k < edits; ++k) {
      std::size_t pos = rng() % s.size();
      switch (rng() % 3) {
        case 0: s[pos] = alphabet[rng() % alphabet.size()]; break;
        case 1: s.erase(pos, 1 + rng() % 8); break;
        default: s.insert(pos, 1, alphabet[rng() % alphabet.size()]); break;
      }
      if (s.empty()) s = "x";
    }
    for (Profile p : {Profile::Engine2, Profile::RaiSim}) {
      CheckOptions o;
      o.profile = p;
      o.checkFiles = true;
      o.fileExists = [](const std::string&) { return false; };
      Diagnostics ds = run(s, o);
      for (const Diagnostic& d : ds) ASSERT_NE(checkInfo(d.code), nullptr) << d.code;
    }
  }
}

}  // namespace
}  // namespace rscene
