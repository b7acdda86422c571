// Robot files as they are found (lib/robot/xml_file.cpp, urdf.cpp): an XML
// declaration after a comment (RaiSim's older ANYmal and cart-pole URDFs),
// an end tag that does not match, a colour written in 0..255.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/filesystem.hpp"
#include "robot/load.hpp"
#include "robot/xml_file.hpp"

namespace rscene::robot {
namespace {

const char* kLink = R"(<link name="base"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>)";

bool load(const std::string& text, Model& m, Diagnostics& d) {
  static MemoryFileSystem files;
  files.addFile("/mem/r.urdf", text);
  LoadOptions options;
  options.files = &files;
  return loadModel("/mem/r.urdf", options, m, d);
}

std::string dump(const Diagnostics& ds) {
  std::string s;
  for (const Diagnostic& d : ds) s += std::to_string(d.line) + ": " + d.message + " [" + d.code + "]\n";
  return s;
}

TEST(RobotXmlFile, DeclarationAfterACommentIsReadWithAWarning) {
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load("<!-- generated -->\n\n<?xml version=\"1.0\" ?>\n<robot name=\"r\">" + std::string(kLink) +
                       "</robot>\n",
                   m, d))
      << dump(d);
  ASSERT_EQ(d.size(), 1u) << dump(d);
  EXPECT_EQ(d[0].code, std::string(rs::RS7054));
  EXPECT_EQ(d[0].severity, Severity::Warning);
  EXPECT_EQ(d[0].line, 3u);
  EXPECT_EQ(m.links.size(), 1u);
}

TEST(RobotXmlFile, DeclarationsFirstNeedNoWarning) {
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load("\n<?xml version=\"1.0\"?>\n<?xml version=\"1.0\"?>\n<!-- c -->\n<robot name=\"r\">" +
                       std::string(kLink) + "</robot>\n",
                   m, d))
      << dump(d);
  EXPECT_TRUE(d.empty()) << dump(d);
}

TEST(RobotXmlFile, BlankingKeepsLinesAndLeavesTheRootAlone) {
  std::string text = "<!-- a -->\n<?xml version=\"1.0\"\n encoding=\"utf-8\"?>\n<robot><?xml version=\"1.0\"?></robot>";
  const std::size_t size = text.size();
  std::vector<int> lines = blankMisplacedDeclarations(text);
  ASSERT_EQ(lines, std::vector<int>{2});
  EXPECT_EQ(text.size(), size);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3);
  EXPECT_EQ(text.find("<?xml"), text.find("<robot>") + 7);  // inside the root: not the prolog's
}

TEST(RobotXmlFile, MismatchedEndTagIsReportedWhereItIsAndNamesBothElements) {
  Model m;
  Diagnostics d;
  EXPECT_FALSE(load("<robot name=\"r\">\n  <link name=\"a\">\n    <visual/>\n\n  </lnk>\n</robot>\n", m, d));
  ASSERT_EQ(d.size(), 1u) << dump(d);
  EXPECT_EQ(d[0].code, std::string(rs::RS7030));
  EXPECT_EQ(d[0].line, 5u) << dump(d);
  EXPECT_NE(d[0].message.find("</lnk> does not close <link> (opened at line 2)"), std::string::npos) << d[0].message;
}

TEST(RobotXmlFile, ColourIn0To255IsClampedWithAWarning) {
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load("<robot name=\"r\">\n<link name=\"base\"><visual><geometry><box size=\"1 1 1\"/></geometry>\n"
                   "<material name=\"g\"><color rgba=\"0 200 0 255\"/></material></visual></link>\n</robot>\n",
                   m, d))
      << dump(d);
  ASSERT_EQ(d.size(), 1u) << dump(d);
  EXPECT_EQ(d[0].code, std::string(rs::RS7055));
  EXPECT_EQ(d[0].line, 3u);
  ASSERT_EQ(m.links.size(), 1u);
  ASSERT_EQ(m.links[0].visuals.size(), 1u);
  ASSERT_TRUE(m.links[0].visuals[0].color.has_value());
  EXPECT_EQ(*m.links[0].visuals[0].color, Eigen::Vector4d(0, 1, 0, 1));
}

}  // namespace
}  // namespace rscene::robot
