// Issue 27: records that lost their ids (a scene sent through rscene-to-xml
// and back) are matched by path; `--ignore id` matches by path only; an
// added or removed record lists its fields with their values.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/diff.hpp"
#include "core/diff_identity.hpp"
#include "core/loader.hpp"

using namespace rscene;

namespace {

const char* kWithIds =
    "raisim_engine_scene 1\n"
    "material mat_a 0.5 0.5 0.5 1 0 0.5 0 0 0 0 false - - - - - - id=m_a\n"
    "group /World id=folder_world parentId=-\n"
    "terrain_region /World/T 3 3 2 2 0 0 0 id=terrain_t heights=0,0,0,0,0,0,0,0,0\n"
    "terrain_splat_layer /World/T slot=1 strength=1\n"
    "object /World/Box box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 2.5 default mat_a false true false - dynamic true 1 "
    "18446744073709551615 id=box parentGroupId=folder_world\n";

// The same scene without any id=, as rscene-from-xml writes it.
const char* kNoIds =
    "raisim_engine_scene 1\n"
    "material mat_a 0.5 0.5 0.5 1 0 0.5 0 0 0 0 false - - - - - -\n"
    "group /World parentId=-\n"
    "terrain_region /World/T 3 3 2 2 0 0 0 heights=0,0,0,0,0,0,0,0,0\n"
    "terrain_splat_layer /World/T slot=1 strength=1\n"
    "object /World/Box box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 2.5 default mat_a false true false - dynamic true 1 "
    "18446744073709551615 parentGroupId=folder_world\n";

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

const RecordDiff* find(const DiffResult& d, std::string_view tag) {
  for (const RecordDiff& r : d.records)
    if (r.tag == tag) return &r;
  return nullptr;
}

}  // namespace

TEST(DiffMatch, RecordsThatLostTheirIdsAreMatchedByPath) {
  for (bool forward : {true, false}) {  // ids dropped, or ids given
    DiffResult d = forward ? run(kWithIds, kNoIds) : run(kNoIds, kWithIds);
    // One changed record per node and material, no removed and added pairs;
    // the splat layer follows its terrain and is no change.
    EXPECT_EQ(d.count(Change::Added), 0u);
    EXPECT_EQ(d.count(Change::Removed), 0u);
    EXPECT_EQ(d.records.size(), 4u);  // material, group, terrain_region, object
    EXPECT_EQ(find(d, "terrain_splat_layer"), nullptr);
    const RecordDiff* box = find(d, "object");
    ASSERT_NE(box, nullptr);
    EXPECT_EQ(box->path, "/World/Box");
    EXPECT_FALSE(box->renamed());
    ASSERT_EQ(box->fields.size(), 1u);
    EXPECT_EQ(box->fields[0].name, "id");
    EXPECT_EQ(box->fields[0].change, forward ? Change::Removed : Change::Added);
    EXPECT_EQ(forward ? box->fields[0].oldValue : box->fields[0].newValue, "box");
    const RecordDiff* material = find(d, "material");
    ASSERT_NE(material, nullptr);
    ASSERT_EQ(material->fields.size(), 1u);
    EXPECT_EQ(material->fields[0].name, "id");
  }
}

TEST(DiffMatch, IdsOnBothSidesStillDecide) {
  // Another id at the same path is another record.
  DiffResult d = run(kWithIds, replace(kWithIds, "id=box", "id=crate"));
  EXPECT_EQ(d.count(Change::Added), 1u);
  EXPECT_EQ(d.count(Change::Removed), 1u);
  // The same id at another path is the same record, moved.
  d = run(kWithIds, replace(kWithIds, "object /World/Box", "object /World/Crate"));
  ASSERT_EQ(d.records.size(), 1u);
  EXPECT_EQ(d.records[0].oldPath, "/World/Box");
  // An id on one side only, at another path: not the same record.
  d = run(kWithIds, replace(kNoIds, "object /World/Box", "object /World/Crate"));
  const RecordDiff* box = nullptr;
  for (const RecordDiff& r : d.records)
    if (r.tag == "object") {
      EXPECT_NE(r.change, Change::Changed);
      box = &r;
    }
  EXPECT_NE(box, nullptr);
}

TEST(DiffMatch, APathThatRepeatsPairsInFileOrder) {
  std::string a = std::string(kWithIds) + "light /World/L 0 0 -1 1 id=l1\nlight /World/L 0 0 -1 2 id=l2\n";
  std::string b = std::string(kWithIds) + "light /World/L 0 0 -1 1\nlight /World/L 0 0 -1 3\n";
  DiffResult d = run(a, b);
  ASSERT_EQ(d.records.size(), 2u);
  EXPECT_EQ(d.records[0].fields.size(), 1u);  // the first: its id only
  ASSERT_EQ(d.records[1].fields.size(), 2u);  // the second: intensity and id
  EXPECT_EQ(d.records[1].fields[0].name, "intensity");
  EXPECT_EQ(d.records[1].fields[0].newValue, "3");
}

TEST(DiffMatch, IgnoreIdMatchesByPathAndReportsNoId) {
  DiffOptions ignore;
  ignore.ignore = {"id", "parentGroupId"};
  EXPECT_TRUE(run(kWithIds, kNoIds, ignore).same());
  // Other ids at the same paths: the same records.
  std::string renamed = replace(replace(kWithIds, "id=box", "id=crate"), "id=m_a", "id=m_b");
  EXPECT_TRUE(run(kWithIds, renamed, ignore).same());
  EXPECT_FALSE(run(kWithIds, renamed).same());
  // The same id at another path: no longer the same record.
  DiffResult d = run(kWithIds, replace(kWithIds, "object /World/Box", "object /World/Crate"), ignore);
  EXPECT_EQ(d.count(Change::Added), 1u);
  EXPECT_EQ(d.count(Change::Removed), 1u);
  // TAG.id: only that kind's ids are ignored.
  DiffOptions objectIds;
  objectIds.ignore = {"object.id"};
  d = run(kWithIds, replace(replace(kWithIds, "id=box", "id=crate"), "id=folder_world parentId", "id=w parentId"),
          objectIds);
  ASSERT_EQ(d.records.size(), 2u);  // the group removed and added, the object the same
  EXPECT_EQ(d.records[0].tag, "group");
  EXPECT_EQ(d.records[1].tag, "group");
}

TEST(DiffMatch, IgnoreIdKeysChildrenAndResourcesByName) {
  LoadResult r = parse(
      "raisim_engine_scene 1\n"
      "articulated_resource arm_res Arm arm.urdf\n"
      "terrain_region /World/T 3 3 2 2 0 0 0 heights=0,0,0,0,0,0,0,0,0\n"
      "terrain_foliage_layer /World/T id=foliage_grass name=Grass\n");
  ASSERT_TRUE(r.ok());
  IdentityOptions ignore;
  ignore.ignoreIdTags = {"*"};
  std::vector<std::string> byId = identityKeys(r.document), byName = identityKeys(r.document, ignore);
  ASSERT_EQ(byName.size(), 4u);
  EXPECT_NE(byId[1].find("arm_res"), std::string::npos);
  EXPECT_NE(byName[1].find("Arm"), std::string::npos);
  EXPECT_EQ(byName[1].find("arm_res"), std::string::npos);
  EXPECT_NE(byName[3].find("Grass"), std::string::npos);
  EXPECT_EQ(byName[3].find("foliage_grass"), std::string::npos);
  EXPECT_EQ(childPath(r.document, r.document.records[3], byName[3], ignore), "/World/T[name=Grass]");
  EXPECT_EQ(childPath(r.document, r.document.records[3], byId[3]), "/World/T[id=foliage_grass]");
}

TEST(DiffMatch, AddedAndRemovedRecordsListTheirValues) {
  std::string b = std::string(kWithIds) + "light /World/Sun 0 0 -1 3 id=sun type=directional\n";
  DiffResult d = run(kWithIds, b);
  ASSERT_EQ(d.records.size(), 1u);
  const RecordDiff& sun = d.records[0];
  EXPECT_EQ(sun.change, Change::Added);
  std::vector<std::string> names;
  for (const FieldDiff& f : sun.fields) {
    EXPECT_EQ(f.change, Change::Added);
    EXPECT_TRUE(f.oldValue.empty());
    names.push_back(f.name + "=" + f.newValue);
  }
  // The path is the record's label, not a field.
  EXPECT_EQ(names, (std::vector<std::string>{"direction=0,0,-1", "intensity=3", "id=sun", "type=directional"}));

  d = run(b, kWithIds);
  ASSERT_EQ(d.records.size(), 1u);
  EXPECT_EQ(d.records[0].change, Change::Removed);
  ASSERT_EQ(d.records[0].fields.size(), 4u);
  EXPECT_EQ(d.records[0].fields[1].oldValue, "3");
  EXPECT_EQ(d.records[0].fields[1].change, Change::Removed);

  // --ignore applies; a long list is counted, not printed.
  DiffOptions opt;
  opt.ignore = {"id"};
  std::string terrain = "terrain_region /World/U 5 5 2 2 0 0 0 heights=0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\n";
  d = run(kWithIds, std::string(kWithIds) + terrain, opt);
  ASSERT_EQ(d.records.size(), 1u);
  bool heights = false;
  for (const FieldDiff& f : d.records[0].fields) {
    EXPECT_NE(f.name, "id");
    if (f.name != "heights") continue;
    heights = true;
    EXPECT_TRUE(f.summarized);
    EXPECT_EQ(f.newCount, 25u);
    EXPECT_TRUE(f.newValue.empty());
  }
  EXPECT_TRUE(heights);
}

TEST(DiffMatch, JsonListsTheFieldsOfAddedRecordsButCountsOnlyChangedOnes) {
  std::string b = replace(kWithIds, "2.5 default", "3 default") + "light /World/Sun 0 0 -1 3 id=sun\n";
  nlohmann::json j = nlohmann::json::parse(diffToJson(run(kWithIds, b)));
  EXPECT_EQ(j["stat"]["fieldsChanged"], 1);  // mass; not the new light's fields
  bool sawLight = false;
  for (const nlohmann::json& r : j["records"]) {
    if (r["tag"] != "light") continue;
    sawLight = true;
    EXPECT_EQ(r["change"], "added");
    ASSERT_EQ(r["fields"].size(), 3u);
    EXPECT_EQ(r["fields"][1]["name"], "intensity");
    EXPECT_EQ(r["fields"][1]["new"], 3);
    EXPECT_FALSE(r["fields"][1].contains("old"));
  }
  EXPECT_TRUE(sawLight);
}

TEST(DiffMatch, AChildNamingItsParentByIdOrByPathIsTheSameChild) {
  const std::string byId =
      "raisim_engine_scene 1\n"
      "compound /World/Table 0 0 1 1 0 0 0 1 1 1 5 dynamic true true id=compound_table\n"
      "compound_child compound_table box 0 0 0.72 1 0 0 0 1 1 1 size=1.2,0.7,0.06\n"
      "compound_child compound_table box 0 0 0.35 1 0 0 0 1 1 1 size=0.06,0.06,0.7\n";
  std::string byPath = byId;
  for (std::size_t at; (at = byPath.find("compound_child compound_table")) != std::string::npos;)
    byPath.replace(at, 29, "compound_child /World/Table");
  EXPECT_TRUE(run(byId, byPath).same());
  // As rscene-from-xml writes it: no id on the parent either.
  DiffResult d = run(byId, replace(byPath, " id=compound_table", ""));
  ASSERT_EQ(d.records.size(), 1u);
  EXPECT_EQ(d.records[0].tag, "compound");
  ASSERT_EQ(d.records[0].fields.size(), 1u);
  EXPECT_EQ(d.records[0].fields[0].name, "id");
  // A changed child still shows, under its parent's path.
  d = run(byId, replace(byPath, "size=0.06,0.06,0.7", "size=0.06,0.06,0.8"));
  ASSERT_EQ(d.records.size(), 1u);
  EXPECT_EQ(d.records[0].path, "/World/Table[1]");
  ASSERT_EQ(d.records[0].fields.size(), 1u);
  EXPECT_EQ(d.records[0].fields[0].name, "size");
}
