// Template expansion: parameters and --param, arrays (end exclusive),
// expressions in values, exist, includes with [THIS_DIR], object_class,
// and the locations errors carry.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "xml_test_util.hpp"

namespace rscene::xml {
namespace {

using test::childrenNamed;
using test::errors;
using test::loadText;
using test::show;

const std::string kData = std::filesystem::path(RSCENE_TEST_DATA "/xml").lexically_normal().string();
const std::string kExamples = RSCENE_SHARED_DIR "/spec/raisim/xml-examples";

const Element& objects(const LoadResult& r) {
  static const Element none;
  const Element* o = r.root ? r.root->child("objects") : nullptr;
  return o ? *o : none;
}

TEST(Expand, PlainWorldKeepsElementsAndLocations) {
  LoadResult r = loadText("<raisim version=\"1.0\">\n  <objects>\n    <sphere  name=\"a\" mass=\"1\"/>\n  </objects>\n</raisim>\n");
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(show(*r.root), "<raisim version=\"1.0\"><objects><sphere name=\"a\" mass=\"1\"/></objects></raisim>");
  const Element& s = objects(r).children[0];
  EXPECT_EQ(s.where.file, "w.xml");
  EXPECT_EQ(s.where.line, 3u);
  EXPECT_EQ(s.where.column, 5u);
  EXPECT_EQ(s.attributes[1].where.line, 3u);
  EXPECT_EQ(s.attributes[1].where.column, 23u);  // mass
  EXPECT_EQ(r.files, std::vector<std::string>{"w.xml"});
  // CRLF and tabs: lines by LF, columns in bytes.
  r = loadText("<raisim>\r\n\t<objects\tx=\"1\"/>\r\n</raisim>");
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(objects(r).where.line, 2u);
  EXPECT_EQ(objects(r).where.column, 2u);
  EXPECT_EQ(objects(r).attributes[0].where.column, 11u);
}

TEST(Expand, ParamsDefineAndParamOverrides) {
  std::string xml = R"(<raisim>
  <params><r value="0.5"/><h value="2"/></params>
  <objects><sphere name="s" mass="@@h"><dim radius="@@r"/></sphere></objects>
</raisim>)";
  LoadResult r = loadText(xml);
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(show(objects(r)), "<objects><sphere name=\"s\" mass=\"2\"><dim radius=\"0.5\"/></sphere></objects>");
  EXPECT_EQ(r.root->child("params"), nullptr);  // removed
  r = loadText(xml, {{"r", "0.25"}, {"unused", "7"}});  // an unused --param is fine
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(objects(r).children[0].children[0].attributes[0].value, "0.25");
  // [THIS_DIR] in a --param is the top file's directory.
  r = loadText("<raisim><objects><mesh file_name=\"@@m\"/></objects></raisim>", {{"m", "[THIS_DIR]/a.obj"}});
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(objects(r).children[0].attributes[0].value, "/base/a.obj");
}

TEST(Expand, UnsetParameterNamesItAndHowToSetIt) {
  LoadResult r = loadText("<raisim>\n<objects>\n  <sphere mass=\"@@m\"/>\n</objects>\n</raisim>");
  EXPECT_FALSE(r.ok());
  EXPECT_FALSE(r.root.has_value());
  EXPECT_EQ(errors(r), "w.xml:3:11: <sphere> mass: @@m is not set: define it in <params> or give --param m=VALUE [RS8104]\n");
}

TEST(Expand, EveryUnsetParameterIsNamedAtOnce) {
  // RaiSim's spheres.xml: sphere_count bounds the array, so its children's
  // spawn_sphere and spawn_box were only reported once it was given.
  LoadResult r = loadText(R"(<raisim><params><sphere_height_offset value="1"/></params><objects>
  <array idx="@@idx" start="0" end="@@sphere_count" increment="1">
    <sphere name="s@@idx" mass="1" exist="@@spawn_sphere"><dim radius="{0.5+@@idx*0.001}"/></sphere>
    <box name="b@@idx" mass="@@spawn_sphere" exist="@@spawn_box"><dim x="1" y="1" z="{@@sphere_height_offset}"/></box>
  </array></objects></raisim>)");
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(errors(r),
            "w.xml:2:32: <array> end: @@sphere_count is not set: define it in <params> or give --param "
            "sphere_count=VALUE [RS8104]\n"
            "w.xml:3:36: <sphere> exist: @@spawn_sphere is not set: define it in <params> or give --param "
            "spawn_sphere=VALUE [RS8104]\n"
            "w.xml:4:46: <box> exist: @@spawn_box is not set: define it in <params> or give --param "
            "spawn_box=VALUE [RS8104]\n");
}

TEST(Expand, LongestNameIsSubstituted) {
  std::string xml = R"(<raisim><params><idx value="1"/><idx2 value="22"/></params>
  <objects><box name="@@idx2 @@idx @@idx_x @@idx3"/></objects></raisim>)";
  LoadResult r = loadText(xml);
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(objects(r).children[0].attributes[0].value, "22 1 1_x 13");
}

TEST(Expand, ParameterValuesMaySubstituteButNotCycle) {
  std::string xml = R"(<raisim><params><a value="@@b+1"/><b value="{2*@@c}"/><c value="3"/></params>
  <objects><box mass="{@@a}"/></objects></raisim>)";
  LoadResult r = loadText(xml);
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(objects(r).children[0].attributes[0].value, "7");
  r = loadText(R"(<raisim><params><a value="x@@b"/><b value="@@a"/></params><objects><box mass="@@a"/></objects></raisim>)");
  EXPECT_NE(errors(r).find("@@a is defined from itself (a -> b -> a) [RS8104]"), std::string::npos) << errors(r);
}

TEST(Expand, ArrayEndIsExclusiveAndRemoved) {
  LoadResult r = loadText(R"(<raisim><objects>
  <array idx="@@i" start="0" end="3" increment="1"><sphere name="s@@i"/></array>
  <array idx="@@j" start="10" end="0" increment="-4"><box name="b@@j"/></array>
  <array idx="@@k" start="5" end="5" increment="1"><box name="never"/></array>
  <array idx="@@k" start="0" end="7" increment="3"><cylinder name="c@@k"/></array>
</objects></raisim>)");
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(show(objects(r)),
            "<objects><sphere name=\"s0\"/><sphere name=\"s1\"/><sphere name=\"s2\"/>"
            "<box name=\"b10\"/><box name=\"b6\"/><box name=\"b2\"/>"
            "<cylinder name=\"c0\"/><cylinder name=\"c3\"/><cylinder name=\"c6\"/></objects>");
}

TEST(Expand, NestedArraysSeeBothVariables) {
  LoadResult r = loadText(R"(<raisim><params><n value="2"/></params><objects>
  <array idx="@@i" start="0" end="@@n" increment="1">
    <array idx="@@j" start="0" end="{@@i+1}" increment="1"><box name="b@@i_@@j" mass="{@@i*10+@@j}"/></array>
  </array>
</objects></raisim>)");
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(show(objects(r)),
            "<objects><box name=\"b0_0\" mass=\"0\"/><box name=\"b1_0\" mass=\"10\"/><box name=\"b1_1\" mass=\"11\"/></objects>");
}

TEST(Expand, ArrayErrors) {
  auto first = [](const std::string& array) {
    LoadResult r = loadText("<raisim><objects>" + array + "<box/></array></objects></raisim>");
    EXPECT_FALSE(r.ok());
    return r.diagnostics.empty() ? std::string() : r.diagnostics[0].message + " [" + r.diagnostics[0].code + "]";
  };
  EXPECT_EQ(first(R"(<array idx="@@i" start="0" end="3" increment="0">)"),
            "<array> increment: increment 0 never reaches end 3 from start 0 (end is exclusive) [RS8106]");
  EXPECT_EQ(first(R"(<array idx="@@i" start="0" end="3" increment="-1">)"),
            "<array> increment: increment -1 never reaches end 3 from start 0 (end is exclusive) [RS8106]");
  EXPECT_EQ(first(R"(<array idx="@@i" start="0" end="2.5" increment="1">)"),
            "<array> end: '2.5' is not an integer [RS8106]");
  EXPECT_EQ(first(R"(<array idx="@@i" start="0" increment="1">)"),
            "<array>: no end (an array needs idx, start, end and increment) [RS8106]");
  EXPECT_EQ(first(R"(<array idx="i j" start="0" end="1" increment="1">)"),
            "<array> idx: 'i j' is not a variable name (write idx=\"@@i\") [RS8106]");
}

TEST(Expand, ExpressionsInValuesAndTheirErrors) {
  LoadResult r = loadText(R"(<raisim><objects><array idx="@@i" start="0" end="2" increment="1">
  <sphere><state pos="{@@i*0.5} {1+@@i} 3"/></sphere></array></objects></raisim>)");
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(objects(r).children[1].children[0].attributes[0].value, "0.5 2 3");
  r = loadText("<raisim><objects><array idx=\"@@i\" start=\"0\" end=\"5\" increment=\"1\">\n"
               "  <sphere><dim radius=\"{1/(@@i-3)}\"/></sphere></array></objects></raisim>");
  // The first failing iteration is reported once, with the loop variable.
  EXPECT_EQ(errors(r), "w.xml:2:16: <dim> radius: {1/(3-3)}: division by zero (in array iteration i=3) [RS8105]\n");
}

TEST(Expand, ExistKeepsOrRemoves) {
  std::string xml = R"(<raisim><params><on value="true"/></params><objects>
  <sphere name="a" exist="@@on"/><sphere name="b" exist="false"/><sphere name="c" exist="1"/>
  <sphere name="d" exist="0"><dim radius="@@unset"/></sphere>
  <array idx="@@i" start="0" end="4" increment="1"><box name="b@@i" exist="{(2*@@i*@@i*@@i-9*@@i*@@i+10*@@i)/3}"/></array>
</objects></raisim>)";
  LoadResult r = loadText(xml);
  ASSERT_TRUE(r.ok()) << errors(r);
  // exist is read first, so a removed element's other values are not needed.
  EXPECT_EQ(show(objects(r)), "<objects><sphere name=\"a\"/><sphere name=\"c\"/><box name=\"b1\"/><box name=\"b3\"/></objects>");
  r = loadText(xml, {{"on", "no"}});
  EXPECT_EQ(errors(r), "w.xml:2:20: <sphere> exist: 'no' is not true, false, 1 or 0 [RS8108]\n");
  r = loadText("<raisim exist=\"false\"><objects/></raisim>");
  EXPECT_EQ(errors(r), "w.xml:1:1: <raisim>: exist removes the whole world [RS8108]\n");
}

TEST(Expand, IncludesWithThisDirFromASubdirectory) {
  LoadResult r = loadWorld(kData + "/include_top.xml", {});
  ASSERT_TRUE(r.ok()) << errors(r);
  std::string subDir = std::filesystem::absolute(kData + "/sub").lexically_normal().string();
  EXPECT_EQ(show(*r.root),
            "<raisim version=\"1.0\"><objects><ground name=\"floor\" height=\"-2\"/>"
            "<sphere name=\"top_ball\" mass=\"1\"><dim radius=\"0.5\"/><state pos=\"0 0 1\"/></sphere>"
            "<mesh name=\"rock\" mass=\"3\" file_name=\"" + subDir + "/rock.obj\" scale=\"1 1 1\"/></objects>"
            "<gravity value=\"0 0 -1.62\"/></raisim>");
  ASSERT_EQ(r.files.size(), 3u);
  EXPECT_EQ(r.files[1], kData + "/sub/terrain.xml");
  // An element keeps the file it was written in.
  EXPECT_EQ(objects(r).children[0].where.file, kData + "/sub/terrain.xml");
  EXPECT_EQ(objects(r).children[0].where.line, 8u);
  EXPECT_EQ(objects(r).children[0].where.column, 9u);
  EXPECT_EQ(objects(r).children[0].attributes[1].where.column, 30u);  // height
  // --param wins over both files' params.
  LoadOptions options;
  options.params = {{"floor_height", "5"}};
  r = loadWorld(kData + "/include_top.xml", options);
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(objects(r).children[0].attributes[1].value, "5");
}

TEST(Expand, IncludeErrors) {
  LoadResult r = loadWorld(kData + "/cycle_a.xml", {});
  EXPECT_FALSE(r.ok());
  ASSERT_EQ(r.diagnostics.size(), 1u) << errors(r);
  EXPECT_EQ(r.diagnostics[0].file, kData + "/cycle_b.xml");
  EXPECT_EQ(r.diagnostics[0].message, "<include> file: include cycle: " + kData + "/cycle_a.xml -> " + kData +
                                          "/cycle_b.xml -> " + kData + "/cycle_a.xml");
  EXPECT_EQ(r.diagnostics[0].code, "RS8103");
  r = loadText("<raisim><include file=\"missing.xml\"/></raisim>");
  EXPECT_EQ(errors(r).rfind("w.xml:1:18: <include> file: cannot read '/base/missing.xml': ", 0), 0u) << errors(r);
  r = loadText("<raisim><objects><sphere><include file=\"x.xml\"/></sphere></objects></raisim>");
  EXPECT_EQ(errors(r), "w.xml:1:26: <include>: belongs directly under <raisim> or <objects> [RS8103]\n");
  r = loadText("<raisim><include name=\"x.xml\"/></raisim>");
  EXPECT_EQ(errors(r), "w.xml:1:9: <include>: no file (write <include value=\"...\"/>) [RS8103]\n");
  r = loadText("<raisim><include file=\"x.xml\" exist=\"false\"/></raisim>");  // not read at all
  EXPECT_TRUE(r.ok()) << errors(r);
}

// A cycle reached through another include is named from the top file on.
TEST(Expand, IncludeCycleIsNamedFromTheTopFile) {
  LoadResult r = loadText("<raisim>\n<include file=\"" + kData + "/cycle_b.xml\"/>\n</raisim>");
  EXPECT_FALSE(r.ok());
  ASSERT_EQ(r.diagnostics.size(), 1u) << errors(r);
  EXPECT_EQ(r.diagnostics[0].message, "<include> file: include cycle: w.xml -> " + kData + "/cycle_b.xml -> " +
                                          kData + "/cycle_a.xml -> " + kData + "/cycle_b.xml");
}

TEST(Expand, SeveralObjectsAndMaterialsMerge) {
  LoadResult r = loadText(R"(<raisim><objects><sphere name="a"/></objects><material><default friction="1"/></material>
  <objects><box name="b"/></objects><material><pair_prop name1="x" name2="y"/></material></raisim>)");
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(show(*r.root), "<raisim><objects><sphere name=\"a\"/><box name=\"b\"/></objects><material>"
                           "<default friction=\"1\"/><pair_prop name1=\"x\" name2=\"y\"/></material></raisim>");
}

TEST(Expand, ObjectClassSphereMeshCompoundArticulated) {
  std::string xml = R"(<raisim>
  <object_class>
    <ball type="sphere" mass="1" material="steel">
      <dimension radius="@@r"/>
      <inertia xx="0.1" xy="0" xz="0" yy="0.1" yz="0" zz="0.1"/>
    </ball>
    <rock type="mesh" mass="2" com="0 0 0">
      <file name="[THIS_DIR]/rock.obj"/>
      <scale x="1" y="2" z="{1+2}"/>
    </rock>
    <cart type="compound" mass="10" com="0 0 0">
      <children>
        <box object_param="1 0.5 0.2" pos="0 0 0"/>
        <sphere object_param="0.1" pos="0.5 0 -0.1" quat="1 0 0 0" material="rubber"/>
        <cylinder object_param="0.1 0.3" pos="0 0 1"/>
      </children>
    </cart>
    <dog type="articulated_system" urdf_path="[THIS_DIR]/anymal.urdf" res_dir="[THIS_DIR]"/>
  </object_class>
  <params><r value="0.5"/></params>
  <objects>
    <ball name="b@@i_unused" exist="false"/>
    <array idx="@@i" start="0" end="2" increment="1">
      <ball name="ball@@i" mass="{1+@@i}"><state pos="@@i 0 1"/></ball>
    </array>
    <rock name="rock" scale="3 3 3"><state pos="0 0 2"/></rock>
    <cart name="cart"><state pos="0 0 3"/></cart>
    <dog name="dog"><state qpos="0 0 0.5 1 0 0 0"/></dog>
  </objects>
</raisim>)";
  LoadResult r = loadText(xml);
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(r.root->child("object_class"), nullptr);
  const Element& o = objects(r);
  ASSERT_EQ(o.children.size(), 5u) << show(o);
  EXPECT_EQ(show(o.children[0]),
            "<sphere mass=\"1\" material=\"steel\" name=\"ball0\"><dim radius=\"0.5\"/>"
            "<inertia xx=\"0.1\" xy=\"0\" xz=\"0\" yy=\"0.1\" yz=\"0\" zz=\"0.1\"/><state pos=\"0 0 1\"/></sphere>");
  EXPECT_EQ(o.children[1].attribute("mass")->value, "2");  // the instance wins
  EXPECT_EQ(o.children[1].where.line, 24u);                // where the instance is
  EXPECT_EQ(show(o.children[2]),
            "<mesh mass=\"2\" com=\"0 0 0\" file_name=\"/base/rock.obj\" scale=\"3 3 3\" name=\"rock\"><state pos=\"0 0 2\"/></mesh>");
  EXPECT_EQ(show(o.children[3]),
            "<compound mass=\"10\" com=\"0 0 0\" name=\"cart\"><children>"
            "<box><dim x=\"1\" y=\"0.5\" z=\"0.2\"/><state pos=\"0 0 0\"/></box>"
            "<sphere material=\"rubber\"><dim radius=\"0.1\"/><state pos=\"0.5 0 -0.1\" quat=\"1 0 0 0\"/></sphere>"
            "<cylinder><dim radius=\"0.1\" height=\"0.3\"/><state pos=\"0 0 1\"/></cylinder>"
            "</children><state pos=\"0 0 3\"/></compound>");
  EXPECT_EQ(show(o.children[4]),
            "<articulated_system urdf_path=\"/base/anymal.urdf\" res_dir=\"/base\" name=\"dog\">"
            "<state qpos=\"0 0 0.5 1 0 0 0\"/></articulated_system>");
  // Without the instance's own scale, the class's <scale> gives it.
  r = loadText(std::string(xml).replace(xml.find(" scale=\"3 3 3\""), 14, ""));
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(objects(r).children[2].attribute("scale")->value, "1 2 3");
}

TEST(Expand, ObjectClassErrors) {
  auto first = [](const std::string& classes, const std::string& objects) {
    LoadResult r = loadText("<raisim><object_class>" + classes + "</object_class><objects>" + objects + "</objects></raisim>");
    EXPECT_FALSE(r.ok());
    return r.diagnostics.empty() ? std::string() : r.diagnostics[0].message + " [" + r.diagnostics[0].code + "]";
  };
  EXPECT_EQ(first("<c mass=\"1\"/>", "<c/>"), "<c>: no type (the element the class stands for: sphere, box, mesh ...) [RS8109]");
  EXPECT_EQ(first("<sphere type=\"box\"/>", ""), "<sphere>: a class may not take the name of an element of the format [RS8109]");
  EXPECT_EQ(first("<c type=\"box\"/><c type=\"box\"/>", ""), "<c>: class defined twice (first at w.xml:1) [RS8109]");
  EXPECT_EQ(first("<c type=\"compound\"><children><box object_param=\"1 2\" pos=\"0 0 0\"/></children></c>", "<c/>"),
            "<box> object_param: a box takes 3 numbers (x y z), found 2 [RS8109]");
  EXPECT_EQ(first("<c type=\"compound\"><children><cone object_param=\"1\" pos=\"0 0 0\"/></children></c>", "<c/>"),
            "<cone>: a compound class's child is a sphere, box, capsule or cylinder [RS8109]");
}

TEST(Expand, TemplatedSpheresExample) {
  const std::string path = kExamples + "/spheres.xml";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  LoadOptions options;
  options.params = {{"sphere_count", "20"}, {"spawn_sphere", "true"}, {"spawn_box", "false"},
                    {"sphere_height_offset", "0.1"}};
  LoadResult r = loadWorld(path, options);
  ASSERT_TRUE(r.ok()) << errors(r);
  std::vector<const Element*> spheres = childrenNamed(objects(r), "sphere");
  ASSERT_EQ(spheres.size(), 20u);
  EXPECT_TRUE(childrenNamed(objects(r), "box").empty());
  for (int i = 0; i < 20; ++i) {
    const Element& s = *spheres[i];
    EXPECT_EQ(s.attribute("name")->value, "sphere_array_" + std::to_string(i));
    EXPECT_EQ(s.attribute("exist"), nullptr);
    double radius = std::stod(s.child("dim")->attribute("radius")->value);
    EXPECT_DOUBLE_EQ(radius, 0.5 + i * 0.001);
  }
  std::vector<double> pos;
  std::istringstream words(spheres[7]->child("state")->attribute("pos")->value);
  for (double v; words >> v;) pos.push_back(v);
  ASSERT_EQ(pos.size(), 3u);
  EXPECT_DOUBLE_EQ(pos[0], std::cos(0.1 * 7) * (7 * 0.2 + 0.1));
  EXPECT_DOUBLE_EQ(pos[1], std::sin(0.1 * 7) * (7 * 0.2 + 0.1));
  EXPECT_DOUBLE_EQ(pos[2], 0.1 + 7 * 1.0);

  options.params["spawn_sphere"] = "false";
  options.params["spawn_box"] = "true";
  r = loadWorld(path, options);
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_TRUE(childrenNamed(objects(r), "sphere").empty());
  EXPECT_EQ(childrenNamed(objects(r), "box").size(), 20u);

  options.params.erase("sphere_count");
  r = loadWorld(path, options);
  EXPECT_NE(errors(r).find("<array> end: @@sphere_count is not set: define it in <params> or give --param "
                           "sphere_count=VALUE [RS8104]"),
            std::string::npos)
      << errors(r);
}

TEST(Expand, SingleBodiesExample) {
  const std::string path = kExamples + "/SingleBodies.xml";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  LoadResult r = loadWorld(path, {});
  ASSERT_TRUE(r.ok()) << errors(r);
  // start=0 end=80: 80 iterations (end exclusive), plus the lone sphere and box.
  EXPECT_EQ(childrenNamed(objects(r), "sphere").size(), 81u);
  EXPECT_EQ(childrenNamed(objects(r), "box").size(), 81u);
  EXPECT_EQ(childrenNamed(objects(r), "sphere")[79]->attribute("name")->value, "sphere_array_79");
  std::string dir = std::filesystem::absolute(kExamples).lexically_normal().string();
  EXPECT_EQ(objects(r).child("mesh")->attribute("file_name")->value, dir + "/../../monkey/monkey.obj");
  EXPECT_EQ(r.root->child("params"), nullptr);
  EXPECT_NE(r.root->child("time_step"), nullptr);
}

TEST(Expand, EveryExampleExpands) {
  if (!std::filesystem::exists(kExamples)) GTEST_SKIP() << "no " << kExamples;
  LoadOptions options;
  options.params = {{"sphere_count", "3"}, {"spawn_sphere", "true"}, {"spawn_box", "true"},
                    {"sphere_height_offset", "0.1"}};
  for (const auto& entry : std::filesystem::directory_iterator(kExamples)) {
    LoadResult r = loadWorld(entry.path().string(), options);
    EXPECT_TRUE(r.ok()) << entry.path() << "\n" << errors(r);
  }
}

}  // namespace
}  // namespace rscene::xml

namespace rscene::xml {
namespace {

// RaiSim's own templated world (rsc/xmlScripts/templatedWorld): top-level
// <include value="..."/> of whole worlds whose objects join the includer's,
// a parameter that only --param sets.
TEST(Expand, RaisimTemplatedWorldForm) {
  std::string top = std::string(RSCENE_TEST_DATA) + "/xml/templated/world.xml";
  LoadResult r = loadWorld(top, {});
  ASSERT_FALSE(r.ok());
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_NE(r.diagnostics[0].message.find("@@start_x is not set"), std::string::npos) << r.diagnostics[0].message;
  LoadOptions options;
  options.params = {{"start_x", "2"}};
  r = loadWorld(top, options);
  ASSERT_TRUE(r.ok()) << (r.diagnostics.empty() ? "" : r.diagnostics[0].message);
  const Element* objects = r.root->child("objects");
  ASSERT_NE(objects, nullptr);
  ASSERT_EQ(objects->children.size(), 2u);
  EXPECT_EQ(objects->children[0].name, "ground");
  EXPECT_EQ(objects->children[0].attribute("height")->value, "0.25");
  EXPECT_EQ(objects->children[1].child("state")->attribute("pos")->value, "2, 0, 1");
}

}  // namespace
}  // namespace rscene::xml

namespace rscene::xml {
namespace {

// The world file and its includes come through LoadOptions::files: a world
// held in memory loads, and a file only on the disk is not seen.
TEST(Expand, WorldAndIncludesReadThroughTheInjectedFiles) {
  MemoryFileSystem files;
  files.addFile("/mem/world.xml", "<raisim>\n  <objects>\n    <include file=\"[THIS_DIR]/part.xml\"/>\n  </objects>\n</raisim>\n");
  files.addFile("/mem/part.xml",
                "<raisim><objects><sphere name=\"s\" mass=\"1\"><dim radius=\"0.5\"/></sphere></objects></raisim>\n");
  LoadOptions options;
  options.files = &files;
  LoadResult r = loadWorld("/mem/world.xml", options);
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(objects(r).children.size(), 1u);
  EXPECT_EQ(r.files, (std::vector<std::string>{"/mem/world.xml", "/mem/part.xml"}));
  r = loadWorld(kData + "/include_top.xml", options);
  EXPECT_FALSE(r.ok());
}

}  // namespace
}  // namespace rscene::xml
