// Semantic diff: identity matching, typed comparison, tolerances, list
// summaries, ignore options and the JSON result.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/diff.hpp"
#include "core/diff_identity.hpp"
#include "core/text.hpp"
#include "test_util.hpp"

using namespace rscene;

namespace {

const char* kBase =
    "raisim_engine_scene 1\n"
    "solver 80 1e-07 0.2 accurate\n"
    "editor_ux multiSelect=true\n"
    "material mat_a 0.5 0.5 0.5 1 0 0.5 0 0 0 0 false - - - - - - id=mat_a\n"
    "contact_material mat_a mat_b 0.8 0 0 0.8 0 0 0\n"
    "terrain_texture 0 grass Grass color=0.2,0.4,0.2\n"
    "group /World id=folder_world parentId=- locked=false\n"
    "terrain_region /World/T 3 3 2 2 0 0 0 id=terrain_t heights=0,0,0,0,0,0,0,0,0\n"
    "terrain_splat_layer /World/T slot=1 strength=1\n"
    "object /World/Box box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 2.5 default mat_a false true false - dynamic true 1 "
    "18446744073709551615 id=box parentGroupId=folder_world\n";

DiffResult run(const std::string& a, const std::string& b, const DiffOptions& opt = {}) {
  LoadResult la = parse(a), lb = parse(b);
  EXPECT_TRUE(la.ok() && lb.ok());
  return diff(la.document, lb.document, opt);
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

}  // namespace

TEST(Diff, SameSceneInAnotherOrderAndSpellingIsNoChange) {
  // The same records in another order, numbers and flags spelt differently,
  // the contact pair written the other way round.
  std::string reordered =
      "raisim_engine_scene 1\n"
      "object /World/Box box 0 0 0.50 1 0 0 0 1 1 1 0.5 1 2.5 default mat_a no yes no - dynamic true 1 "
      "18446744073709551615 parentGroupId=folder_world id=box\n"
      "terrain_region /World/T 3 3 2 2 0 0 0 id=terrain_t heights=0,0,0,0,0,0,0,0,0\n"
      "terrain_splat_layer /World/T slot=01 strength=1.0\n"
      "group /World id=folder_world parentId=- locked=no\n"
      "terrain_texture 0 grass Grass color=0.2,0.4,0.2\n"
      "contact_material mat_b mat_a 0.8 0 0 0.8 0 0 0\n"
      "material mat_a 0.5 0.5 0.5 1 0 0.5 0 0 0 0 false - - - - - - id=mat_a\n"
      "editor_ux multiSelect=yes\n"
      "solver 80 1e-7 0.2 accurate\n";
  EXPECT_TRUE(run(kBase, reordered).same());
}

TEST(Diff, ChangedFieldsAreNamedWithOldAndNewValues) {
  std::string b = replace(kBase, "2.5 default", "3 default");
  b = replace(b, "0 0 0.5 1 0 0 0 1 1 1", "0 0 0.75 1 0 0 0 1 1 1");
  DiffResult d = run(kBase, b);
  ASSERT_EQ(d.records.size(), 1u);
  const RecordDiff& r = d.records[0];
  EXPECT_EQ(r.change, Change::Changed);
  EXPECT_EQ(r.tag, "object");
  EXPECT_EQ(r.path, "/World/Box");
  EXPECT_EQ(r.key, "box");
  ASSERT_EQ(r.fields.size(), 2u);
  EXPECT_EQ(r.fields[0].name, "position");
  EXPECT_EQ(r.fields[0].oldValue, "0,0,0.5");  // vectors whole
  EXPECT_EQ(r.fields[0].newValue, "0,0,0.75");
  EXPECT_EQ(r.fields[1].name, "mass");
  EXPECT_EQ(r.fields[1].oldValue, "2.5");
  EXPECT_EQ(r.fields[1].newValue, "3");
}

TEST(Diff, NodeThatKeepsItsIdIsRenamedOrMoved) {
  DiffResult d = run(kBase, replace(kBase, "object /World/Box", "object /World/Props/Crate"));
  ASSERT_EQ(d.records.size(), 1u);
  EXPECT_EQ(d.records[0].change, Change::Changed);
  EXPECT_EQ(d.records[0].oldPath, "/World/Box");
  EXPECT_EQ(d.records[0].path, "/World/Props/Crate");
  EXPECT_TRUE(d.records[0].fields.empty());
}

TEST(Diff, AddedAndRemovedRecords) {
  std::string b = replace(kBase, "terrain_texture 0 grass Grass color=0.2,0.4,0.2\n", "");
  b += "light /World/Sun 0 0 -1 3 id=sun\n";
  DiffResult d = run(kBase, b);
  ASSERT_EQ(d.records.size(), 2u);
  EXPECT_EQ(d.count(Change::Added), 1u);
  EXPECT_EQ(d.count(Change::Removed), 1u);
  for (const RecordDiff& r : d.records) {
    if (r.change == Change::Added) {
      EXPECT_EQ(r.path, "/World/Sun");
    }
    if (r.change == Change::Removed) {
      EXPECT_EQ(r.key, "0");  // terrain textures by slot
    }
  }
}

TEST(Diff, ChildrenMatchThroughTheirParent) {
  DiffResult d = run(kBase, replace(kBase, "slot=1 strength=1", "slot=1 strength=0.5"));
  ASSERT_EQ(d.records.size(), 1u);
  EXPECT_EQ(d.records[0].tag, "terrain_splat_layer");
  EXPECT_EQ(d.records[0].fields.at(0).name, "strength");
}

TEST(Diff, LongListsAreSummarised) {
  DiffResult d = run(kBase, replace(kBase, "heights=0,0,0,0,0,0,0,0,0", "heights=0,0.03,0,0,0.01,0,0,0,0"),
                     DiffOptions{0, 0, false, {}, 4});
  ASSERT_EQ(d.records.size(), 1u);
  const FieldDiff& f = d.records[0].fields.at(0);
  EXPECT_EQ(f.name, "heights");
  EXPECT_TRUE(f.summarized);
  EXPECT_EQ(f.newCount, 9u);
  EXPECT_EQ(f.changedCount, 2u);
  EXPECT_DOUBLE_EQ(f.maxDelta, 0.03);
}

TEST(Diff, TolerancesHideFloatNoise) {
  std::string b = replace(kBase, "2.5 default", "2.5000001 default");
  EXPECT_FALSE(run(kBase, b).same());
  DiffOptions abs;
  abs.tolerance = 1e-6;
  EXPECT_TRUE(run(kBase, b, abs).same());
  DiffOptions rel;
  rel.relTolerance = 1e-6;
  EXPECT_TRUE(run(kBase, b, rel).same());
}

TEST(Diff, DefaultsAndIgnoredFields) {
  // Writing a key with its default value is no change.
  EXPECT_TRUE(run(kBase, replace(kBase, "accurate\n", "accurate erp2=0\n")).same());
  DiffResult d = run(kBase, replace(kBase, "accurate\n", "accurate erp2=0.5\n"));
  ASSERT_EQ(d.records.size(), 1u);
  EXPECT_EQ(d.records[0].fields.at(0).oldValue, "0 (default)");

  std::string b = replace(kBase, "multiSelect=true", "multiSelect=false");
  b = replace(b, "locked=false", "locked=true");
  EXPECT_EQ(run(kBase, b).records.size(), 2u);
  DiffOptions editor;
  editor.ignoreEditorState = true;
  EXPECT_TRUE(run(kBase, b, editor).same());

  DiffOptions ignore;
  ignore.ignore = {"object.mass"};
  EXPECT_TRUE(run(kBase, replace(kBase, "2.5 default", "9 default"), ignore).same());
  ignore.ignore = {"light.mass"};
  EXPECT_FALSE(run(kBase, replace(kBase, "2.5 default", "9 default"), ignore).same());
}

TEST(Diff, IdentityRulesNameSchemaFields) {
  for (const IdentityRule& rule : identityRules()) {
    const KindDef* k = Schema::get().kind(rule.tag);
    ASSERT_NE(k, nullptr) << rule.tag;
    for (std::string_view word : splitWords(rule.fields)) {
      while (!word.empty()) {
        std::size_t bar = word.find('|');
        std::string name(word.substr(0, bar));
        bool found = k->key(name) != nullptr;
        for (const FieldDef& f : k->layouts[0].fields) found = found || f.name == name;
        EXPECT_TRUE(found) << rule.tag << "." << name;
        word = bar == std::string_view::npos ? std::string_view() : word.substr(bar + 1);
      }
    }
  }
}

TEST(Diff, RepeatedKeysAreNumbered) {
  LoadResult r = parse("raisim_engine_scene 1\nprefab_override /World/A property=visible value=false\n"
                       "prefab_override /World/A property=visible value=true\n");
  ASSERT_TRUE(r.ok());
  std::vector<std::string> keys = identityKeys(r.document);
  ASSERT_EQ(keys.size(), 3u);
  EXPECT_EQ(keys[2], keys[1] + "#2");
}

TEST(Diff, JsonResult) {
  nlohmann::json j = nlohmann::json::parse(diffToJson(run(kBase, replace(kBase, "2.5 default", "3 default"))));
  EXPECT_EQ(j["same"], false);
  EXPECT_EQ(j["stat"]["changed"], 1);
  EXPECT_EQ(j["records"][0]["fields"][0]["name"], "mass");
  EXPECT_EQ(j["records"][0]["fields"][0]["old"], "2.5");
  EXPECT_EQ(j["records"][0]["fields"][0]["new"], "3");
  EXPECT_EQ(nlohmann::json::parse(diffToJson(run(kBase, kBase)))["same"], true);
}
