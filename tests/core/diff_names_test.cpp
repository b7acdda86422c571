// DiffOptions::entryNames: number lists whose entries a caller names (the
// joints of generalizedCoordinate) are compared and shown by name.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/diff.hpp"
#include "core/loader.hpp"

using namespace rscene;

namespace {

std::string scene(const std::string& q, const std::string& extra = "") {
  return "raisim_engine_scene 1\n"
         "articulated_resource arm_res Arm arm.urdf\n"
         "articulated /World/Arm arm_res 0 0 0 1 0 0 0 true true id=arm generalizedCoordinate=" +
         q + extra + "\n";
}

struct Names {
  std::vector<std::string> joints{"shoulder", "elbow", "wrist"};
  int calls = 0;
  DiffOptions options() {
    DiffOptions o;
    o.entryNames = [this](const Document& doc, std::size_t record, std::string_view field) {
      ++calls;
      EXPECT_EQ(doc.tag(doc.records[record]), "articulated");
      return field == "generalizedCoordinate" ? joints : std::vector<std::string>{};
    };
    return o;
  }
};

DiffResult run(const std::string& a, const std::string& b, const DiffOptions& opt) {
  LoadResult la = parse(a), lb = parse(b);
  EXPECT_TRUE(la.ok() && lb.ok());
  return diff(la.document, lb.document, opt);
}

TEST(DiffEntryNames, ChangedEntriesAreNamedByJoint) {
  Names n;
  DiffResult r = run(scene("0.1,-0.8,0.3"), scene("0.1,-0.75,0.3"), n.options());
  ASSERT_EQ(r.records.size(), 1u);
  ASSERT_EQ(r.records[0].fields.size(), 1u);
  const FieldDiff& f = r.records[0].fields[0];
  EXPECT_EQ(f.name, "generalizedCoordinate[elbow]");
  EXPECT_EQ(f.oldValue, "-0.8");
  EXPECT_EQ(f.newValue, "-0.75");
  EXPECT_FALSE(f.entry);  // a short list: no summary line above it
  EXPECT_GT(n.calls, 0);
}

TEST(DiffEntryNames, WithoutNamesTheListChangesAsAWhole) {
  DiffResult r = run(scene("0.1,-0.8,0.3"), scene("0.1,-0.75,0.3"), DiffOptions{});
  ASSERT_EQ(r.records[0].fields.size(), 1u);
  EXPECT_EQ(r.records[0].fields[0].name, "generalizedCoordinate");
  EXPECT_EQ(r.records[0].fields[0].newValue, "0.1,-0.75,0.3");
}

TEST(DiffEntryNames, ToleranceAppliesAndSameValuesAreNoChange) {
  Names n;
  DiffOptions o = n.options();
  o.tolerance = 0.1;
  EXPECT_TRUE(run(scene("0.1,-0.8,0.3"), scene("0.1,-0.75,0.3"), o).same());
  EXPECT_TRUE(run(scene("0.1,-0.8,0.3"), scene("0.10,-0.80,0.3"), n.options()).same());
}

TEST(DiffEntryNames, ListsOfAnotherLengthFallBackToIndices) {
  Names n;  // three names, four values on the new side: the record is wrong, not renamed
  DiffResult r = run(scene("0.1,-0.8,0.3"), scene("0.1,-0.8,0.3,4"), n.options());
  ASSERT_EQ(r.records[0].fields.size(), 1u);
  EXPECT_EQ(r.records[0].fields[0].name, "generalizedCoordinate");
}

// A new jointOrder reorders the numbers; the same joint values are no change.
TEST(DiffEntryNames, EntriesMatchByNameNotPlace) {
  LoadResult la = parse(scene("1,2,3")), lb = parse(scene("3,1,2"));
  DiffOptions o;
  o.entryNames = [&](const Document& doc, std::size_t, std::string_view) {
    return &doc == &la.document ? std::vector<std::string>{"a", "b", "c"} : std::vector<std::string>{"c", "a", "b"};
  };
  EXPECT_TRUE(diff(la.document, lb.document, o).same());
  o.entryNames = [&](const Document& doc, std::size_t, std::string_view) {
    return &doc == &la.document ? std::vector<std::string>{"a", "b", "c"} : std::vector<std::string>{"c", "a", "d"};
  };
  DiffResult r = diff(la.document, lb.document, o);
  ASSERT_EQ(r.records[0].fields.size(), 2u);
  EXPECT_EQ(r.records[0].fields[0].name, "generalizedCoordinate[d]");
  EXPECT_EQ(r.records[0].fields[0].change, Change::Added);
  EXPECT_EQ(r.records[0].fields[1].name, "generalizedCoordinate[b]");
  EXPECT_EQ(r.records[0].fields[1].change, Change::Removed);
  EXPECT_EQ(r.records[0].fields[1].oldValue, "2");
}

TEST(DiffEntryNames, LongListsKeepTheirSummaryAndTheJsonNamesTheJoint) {
  Names n;
  n.joints.clear();
  std::string a, b;
  for (int i = 0; i < 19; ++i) {
    n.joints.push_back("j" + std::to_string(i));
    a += (i ? "," : "") + std::to_string(i);
    b += (i ? "," : "") + std::to_string(i == 12 ? 40 : i);
  }
  DiffResult r = run(scene(a), scene(b), n.options());
  ASSERT_EQ(r.records[0].fields.size(), 2u);
  EXPECT_TRUE(r.records[0].fields[0].summarized);
  EXPECT_EQ(r.records[0].fields[0].changedCount, 1u);
  EXPECT_EQ(r.records[0].fields[0].maxDelta, 28);
  EXPECT_EQ(r.records[0].fields[1].name, "generalizedCoordinate[j12]");
  EXPECT_TRUE(r.records[0].fields[1].entry);
  nlohmann::json j = nlohmann::json::parse(diffToJson(r));
  auto fields = j["records"][0]["fields"];
  ASSERT_EQ(fields.size(), 2u);
  EXPECT_EQ(fields[1]["name"], "generalizedCoordinate[j12]");
  EXPECT_EQ(fields[1]["old"], 12);
  EXPECT_EQ(fields[1]["new"], 40);
}

}  // namespace
