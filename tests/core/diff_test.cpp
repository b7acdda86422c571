// Semantic diff: identity matching, typed comparison, tolerances, list
// summaries, ignore options and the JSON result.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
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
  const std::vector<FieldDiff>& fs = d.records[0].fields;
  ASSERT_EQ(fs.size(), 3u);
  EXPECT_EQ(fs[0].name, "heights");
  EXPECT_TRUE(fs[0].summarized);
  EXPECT_EQ(fs[0].newCount, 9u);
  EXPECT_EQ(fs[0].changedCount, 2u);
  EXPECT_EQ(fs[0].listedCount, 2u);
  EXPECT_DOUBLE_EQ(fs[0].maxDelta, 0.03);
  // The changed entries follow, named by their index.
  EXPECT_EQ(fs[1].name, "heights[1]");
  EXPECT_TRUE(fs[1].entry);
  EXPECT_EQ(fs[1].oldValue, "0");
  EXPECT_EQ(fs[1].newValue, "0.03");
  EXPECT_EQ(fs[2].name, "heights[4]");
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
  EXPECT_EQ(d.records[0].fields.at(0).oldValue, "0");
  EXPECT_TRUE(d.records[0].fields.at(0).oldDefault);
  EXPECT_FALSE(d.records[0].fields.at(0).newDefault);

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
  EXPECT_EQ(j["records"][0]["fields"][0]["old"], 2.5);  // typed: numbers are numbers
  EXPECT_EQ(j["records"][0]["fields"][0]["new"], 3);
  EXPECT_EQ(nlohmann::json::parse(diffToJson(run(kBase, kBase)))["same"], true);
}

// --- every value by its schema type (issue 9, section 3) ---

namespace {

const char* kTyped =
    "raisim_engine_scene 1\n"
    "terrain_texture 0 terrain_sand Sand color=0.76,0.68,0.50,1 uvScale=4\n"
    "light /World/Area 0 0 -1 3 id=light_area type=area areaRight=1.0,0,0 areaUp=0,1.0,0 color=1,0.90,0.8\n"
    "compound /World/Cart 0 0 1 1 0 0 0 1 1 1 5 dynamic true true id=cart\n"
    "compound_child /World/Cart box 0 0 0 1 0 0 0 1 1 1 size=1.0,0.6,0.10\n"
    "compound_child /World/Cart sphere 0 0 0.5 1 0 0 0 1 1 1 radius=0.25\n"
    "deformable /World/Cloth cloth - 0 0 2 1 0 0 0 1 1 1 id=cloth scale=1\n"
    "articulated_ik /World/Arm hand 0.5,0,1.00\n"
    "instanced_visual /World/Grass box id=grass instances="
    "0,0,0,1,0,0,0,1,1,1;1,0,0,1,0,0,0,1,1,1;2,0,0,1,0,0,0,1,1,1;3,0,0,1,0,0,0,1,1,1\n"
    "point_cloud /World/Points id=points points=0,0,0;1,1,1 colors=1,0,0,1;0,1,0\n";

}  // namespace

TEST(DiffTyped, VectorsAndColorsInKeysCompareAsNumbers) {
  // The "Seen" of the issue: `color: 0.76,0.68,0.5,1 -> 0.76,0.68,0.5,1`,
  // the same for areaRight/areaUp, compound_child size and csv3 targets.
  std::string b = replace(kTyped, "color=0.76,0.68,0.50,1", "color=0.76,0.680,0.5,1.0");
  b = replace(b, "areaRight=1.0,0,0 areaUp=0,1.0,0 color=1,0.90,0.8", "areaRight=1,0,0 areaUp=0,1,0 color=1,0.9,0.80");
  b = replace(b, "size=1.0,0.6,0.10", "size=1,0.6,0.1");
  b = replace(b, "hand 0.5,0,1.00", "hand 0.50,0,1");
  EXPECT_TRUE(run(kTyped, b).same());
  EXPECT_TRUE(run(kTyped, test::fmt(kTyped)).same());

  DiffResult d = run(kTyped, replace(kTyped, "color=0.76,0.68,0.50,1", "color=0.76,0.68,0.51,1"));
  ASSERT_EQ(d.records.size(), 1u);
  EXPECT_EQ(d.records[0].fields.at(0).name, "color");
  EXPECT_EQ(d.records[0].fields.at(0).type, ValueType::Color);
  EXPECT_EQ(d.records[0].fields.at(0).oldValue, "0.76,0.68,0.5,1");
  EXPECT_EQ(d.records[0].fields.at(0).newValue, "0.76,0.68,0.51,1");
  // A vector with another number of components is a change.
  EXPECT_FALSE(run(kTyped, replace(kTyped, "size=1.0,0.6,0.10", "size=1.0,0.6")).same());
}

TEST(DiffTyped, ToleranceAppliesToEveryNumberInsideValues) {
  std::string b = replace(kTyped, "color=0.76,0.68,0.50,1", "color=0.7600001,0.68,0.50,1");
  b = replace(b, "size=1.0,0.6,0.10", "size=1.0,0.6000001,0.10");
  b = replace(b, "1,0,0,1,0,0,0,1,1,1;2", "1,0,0,1,0,0,0,1,1.0000001,1;2");
  b = replace(b, "points=0,0,0;1,1,1", "points=0,0,0;1,1,1.0000001");
  b = replace(b, "/World/Cart 0 0 1 1 0 0 0", "/World/Cart 0 0 1 0.9999999 0 0 0");  // a positional quaternion
  EXPECT_EQ(run(kTyped, b).records.size(), 5u);
  DiffOptions abs;
  abs.tolerance = 1e-6;
  EXPECT_TRUE(run(kTyped, b, abs).same());
  DiffOptions rel;
  rel.relTolerance = 1e-6;
  EXPECT_TRUE(run(kTyped, b, rel).same());
}

TEST(DiffTyped, PositionalFieldAndKeyOfTheSameNameAreTwoFields) {
  // deformable: positional `scale` (vec3) and the key `scale=` (a number).
  EXPECT_TRUE(run(kTyped, replace(kTyped, "scale=1\n", "scale=1.0\n")).same());
  DiffResult d = run(kTyped, replace(kTyped, "scale=1\n", "scale=2\n"));
  ASSERT_EQ(d.records.size(), 1u);
  ASSERT_EQ(d.records[0].fields.size(), 1u);
  const FieldDiff& key = d.records[0].fields[0];
  EXPECT_EQ(key.name, "scale");
  EXPECT_TRUE(key.keyForm);
  EXPECT_EQ(key.type, ValueType::Number);
  EXPECT_EQ(key.oldValue, "1");
  EXPECT_EQ(key.newValue, "2");

  d = run(kTyped, replace(kTyped, "0 0 2 1 0 0 0 1 1 1 id=cloth", "0 0 2 1 0 0 0 2 2 2 id=cloth"));
  ASSERT_EQ(d.records.size(), 1u);
  ASSERT_EQ(d.records[0].fields.size(), 1u);
  EXPECT_FALSE(d.records[0].fields[0].keyForm);
  EXPECT_EQ(d.records[0].fields[0].oldValue, "1,1,1");
  EXPECT_EQ(d.records[0].fields[0].newValue, "2,2,2");

  // Removing the key is a change when it differs from the default (1):
  // the key now reads as its schema default.
  d = run(replace(kTyped, " scale=1\n", " scale=2\n"), replace(kTyped, " scale=1\n", "\n"));
  ASSERT_EQ(d.records.size(), 1u);
  ASSERT_EQ(d.records[0].fields.size(), 1u);
  EXPECT_EQ(d.records[0].fields[0].newValue, "1");
  EXPECT_TRUE(d.records[0].fields[0].keyForm);
}

TEST(DiffTyped, ChildRecordsAreNamedByTheirParentAndPlace) {
  DiffResult d = run(kTyped, replace(kTyped, "radius=0.25", "radius=0.3"));
  ASSERT_EQ(d.records.size(), 1u);
  EXPECT_EQ(d.records[0].tag, "compound_child");
  EXPECT_EQ(d.records[0].path, "/World/Cart[1]");
  d = run(kBase, replace(kBase, "slot=1 strength=1", "slot=1 strength=0.5"));
  ASSERT_EQ(d.records.size(), 1u);
  EXPECT_EQ(d.records[0].path, "/World/T[slot=1]");
  d = run(kTyped, replace(kTyped, "hand 0.5,0,1.00", "hand 0.5,0,2"));
  ASSERT_EQ(d.records.size(), 1u);
  EXPECT_EQ(d.records[0].path, "/World/Arm[frame=hand]");
}

TEST(DiffTyped, LongListsNameTheirChangedEntries) {
  DiffOptions opt;
  opt.summarizeAbove = 16;
  // A transform list names the part of the entry that changed.
  DiffResult d = run(kTyped, replace(kTyped, "3,0,0,1,0,0,0,1,1,1\n", "3,0,0.5,1,0,0,0,2,2,2\n"), opt);
  ASSERT_EQ(d.records.size(), 1u);
  const std::vector<FieldDiff>& fs = d.records[0].fields;
  ASSERT_EQ(fs.size(), 3u);
  EXPECT_TRUE(fs[0].summarized);
  EXPECT_EQ(fs[0].name, "instances");
  EXPECT_EQ(fs[0].newCount, 4u);  // entries, not numbers
  EXPECT_EQ(fs[0].changedCount, 1u);
  EXPECT_EQ(fs[1].name, "instances[3].position");
  EXPECT_EQ(fs[1].type, ValueType::Vec3);
  EXPECT_EQ(fs[1].oldValue, "3,0,0");
  EXPECT_EQ(fs[1].newValue, "3,0,0.5");
  EXPECT_EQ(fs[2].name, "instances[3].scale");
  EXPECT_EQ(fs[2].newValue, "2,2,2");

  // An appended entry; at most listEntries are named.
  d = run(kTyped, replace(kTyped, "3,0,0,1,0,0,0,1,1,1\n", "3,0,0,1,0,0,0,1,1,1;4,0,0,1,0,0,0,1,1,1\n"), opt);
  ASSERT_EQ(d.records.size(), 1u);
  ASSERT_EQ(d.records[0].fields.size(), 2u);
  EXPECT_EQ(d.records[0].fields[0].oldCount, 4u);
  EXPECT_EQ(d.records[0].fields[0].newCount, 5u);
  EXPECT_EQ(d.records[0].fields[1].name, "instances[4]");
  EXPECT_EQ(d.records[0].fields[1].change, Change::Added);
  EXPECT_EQ(d.records[0].fields[1].newValue, "4,0,0,1,0,0,0,1,1,1");

  opt.listEntries = 1;
  d = run(kTyped, replace(replace(kTyped, "2,0,0,1", "2,0,1,1"), "3,0,0,1", "3,0,1,1"), opt);
  ASSERT_EQ(d.records.size(), 1u);
  ASSERT_EQ(d.records[0].fields.size(), 2u);
  EXPECT_EQ(d.records[0].fields[0].changedCount, 2u);
  EXPECT_EQ(d.records[0].fields[0].listedCount, 1u);
  EXPECT_EQ(d.records[0].fields[1].name, "instances[2].position");
}

TEST(DiffTyped, ColorListEntriesAreTheirSemicolonGroups) {
  DiffOptions opt;
  opt.summarizeAbove = 4;
  DiffResult d = run(kTyped, replace(kTyped, "colors=1,0,0,1;0,1,0", "colors=1,0,0,1;0,1,0.5"), opt);
  ASSERT_EQ(d.records.size(), 1u);
  ASSERT_EQ(d.records[0].fields.size(), 2u);
  EXPECT_EQ(d.records[0].fields[0].newCount, 2u);
  EXPECT_EQ(d.records[0].fields[1].name, "colors[1]");
  EXPECT_EQ(d.records[0].fields[1].oldValue, "0,1,0");
}

TEST(DiffTyped, JsonCarriesTypedValues) {
  std::string b = replace(kTyped, "color=0.76,0.68,0.50,1", "color=0.7,0.68,0.5,1");
  b = replace(b, "scale=1\n", "scale=2\n");
  b = replace(b, "3,0,0,1,0,0,0,1,1,1\n", "3,0,0.5,1,0,0,0,1,1,1\n");
  nlohmann::json j = nlohmann::json::parse(diffToJson(run(kTyped, b)));
  std::map<std::string, nlohmann::json> fields;
  for (const auto& r : j["records"])
    for (const auto& f : r["fields"]) fields[f["name"].get<std::string>()] = f;
  EXPECT_EQ(fields["color"]["old"], nlohmann::json::parse("[0.76, 0.68, 0.5, 1]"));
  EXPECT_EQ(fields["color"]["new"], nlohmann::json::parse("[0.7, 0.68, 0.5, 1]"));
  EXPECT_EQ(fields["color"]["type"], "color");
  EXPECT_EQ(fields["scale"]["old"], 1);
  EXPECT_EQ(fields["scale"]["form"], "key");
  EXPECT_EQ(fields["instances"]["changedCount"], 1);
  EXPECT_EQ(fields["instances[3].position"]["new"], nlohmann::json::parse("[3, 0, 0.5]"));
  EXPECT_EQ(fields["instances[3].position"]["entry"], true);
  EXPECT_EQ(j["stat"]["fieldsChanged"], 3);  // entries are not counted as fields

  // Flags are booleans, uint64 groups strings, defaults marked.
  std::string o = replace(kBase, "false true false - dynamic true 1 18446744073709551615",
                          "false false false - dynamic true 1 18446744073709551614");
  o = replace(o, "accurate\n", "accurate erp2=0.5\n");
  j = nlohmann::json::parse(diffToJson(run(kBase, o)));
  fields.clear();
  for (const auto& r : j["records"])
    for (const auto& f : r["fields"]) fields[f["name"].get<std::string>()] = f;
  EXPECT_EQ(fields["visible"]["old"], true);
  EXPECT_EQ(fields["visible"]["new"], false);
  EXPECT_EQ(fields["collisionMask"]["new"], "18446744073709551614");
  EXPECT_EQ(fields["erp2"]["old"], 0);
  EXPECT_EQ(fields["erp2"]["oldIsDefault"], true);
}

TEST(DiffTyped, IgnoreNamesAreChecked) {
  LoadResult a = parse(std::string(kTyped) + "object /World/X box 0 0 0 1 0 0 0 1 1 1 0.5 1 1 default - false true "
                                              "false - dynamic true 1 1 futureKey=3\n"),
             b = parse(kTyped);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(checkIgnoreName("color", a.document, b.document), std::nullopt);
  EXPECT_EQ(checkIgnoreName("object.mass", a.document, b.document), std::nullopt);
  EXPECT_EQ(checkIgnoreName("futureKey", a.document, b.document), std::nullopt);  // a key the files write
  EXPECT_EQ(checkIgnoreName("colr", a.document, b.document), "no field 'colr'; did you mean 'color'?");
  EXPECT_EQ(checkIgnoreName("object.mas", a.document, b.document),
            "no field 'mas' in object records; did you mean 'mass'?");
  EXPECT_EQ(checkIgnoreName("objekt.mass", a.document, b.document),
            "no record kind 'objekt'; did you mean 'object'?");
  EXPECT_EQ(checkIgnoreName("light.futureKey", a.document, b.document),
            "no field 'futureKey' in light records");
}

// Formatting a file is never a difference: every fixture and example, and
// the real files of ../shared/corpus when present, against their
// canonical form.
TEST(DiffTyped, EveryFixtureIsTheSameAsItsFormattedSelf) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;  // tests/data/**/*.rscene
  for (const auto& e : fs::recursive_directory_iterator(RSCENE_TEST_DATA))
    if (e.path().extension() == ".rscene") files.push_back(e.path());
  for (const fs::path& p : test::scenesIn(fs::path(RSCENE_TEST_DATA) / ".." / ".." / "examples")) files.push_back(p);
  for (const fs::path& p : test::scenesIn(fs::path(RSCENE_SHARED_DIR) / "corpus")) files.push_back(p);
  std::size_t compared = 0;
  for (const fs::path& p : files) {
    LoadResult a = parse(test::readAll(p));
    if (!a.ok()) continue;  // fixtures of parse errors
    LoadResult b = parse(canonicalText(a.document));
    ASSERT_TRUE(b.ok()) << p;
    DiffResult d = diff(a.document, b.document);
    ++compared;
    EXPECT_TRUE(d.same()) << p << ": " << (d.records.empty() ? "" : d.records[0].tag + " " + d.records[0].key) << " "
                          << (d.records.empty() || d.records[0].fields.empty()
                                  ? ""
                                  : d.records[0].fields[0].name + ": " + d.records[0].fields[0].oldValue + " -> " +
                                        d.records[0].fields[0].newValue);
  }
  EXPECT_GE(compared, 15u);
}

TEST(DiffTyped, IntegersWrittenAsDecimalsAreTheSameNumber) {
  // `0.0` is no integer syntax (validate reports it), but it is the number
  // 0; rscene-fmt keeps it as written.
  std::string a = replace(kTyped, "id=grass instances=", "id=grass terrainFoliageLayer=2 instances=");
  EXPECT_TRUE(run(a, replace(a, "terrainFoliageLayer=2", "terrainFoliageLayer=2.0")).same());
  EXPECT_FALSE(run(a, replace(a, "terrainFoliageLayer=2", "terrainFoliageLayer=2.5")).same());
  std::string list = std::string(kBase) + "deformable /World/C cloth - 0 0 2 1 0 0 0 1 1 1 pinnedVertices=0,1,2\n";
  EXPECT_TRUE(run(list, replace(list, "pinnedVertices=0,1,2", "pinnedVertices=0.0,1,2")).same());
  DiffResult d = run(list, replace(list, "pinnedVertices=0,1,2", "pinnedVertices=0,1,3"));
  ASSERT_EQ(d.records.size(), 1u);
  EXPECT_EQ(d.records[0].fields.at(0).newValue, "0,1,3");
}

// Spellings of one value: a color without alpha is the color with alpha 1,
// and q and -q are one rotation (positional and key=value alike).
TEST(Diff, AlphaOneAndANegatedQuaternionAreNoChange) {
  EXPECT_TRUE(run(kBase, replace(kBase, "color=0.2,0.4,0.2", "color=0.2,0.4,0.2,1")).same());
  EXPECT_TRUE(run(kBase, replace(kBase, "0 0 0.5 1 0 0 0 1 1 1", "0 0 0.5 -1 -0 0 0 1 1 1")).same());
  EXPECT_FALSE(run(kBase, replace(kBase, "color=0.2,0.4,0.2", "color=0.2,0.4,0.2,0.5")).same());
  EXPECT_FALSE(run(kBase, replace(kBase, "0 0 0.5 1 0 0 0 1 1 1", "0 0 0.5 0 1 0 0 1 1 1")).same());
  EXPECT_FALSE(run(kBase, replace(kBase, "color=0.2,0.4,0.2", "color=0.2,0.4,0.3,1")).same());
}
