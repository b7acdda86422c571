// "Did you mean" for references that name nothing (check_refs.cpp).
#include <gtest/gtest.h>

#include "core/check.hpp"

using namespace rscene;

namespace {

const std::string kScene =
    "raisim_engine_scene 1\n"
    "material mat_box 1 0.42 0.05 1 0 0.6 0 0 0 0 false - - - - - - id=mat_box\n"
    "contact_material rubber steel 0.9 0 0 0.9 0 0 0 id=rubber_steel\n"
    "group /World/Props id=folder_props\n"
    "group /World/Other\n";

std::string box(const std::string& name, const std::string& material, const std::string& keys) {
  return "object /World/Props/" + name + " box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 1.0 default " + material +
         " false true false - dynamic true 1 18446744073709551615 " + keys + "\n";
}

// The hint of the first finding with `code`.
std::string hintOf(const std::string& text, const std::string& code) {
  Document doc;
  for (const Diagnostic& d : validateText(text, {}, doc))
    if (d.code == code) return d.hint;
  return "<no " + code + ">";
}

}  // namespace

TEST(CheckRefs, SuggestsTheClosestMaterial) {
  EXPECT_EQ(hintOf(kScene + box("a", "mat_bx", ""), "RS3008"), "did you mean `mat_box`?");
  EXPECT_EQ(hintOf(kScene + box("a", "Mat_Box", ""), "RS3008"), "did you mean `mat_box`?");
  EXPECT_EQ(hintOf(kScene + box("a", "engine_defualt", ""), "RS3008"), "did you mean `engine_default`?");
  // Nothing close: the general hint stays.
  EXPECT_EQ(hintOf(kScene + box("a", "banana", ""), "RS3008"),
            "engine_default always exists; other names need a material record");
}

TEST(CheckRefs, SuggestsParentsByIdDefaultIdOrPath) {
  EXPECT_EQ(hintOf(kScene + box("a", "mat_box", "parentGroupId=folder_prop"), "RS3006"),
            "did you mean `folder_props`?");
  EXPECT_EQ(hintOf(kScene + box("a", "mat_box", "parentGroupId=folder_/World/Othr"), "RS3006"),
            "did you mean `folder_/World/Other`?");
  EXPECT_EQ(hintOf(kScene + box("a", "mat_box", "parentGroupId=/World/Prop"), "RS3006"),
            "did you mean `/World/Props`?");
  // A node's name instead of its path.
  EXPECT_EQ(hintOf(kScene + box("a", "mat_box", "parentGroupId=Other"), "RS3006"), "did you mean `/World/Other`?");
  EXPECT_EQ(hintOf(kScene + box("a", "mat_box", "parentGroupId=zzzzzz"), "RS3006"), "name a group by its id or path");
}

TEST(CheckRefs, SuggestsContactMaterialsAndChildParentsOfTheRightKind) {
  EXPECT_EQ(hintOf(kScene + "object /World/a box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 1.0 defualt mat_box\n", "RS3009"),
            "did you mean `default`?");
  EXPECT_EQ(hintOf(kScene + "object /World/a box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 1.0 rubber_stel mat_box\n", "RS3009"),
            "did you mean `rubber_steel`?");
  // A compound_child names a compound: /World/Props is a group, not one.
  std::string text = kScene + "compound /World/Cart 0 0 1 1 0 0 0 1 1 1 10 dynamic true true\n" +
                     "compound_child /World/Crat box 0 0 0 1 0 0 0 1 1 1 size=1,1,1\n" +
                     "compound_child /World/Prop box 0 0 0 1 0 0 0 1 1 1 size=1,1,1\n";
  Document doc;
  Diagnostics ds = validateText(text, {}, doc);
  std::vector<std::string> hints;
  for (const Diagnostic& d : ds)
    if (d.code == "RS3014") hints.push_back(d.hint);
  EXPECT_EQ(hints, (std::vector<std::string>{"did you mean `/World/Cart`?", ""}));
}

TEST(CheckRefs, ManyMissingReferencesAmongManyNodesStayCheap) {
  // 20000 groups and 5000 distinct missing parents: the comparison budget
  // (1M candidates, 40000 names each time) answers the first ones and then
  // stops looking.
  std::string text = "raisim_engine_scene 1\n";
  for (int i = 0; i < 20000; ++i) text += "group /World/G" + std::to_string(i) + "\n";
  for (int i = 0; i < 5000; ++i)
    text += "group /World/H" + std::to_string(i) + " parentId=/World/G" + std::to_string(i) + "x\n";
  Document doc;
  Diagnostics ds = validateText(text, {}, doc);
  ASSERT_EQ(ds.size(), 5000u);
  EXPECT_EQ(ds.front().hint, "did you mean `/World/G0`?");
  EXPECT_EQ(ds.back().hint, "name a group by its id or path");
}
