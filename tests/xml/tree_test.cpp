// The expanded tree's lookups and the way its diagnostics name the file,
// line and element.
#include <gtest/gtest.h>

#include "xml/xml_tree.hpp"

namespace rscene::xml {
namespace {

Element sphere() {
  Element e;
  e.name = "sphere";
  e.where = {"w.xml", 7, 9};
  e.attributes = {{"collisionGroup", "2", {"w.xml", 7, 17}}, {"collision_group", "4", {"w.xml", 7, 36}}};
  Element dim;
  dim.name = "dim";
  e.children.push_back(dim);
  return e;
}

TEST(XmlTree, SnakeCaseWinsOverItsAlias) {
  Element e = sphere();
  ASSERT_NE(e.attribute("collision_group", "collisionGroup"), nullptr);
  EXPECT_EQ(e.attribute("collision_group", "collisionGroup")->value, "4");
  EXPECT_EQ(e.attribute("collision_mask", "collisionMask"), nullptr);
  EXPECT_NE(e.child("dim"), nullptr);
  EXPECT_EQ(e.child("state"), nullptr);
}

TEST(XmlTree, DiagnosticsNameFileLineAndElement) {
  Element e = sphere();
  Diagnostic d = attributeDiagnostic(Severity::Error, "RS8110", e, e.attributes[0], "not an integer");
  EXPECT_EQ(d.file, "w.xml");
  EXPECT_EQ(d.line, 7u);
  EXPECT_EQ(d.column, 17u);
  EXPECT_EQ(d.message, "<sphere> collisionGroup: not an integer");
  Diagnostic whole = elementDiagnostic(Severity::Warning, "RS8110", e, "no <state>");
  EXPECT_EQ(whole.column, 9u);
  EXPECT_EQ(whole.message, "<sphere>: no <state>");
}

}  // namespace
}  // namespace rscene::xml
