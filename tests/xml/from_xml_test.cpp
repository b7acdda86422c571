// rscene-from-xml's mapping (from_xml.hpp): every element kind and value
// notation becomes the record the mapping table says, bad values are
// errors at their file and line, what has no field is reported.
#include <gtest/gtest.h>

#include <filesystem>
#include <cmath>
#include <fstream>

#include "asset/image.hpp"
#include "core/loader.hpp"
#include "xml/from_xml.hpp"
#include "xml/xml_tree.hpp"

namespace rscene::xml {
namespace {

namespace fs = std::filesystem;

FromXmlResult convert(const std::string& xml, FromXmlOptions options = {}) {
  LoadResult loaded = loadWorldText(xml, "w.xml", ".", {});
  EXPECT_TRUE(loaded.ok()) << (loaded.diagnostics.empty() ? "" : loaded.diagnostics[0].message);
  if (!loaded.ok()) return {};
  return worldToScene(*loaded.root, options);
}

std::string world(const std::string& objects, const std::string& rest = "") {
  return "<raisim version=\"1.0\">\n<objects>\n" + objects + "\n</objects>\n" + rest + "</raisim>\n";
}

// The record lines after the three physics records.
std::string bodies(const FromXmlResult& r) {
  std::string out;
  std::size_t start = 0;
  while (start < r.text.size()) {
    std::size_t end = r.text.find('\n', start);
    std::string line = r.text.substr(start, end - start);
    if (line.rfind("raisim_engine_scene", 0) && line.rfind("time_step", 0) && line.rfind("gravity", 0) &&
        line.rfind("solver", 0))
      out += line + '\n';
    start = end + 1;
  }
  return out;
}

const Diagnostic* find(const FromXmlResult& r, const std::string& code) {
  for (const Diagnostic& d : r.diagnostics)
    if (d.code == code) return &d;
  return nullptr;
}

constexpr const char* kAll = "18446744073709551615";

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += x + "; ";
  return s;
}

TEST(FromXml, EmptyWorldGetsRaisimDefaultsWrittenExplicitly) {
  FromXmlResult r = convert("<raisim version=\"1.0\"><objects/></raisim>");
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.text,
            "raisim_engine_scene 1\ntime_step 0.005\ngravity 0 0 -9.81\n"
            "solver 80 1e-07 0.2 accurate erp2=0 defaultFriction=0.8 defaultRestitution=0 "
            "defaultRestitutionThreshold=0\n");
  EXPECT_TRUE(r.notConverted.empty());
}

TEST(FromXml, PhysicsSettingsAndMaterials) {
  FromXmlResult r = convert(
      "<raisim version=\"1.0\"><time_step value=\"0.002\"/><gravity value=\"0 0 -3.5\"/>"
      "<erp erp=\"0.3\" erp2=\"0.1\"/><objects/>"
      "<material><default friction=\"0.6\" restitution=\"0.1\" restitution_threshold=\"0.2\"/>"
      "<pair_prop name1=\"steel\" name2=\"rubber\" friction=\"0.9\" restitution=\"0.5\" restitution_threshold=\"0.01\"/>"
      "<pair_prop name1=\"a\" name2=\"b\" friction=\"0.9\" restitution=\"0\" restitution_threshold=\"0\" "
      "static_friction=\"1.1\" static_friction_velocity_threshold=\"0.002\" rolling_friction=\"0.05\" "
      "spinning_friction=\"0.02\"/></material></raisim>");
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.text,
            "raisim_engine_scene 1\ntime_step 0.002\ngravity 0 0 -3.5\n"
            "solver 80 1e-07 0.3 accurate erp2=0.1 defaultFriction=0.6 defaultRestitution=0.1 "
            "defaultRestitutionThreshold=0.2\n"
            "contact_material steel rubber 0.9 0.5 0.01 0.9 0.001 0 0\n"
            "contact_material a b 0.9 0 0 1.1 0.002 0.05 0.02\n");
}

TEST(FromXml, TimeStepCamelCase) {
  FromXmlResult r = convert("<raisim><timeStep value=\"0.001\"/><objects/></raisim>");
  ASSERT_TRUE(r.ok());
  EXPECT_NE(r.text.find("time_step 0.001\n"), std::string::npos);
}

TEST(FromXml, PrimitivesWithStateInertiaAndModes) {
  FromXmlResult r = convert(world(
      "<sphere name=\"ball\" mass=\"2\" material=\"rubber\"><dim radius=\"0.5\"/>"
      "<state pos=\"1 2 3\" quat=\"0 1 0 0\"/></sphere>\n"
      "<capsule name=\"cap\" mass=\"1\" body_type=\"kinematic\"><dim radius=\"0.2\" height=\"1\"/></capsule>\n"
      "<cylinder name=\"cyl\" mass=\"1\"><dim radius=\"0.3\" height=\"0.4\"/>"
      "<inertia xx=\"1\" xy=\"0\" xz=\"0\" yy=\"2\" yz=\"0\" zz=\"3\"/></cylinder>\n"
      "<box name=\"crate\" body_type=\"static\"><dim x=\"0.5\" y=\"1\" z=\"2\"/></box>"));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(bodies(r),
            std::string("object /World/ball sphere 1 2 3 0 1 0 0 1 1 1 0.5 0 2 rubber - false true false - dynamic true 1 ") +
                kAll + "\n" +
                "object /World/cap capsule 0 0 0 1 0 0 0 1 1 1 0.2 1 1 default - false true false - kinematic true 1 " +
                kAll + "\n" +
                "object /World/cyl cylinder 0 0 0 1 0 0 0 1 1 1 0.3 0.4 1 default - false true false - dynamic true 1 " +
                kAll + " customInertia=true inertiaDiagonal=1,2,3\n" +
                "object /World/crate box 0 0 0 1 0 0 0 0.5 1 2 0 0 0 default - false true false - static true 1 " +
                kAll + "\n");
}

TEST(FromXml, CollisionGroupNotations) {
  FromXmlResult r = convert(world(
      "<sphere name=\"a\" mass=\"1\" collision_group=\"collision[1|4|6]\" collision_mask=\"-1\"><dim radius=\"1\"/></sphere>"
      "<sphere name=\"b\" mass=\"1\" collisionGroup=\"5\" collisionMask=\"collision[-1]\"><dim radius=\"1\"/></sphere>"
      "<sphere name=\"c\" mass=\"1\" collision_group=\"collision[0]\" collision_mask=\"18446744073709551614\">"
      "<dim radius=\"1\"/></sphere>"));
  ASSERT_TRUE(r.ok());
  std::string b = bodies(r);
  EXPECT_NE(b.find("/World/a sphere 0 0 0 1 0 0 0 1 1 1 1 0 1 default - false true false - dynamic true 82 " +
                   std::string(kAll)),
            std::string::npos)
      << b;  // 0b1010010
  EXPECT_NE(b.find("dynamic true 5 " + std::string(kAll)), std::string::npos) << b;
  EXPECT_NE(b.find("dynamic true 1 18446744073709551614"), std::string::npos) << b;
}

TEST(FromXml, BadCollisionGroupIsAnErrorAtItsLine) {
  for (const char* bad : {"collision[64]", "collision[1|x]", "collision[2", "-9223372036854775809", "1.5", "-1.5",
                          "18446744073709551616", "abc", "-"}) {
    FromXmlResult r = convert(world(std::string("<sphere mass=\"1\"\n collision_mask=\"") + bad +
                                    "\"><dim radius=\"1\"/></sphere>"));
    ASSERT_FALSE(r.ok()) << bad;
    const Diagnostic* d = find(r, "RS8110");
    ASSERT_NE(d, nullptr) << bad;
    EXPECT_EQ(d->file, "w.xml");
    // The attribute's own line (4) where the reader knows attribute places
    // (it then knows columns too), else its element's (3).
    EXPECT_EQ(d->line, d->column ? 4u : 3u) << bad;
    EXPECT_EQ(d->message.rfind("<sphere> collision_mask: '", 0), 0u) << d->message;
    EXPECT_TRUE(r.text.empty());
  }
}

TEST(FromXml, ErrorsAtTheAttributeOrElementColumn) {
  std::string line = "  <sphere name=\"a\" mass=\"x\"><dim/></sphere>";
  FromXmlResult r = convert(world("\n" + line));
  const Diagnostic* bad = find(r, "RS8110");
  const Diagnostic* missing = find(r, "RS8112");
  ASSERT_NE(bad, nullptr);
  ASSERT_NE(missing, nullptr);
  EXPECT_EQ(bad->file, "w.xml");
  EXPECT_EQ(bad->line, 4u);
  EXPECT_EQ(bad->column, line.find("mass=") + 1);  // the attribute's name
  EXPECT_EQ(missing->line, 4u);
  EXPECT_EQ(missing->column, line.find("<dim") + 1);  // the element's '<'
  EXPECT_EQ(missing->message, "<dim>: 'radius' is required");
}

TEST(FromXml, NumbersMustBeFiniteAndVectorsExact) {
  FromXmlResult nan = convert(world("<sphere mass=\"nan\"><dim radius=\"1\"/></sphere>"));
  ASSERT_NE(find(nan, "RS8110"), nullptr);
  EXPECT_EQ(find(nan, "RS8110")->message, "<sphere> mass: 'nan' is not a finite number");
  FromXmlResult shortPos = convert(world("<sphere mass=\"1\"><dim radius=\"1\"/><state pos=\"1 2\"/></sphere>"));
  ASSERT_NE(find(shortPos, "RS8110"), nullptr);
  EXPECT_EQ(find(shortPos, "RS8110")->message, "<state> pos: expected 3 numbers, found 2");
  FromXmlResult mode = convert(world("<sphere mass=\"1\" body_type=\"frozen\"><dim radius=\"1\"/></sphere>"));
  ASSERT_NE(find(mode, "RS8110"), nullptr);
  EXPECT_EQ(find(mode, "RS8110")->message, "<sphere> body_type: 'frozen' is not dynamic, kinematic or static");
}

TEST(FromXml, MissingRequiredPartsAreErrorsAtTheElement) {
  struct Case {
    const char* xml;
    const char* message;
  } cases[] = {
      {"<sphere mass=\"1\"><dim/></sphere>", "<dim>: 'radius' is required"},
      {"<sphere mass=\"1\"/>", "<sphere>: <dim> is required"},
      {"<box mass=\"1\"><dim x=\"1\" y=\"1\"/></box>", "<dim>: 'z' is required"},
      {"<mesh mass=\"1\"/>", "<mesh>: 'file_name' is required"},
      {"<sphere><dim radius=\"1\"/></sphere>", "<sphere>: 'mass' is required for a dynamic body"},
      {"<heightmap center_x=\"0\" center_y=\"0\" x_sample=\"2\" y_sample=\"2\" x_size=\"1\" height=\"0 0 0 0\"/>",
       "<heightmap>: 'y_size' is required"},
      {"<articulatedSystem name=\"r\"/>", "<articulatedSystem>: 'urdf_path' is required"},
  };
  for (const Case& c : cases) {
    FromXmlResult r = convert(world(std::string("\n") + c.xml));
    const Diagnostic* d = find(r, "RS8112");
    ASSERT_NE(d, nullptr) << c.xml;
    EXPECT_EQ(d->message, c.message);
    EXPECT_EQ(d->file, "w.xml");
    EXPECT_EQ(d->line, 4u) << c.xml;
  }
}

TEST(FromXml, EmptyFilePathsAreErrors) {
  for (const char* xml : {"<mesh mass=\"1\" file_name=\"\"/>", "<articulatedSystem urdf_path=\" \"/>"}) {
    FromXmlResult r = convert(world(xml));
    ASSERT_NE(find(r, "RS8110"), nullptr) << xml;
    EXPECT_NE(find(r, "RS8110")->message.find(": is empty: a file is required"), std::string::npos);
  }
}

TEST(FromXml, UnknownElementsAndAttributesAreWarnedAndListed) {
  FromXmlResult r = convert(world("<sphere name=\"s\" mass=\"1\" colour=\"red\" appearance=\"blue\"><dim radius=\"1\"/>"
                                  "<state pos=\"0 0 1\" lin_vel=\"1 0 0\" ang_vel=\"0 0 0\"/>"
                                  "<inertia xx=\"1\" xy=\"0.5\" xz=\"0\" yy=\"1\" yz=\"0\" zz=\"1\"/></sphere>"
                                  "<teapot/>",
                                  "<camera follow=\"s\"/>"));
  ASSERT_TRUE(r.ok());
  int warnings = 0;
  for (const Diagnostic& d : r.diagnostics) warnings += d.code == "RS8111";
  EXPECT_EQ(warnings, 2);  // colour, teapot; appearance and camera are known to have no field
  std::vector<std::string> want = {"raisim: <camera>", "sphere 's': colour", "sphere 's': appearance",
                                   "sphere 's': lin_vel", "sphere 's': inertia xy", "<teapot>"};
  for (const std::string& w : want)
    EXPECT_NE(std::find(r.notConverted.begin(), r.notConverted.end(), w), r.notConverted.end()) << w;
  EXPECT_EQ(r.notConverted.size(), want.size());
}

TEST(FromXml, NamesBecomePathsAndRepeatsAreRenamed) {
  FromXmlResult r = convert(world("<sphere name=\"box\" mass=\"1\"><dim radius=\"1\"/></sphere>"
                                  "<box name=\"box\" mass=\"1\"><dim x=\"1\" y=\"1\" z=\"1\"/></box>"
                                  "<box name=\"box\" mass=\"1\"><dim x=\"1\" y=\"1\" z=\"1\"/></box>"
                                  "<box name=\"/World/Props/crate\" mass=\"1\"><dim x=\"1\" y=\"1\" z=\"1\"/></box>"
                                  "<capsule mass=\"1\"><dim radius=\"1\" height=\"1\"/></capsule>"
                                  "<box name=\"a b\" mass=\"1\"><dim x=\"1\" y=\"1\" z=\"1\"/></box>"));
  ASSERT_TRUE(r.ok());
  std::string b = bodies(r);
  for (const char* path : {"object /World/box sphere", "object /World/box_2 box", "object /World/box_3 box",
                           "object /World/Props/crate box", "object /World/capsule capsule", "object /World/a%20b box"})
    EXPECT_NE(b.find(path), std::string::npos) << path << "\n" << b;
  const Diagnostic* d = find(r, "RS8113");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->severity, Severity::Warning);
  EXPECT_EQ(d->message, "<raisim>: repeated names made unique: /World/box -> /World/box_2, /World/box_3");
}

TEST(FromXml, GroundAndMesh) {
  fs::path dir = fs::temp_directory_path() / "rscene_from_xml_mesh";
  fs::create_directories(dir / "meshes");
  FromXmlOptions options;
  options.outputDir = dir.string();
  std::string mesh = (dir / "meshes" / "m.obj").string();
  FromXmlResult r = convert(world("<ground name=\"floor\" height=\"-0.5\" material=\"steel\" collision_mask=\"collision[0|1]\"/>"
                                  "<mesh name=\"m\" mass=\"3\" file_name=\"" + mesh +
                                  "\" scale=\"1 2 3\" com=\"0 0 0.1\"><state pos=\"0 0 1\"/></mesh>"),
                            options);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(bodies(r), "object /World/floor ground 0 0 -0.5 1 0 0 0 10 10 1 0 0 0 steel - false true false - static true 1 3\n"
                       "object /World/m mesh 0 0 1 1 0 0 0 1 2 3 0 0 3 default - false true false meshes/m.obj dynamic "
                       "true 1 " + std::string(kAll) + " centerOfMass=0,0,0.1\n");
  options.absolutePaths = true;
  FromXmlResult abs = convert(world("<mesh mass=\"3\" file_name=\"" + mesh + "\"/>"), options);
  ASSERT_TRUE(abs.ok());
  EXPECT_NE(abs.text.find(" " + fs::path(mesh).lexically_normal().generic_string() + " dynamic"), std::string::npos)
      << abs.text;
}

TEST(FromXml, CompoundWithChildren) {
  FromXmlResult r = convert(world(
      "<compound name=\"c\" mass=\"10\" com=\"0 0 0.1\" material=\"wood\" collision_group=\"2\">"
      "<inertia xx=\"1\" xy=\"0\" xz=\"0\" yy=\"2\" yz=\"0\" zz=\"3\"/><children>"
      "<sphere name=\"s\" mass=\"1\"><dim radius=\"0.2\"/><state pos=\"-0.5 0 0\"/></sphere>"
      "<box material=\"steel\"><dim x=\"0.2\" y=\"0.5\" z=\"0.7\"/><state pos=\"0 0 0.5\" quat=\"0 0 0 1\"/></box>"
      "<capsule><dim radius=\"0.1\" height=\"0.3\"/></capsule>"
      "</children><state pos=\"0 0 10\"/></compound>"));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(bodies(r),
            "compound /World/c 0 0 10 1 0 0 0 1 1 1 10 dynamic true true centerOfMass=0,0,0.1 inertiaDiagonal=1,2,3 "
            "collisionGroup=2 collisionMask=" + std::string(kAll) + " contactMaterial=wood\n"
            "compound_child /World/c sphere -0.5 0 0 1 0 0 0 1 1 1 radius=0.2 contactMaterial=default\n"
            "compound_child /World/c box 0 0 0.5 0 0 0 1 1 1 1 size=0.2,0.5,0.7 contactMaterial=steel\n"
            "compound_child /World/c capsule 0 0 0 1 0 0 0 1 1 1 radius=0.1 height=0.3 contactMaterial=default\n");
  EXPECT_NE(std::find(r.notConverted.begin(), r.notConverted.end(), "compound 'c' <children>: mass"),
            r.notConverted.end());
}

TEST(FromXml, CompoundAndMeshWithoutComHaveNoCenterOfMass) {
  FromXmlResult r = convert(world("<compound name=\"c\" mass=\"1\"><children><box><dim x=\"1\" y=\"1\" z=\"1\"/>"
                                  "</box></children></compound><mesh name=\"m\" mass=\"1\" file_name=\"/m.obj\"/>"));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.text.find("centerOfMass"), std::string::npos) << r.text;
}

TEST(FromXml, HeightmapFromSamples) {
  FromXmlResult r = convert(world("<heightmap name=\"t\" xSample=\"3\" ySample=\"2\" xSize=\"4\" ySize=\"2\" "
                                  "centerX=\"1\" centerY=\"-1\" material=\"dirt\" height=\"0 1 2, 3 4 5\"/>"));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(bodies(r), "terrain_region /World/t 3 2 4 2 1 -1 0 contactMaterial=dirt sourceKind=samples "
                       "heights=0,1,2,3,4,5\n");
  FromXmlResult wrong = convert(world("<heightmap x_sample=\"3\" y_sample=\"2\" x_size=\"4\" y_size=\"2\" "
                                      "center_x=\"0\" center_y=\"0\" height=\"0 1 2\"/>"));
  ASSERT_NE(find(wrong, "RS8110"), nullptr);
  EXPECT_EQ(find(wrong, "RS8110")->message, "<heightmap> height: has 3 numbers, expected x_sample * y_sample = 6");
  FromXmlResult huge = convert(world("<heightmap x_sample=\"100000\" y_sample=\"2\" x_size=\"4\" y_size=\"2\" "
                                     "center_x=\"0\" center_y=\"0\" height=\"0\"/>"));
  EXPECT_NE(find(huge, "RS8110"), nullptr);
}

TEST(FromXml, HeightmapFromTextAndPng) {
  fs::path dir = fs::temp_directory_path() / "rscene_from_xml_terrain";
  fs::create_directories(dir);
  std::ofstream(dir / "h.txt") << "2 2 3 4\n0.5 1\n1.5 2\n";
  asset::Image image;
  image.width = 2;
  image.height = 2;
  image.rgba = {0, 0, 0, 255, 255, 0, 0, 255,  // top row (+y): 0, 255
                51, 0, 0, 255, 102, 0, 0, 255};  // bottom row (y = 0): 51, 102
  std::ofstream(dir / "h.png", std::ios::binary) << asset::encodePng(image);
  FromXmlOptions options;
  options.outputDir = dir.string();
  FromXmlResult r = convert(world("<heightmap name=\"txt\" center_x=\"0\" center_y=\"0\" text=\"" +
                                  (dir / "h.txt").string() + "\"/>"
                                  "<heightmap name=\"png\" center_x=\"0\" center_y=\"0\" x_size=\"5\" y_size=\"6\" "
                                  "z_scale=\"10\" z_offset=\"-1\" png=\"" + (dir / "h.png").string() + "\"/>"),
                            options);
  ASSERT_TRUE(r.ok()) << r.diagnostics[0].message;
  EXPECT_EQ(bodies(r), "terrain_region /World/txt 2 2 3 4 0 0 0 contactMaterial=default sourceKind=samples "
                       "heights=0.5,1,1.5,2\n"
                       "terrain_region /World/png 2 2 5 6 0 0 0 contactMaterial=default sourceKind=png sourcePath=h.png "
                       "pngHeightScale=10 pngHeightOffset=-1 heights=1,3,-1,9\n");
  FromXmlResult missing = convert(world("<heightmap center_x=\"0\" center_y=\"0\" text=\"/nonexistent/h.txt\"/>"));
  ASSERT_NE(find(missing, "RS8114"), nullptr);
  std::ofstream(dir / "bad.txt") << "2 2 3 4\n0.5 1\n";
  FromXmlResult shortText =
      convert(world("<heightmap center_x=\"0\" center_y=\"0\" text=\"" + (dir / "bad.txt").string() + "\"/>"));
  ASSERT_NE(find(shortText, "RS8114"), nullptr);
  EXPECT_NE(find(shortText, "RS8114")->message.find("has 2 heights, expected 4"), std::string::npos);
}

TEST(FromXml, ProceduralHeightmapKeepsParametersAndWarnsOnce) {
  FromXmlResult r = convert(world("<heightmap name=\"p\" x_sample=\"10\" y_sample=\"10\" x_size=\"5\" y_size=\"5\" "
                                  "center_x=\"0\" center_y=\"0\"><terrain_properties frequency=\"0.2\" z_scale=\"3\" "
                                  "fractal_octaves=\"3\" fractal_lacunarity=\"2\" fractal_gain=\"0.25\" step_size=\"0\" "
                                  "height_offset=\"0.5\" seed=\"7\"/></heightmap>"));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(bodies(r), "terrain_region /World/p 10 10 5 5 0 0 0 contactMaterial=default sourceKind=procedural "
                       "proceduralFrequency=0.2 proceduralZScale=3 proceduralOctaves=3 proceduralLacunarity=2 "
                       "proceduralGain=0.25 proceduralStepSize=0 proceduralHeightOffset=0.5 proceduralSeed=7\n");
  int approximate = 0;
  for (const Diagnostic& d : r.diagnostics) approximate += d.code == "RS8113";
  EXPECT_EQ(approximate, 1);
}

// A floating-base robot: base -> (revolute) arm -> (fixed) tip.
// A folder of this test's own: ctest runs tests in parallel processes, and
// two tests rewriting one arm.urdf made a reader see it half-written.
fs::path ownDir(const std::string& stem) {
  return fs::temp_directory_path() /
         (stem + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
}

void writeRobot(const fs::path& file) {
  std::ofstream(file) << R"(<robot name="arm">
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="arm"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="tip"/>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 1"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="tip_joint" type="fixed"><parent link="arm"/><child link="tip"/><origin xyz="0 0 0.5"/></joint>
</robot>
)";
}

TEST(FromXml, ArticulatedSystemAndWireToAFrame) {
  fs::path dir = ownDir("rscene_from_xml_robot");
  fs::create_directories(dir);
  writeRobot(dir / "arm.urdf");
  FromXmlOptions options;
  options.outputDir = dir.string();
  std::string urdf = (dir / "arm.urdf").string();
  FromXmlResult r = convert(
      world("<articulatedSystem name=\"r\" urdf_path=\"" + urdf + "\" res_dir=\"" + dir.string() +
            "\" collision_mask=\"collision[1]\" modules=\"\"><state qpos=\"1, 2, 3, 1, 0, 0, 0, 0.5\" qvel=\"0 0 0 0 0 0 1\"/>"
            "</articulatedSystem>"
            "<articulated_system name=\"r2\" urdfPath=\"" + urdf + "\"/>"
            "<sphere name=\"bob\" mass=\"1\"><dim radius=\"0.1\"/></sphere>",
            "<wire name=\"w\" type=\"compliant\" length=\"2\" stiffness=\"500\" stretch_type=\"STRETCH_RESISTANT_ONLY\">"
            "<object1 name=\"r\" frame=\"tip_joint\" pos=\"0 0 0.1\"/><object2 name=\"bob\" local_index=\"0\" pos=\"0 0 0.1\"/>"
            "</wire>"),
      options);
  ASSERT_TRUE(r.ok()) << r.diagnostics[0].message;
  EXPECT_EQ(bodies(r),
            "articulated_resource res_arm arm arm.urdf\n"
            "object /World/bob sphere 0 0 0 1 0 0 0 1 1 1 0.1 0 1 default - false true false - dynamic true 1 " +
                std::string(kAll) + "\n" +
                "articulated /World/r res_arm 1 2 3 1 0 0 0 true true resourceDirectory=. collisionMask=2 "
                "generalizedCoordinate=1,2,3,1,0,0,0,0.5 generalizedVelocity=0,0,0,0,0,0,1\n"
                "articulated /World/r2 res_arm 0 0 0 1 0 0 0 true true\n"
                "wire /World/w compliant /World/r /World/bob 2 localIndexA=1 localIndexB=0 localPositionA=0,0,0.6 "
                "localPositionB=0,0,0.1 stiffness=500\n");
}

TEST(FromXml, RobotErrorsAndUnreadableRobot) {
  fs::path dir = ownDir("rscene_from_xml_robot");
  fs::create_directories(dir);
  writeRobot(dir / "arm.urdf");
  std::string urdf = (dir / "arm.urdf").string();
  FromXmlResult q = convert(world("<articulatedSystem urdf_path=\"" + urdf + "\"><state qpos=\"0 0 0\"/></articulatedSystem>"));
  ASSERT_NE(find(q, "RS8110"), nullptr);
  EXPECT_EQ(find(q, "RS8110")->message, "<state> qpos: has 3 numbers, the robot has 8");
  FromXmlResult frame = convert(world("<articulatedSystem name=\"r\" urdf_path=\"" + urdf + "\"/>",
                                      "<wire type=\"stiff\" length=\"1\"><object1 name=\"r\" frame=\"nope\"/>"
                                      "<object2 name=\"r\" frame=\"base\"/></wire>"));
  ASSERT_NE(find(frame, "RS8110"), nullptr);
  EXPECT_EQ(find(frame, "RS8110")->message, "<object1> frame: 'r' has no frame named 'nope'");
  FromXmlResult gone = convert(world("<articulatedSystem name=\"r\" urdf_path=\"/nonexistent/x.urdf\">"
                                     "<state qpos=\"0 0 1 1 0 0 0\"/></articulatedSystem>"));
  ASSERT_TRUE(gone.ok());
  ASSERT_NE(find(gone, "RS8113"), nullptr);
  EXPECT_NE(gone.text.find("articulated /World/r res_x 0 0 0 1 0 0 0 true true generalizedCoordinate=0,0,1,1,0,0,0"),
            std::string::npos)
      << gone.text;
  FromXmlResult modules = convert(world("<articulatedSystem name=\"m\" urdfPath=\"/nonexistent/y.urdf\" "
                                        "resDir=\"/nonexistent\" modules=\" a  b \"/><sphere name=\"s\" mass=\"1\">"
                                        "<dim radius=\"1\"/></sphere>",
                                        "<wire type=\"custom\" length=\"1\" stretch_type=\"BOTH\">"
                                        "<object1 name=\"m\" frame=\"hip\"/><object2 name=\"s\"/></wire>"));
  ASSERT_TRUE(modules.ok());
  EXPECT_NE(modules.text.find(" modules=a;b\n"), std::string::npos) << modules.text;
  EXPECT_NE(modules.text.find("wire /World/wire custom /World/m /World/s 1 localIndexA=0"), std::string::npos)
      << modules.text;
  for (const char* lost : {"wire <object1>: frame 'hip' (robot file not read)",
                           "wire: stretch_type BOTH (rscene wires resist stretch only)"})
    EXPECT_NE(std::find(modules.notConverted.begin(), modules.notConverted.end(), lost), modules.notConverted.end())
        << lost;
  FromXmlResult noBody = convert(world("", "<wire type=\"stiff\" length=\"1\"><object1 name=\"a\"/><object2 name=\"b\"/></wire>"));
  ASSERT_NE(find(noBody, "RS8110"), nullptr);
  EXPECT_EQ(find(noBody, "RS8110")->message, "<object1> name: no object named 'a' before this wire");
}

TEST(FromXml, OutputLoadsAndIsCanonical) {
  FromXmlResult r = convert(world("<ground/><sphere name=\"s\" mass=\"1\"><dim radius=\"0.5\"/></sphere>"
                                  "<compound mass=\"1\"><children><box><dim x=\"1\" y=\"1\" z=\"1\"/></box></children></compound>",
                                  "<material><pair_prop name1=\"a\" name2=\"b\" friction=\"1\" restitution=\"0\" "
                                  "restitution_threshold=\"0\"/></material>"));
  ASSERT_TRUE(r.ok());
  rscene::LoadResult loaded = parse(r.text);
  ASSERT_TRUE(loaded.ok());
  // Canonical order: contact_material (resources) before the bodies.
  EXPECT_LT(r.text.find("contact_material"), r.text.find("object /World/ground"));
}

}  // namespace
}  // namespace rscene::xml

namespace rscene::xml {
namespace {

// RaiSim's templated example (xml-examples/spheres.xml) through the front
// end and the mapping.  Skipped while the front end is the interim plain
// parser, which leaves <array> and @@ unexpanded.
class TemplatedExample : public ::testing::Test {
 protected:
  FromXmlResult convertSpheres(const std::string& spawnSphere) {
    fs::path file = fs::path(RSCENE_SHARED_DIR) / "spec/raisim/xml-examples/spheres.xml";
    if (!fs::exists(file)) {
      skipped = "no ../shared/spec/raisim/xml-examples";
      return {};
    }
    LoadOptions options;
    options.params = {{"sphere_count", "20"}, {"spawn_sphere", spawnSphere}, {"spawn_box", "false"},
                      {"sphere_height_offset", "0.1"}};
    LoadResult loaded = loadWorld(file.string(), options);
    const Element* objects = loaded.ok() ? loaded.root->child("objects") : nullptr;
    if (!objects || objects->child("array")) {
      skipped = "the XML front end does not expand templates yet (interim lib/xml/load_world.cpp)";
      return {};
    }
    return worldToScene(*loaded.root, {});
  }
  std::string skipped;
};

TEST_F(TemplatedExample, TwentySpheresWhereTheExpressionsSay) {
  FromXmlResult r = convertSpheres("true");
  if (!skipped.empty()) GTEST_SKIP() << skipped;
  ASSERT_TRUE(r.ok());
  rscene::LoadResult doc = parse(r.text);
  ASSERT_TRUE(doc.ok());
  int spheres = 0;
  for (const Record& rec : doc.document.records) {
    if (doc.document.tag(rec) != "object") continue;
    std::string path = nodePath(doc.document, rec);
    ASSERT_EQ(path.rfind("/World/sphere_array_", 0), 0u) << path;
    int i = std::stoi(path.substr(20));
    double x = std::stod(std::string(doc.document.positionalText(rec, 2)));
    double y = std::stod(std::string(doc.document.positionalText(rec, 3)));
    double z = std::stod(std::string(doc.document.positionalText(rec, 4)));
    double radius = std::stod(std::string(doc.document.positionalText(rec, 12)));
    EXPECT_NEAR(x, std::cos(0.1 * i) * (i * 0.2 + 0.1), 1e-12) << path;
    EXPECT_NEAR(y, std::sin(0.1 * i) * (i * 0.2 + 0.1), 1e-12) << path;
    EXPECT_NEAR(z, 0.1 + i * 1.0, 1e-12) << path;
    EXPECT_NEAR(radius, 0.5 + i * 0.001, 1e-12) << path;
    ++spheres;
  }
  EXPECT_EQ(spheres, 20);
}

TEST_F(TemplatedExample, ExistFalseRemovesThem) {
  FromXmlResult r = convertSpheres("false");
  if (!skipped.empty()) GTEST_SKIP() << skipped;
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.text.find("object "), std::string::npos) << r.text;
}


// RaiSim keeps groups in signed integers (laikago.xml: -2147483648): a
// negative whole number is its int64 two's complement as a uint64.
TEST(FromXml, NegativeCollisionGroupIsTwosComplement) {
  FromXmlResult r = convert(world("<sphere name=\"a\" mass=\"1\" collisionGroup=\"-2147483648\" "
                                  "collisionMask=\"-2\"><dim radius=\"1\"/></sphere>"
                                  "<sphere name=\"b\" mass=\"1\" collision_group=\"-9223372036854775808\" "
                                  "collision_mask=\"-1\"><dim radius=\"1\"/></sphere>"));
  ASSERT_TRUE(r.ok()) << r.diagnostics[0].message;
  std::string b = bodies(r);
  EXPECT_NE(b.find(" dynamic true 18446744071562067968 18446744073709551614\n"), std::string::npos) << b;
  EXPECT_NE(b.find(" dynamic true 9223372036854775808 18446744073709551615\n"), std::string::npos) << b;
}

// RaiSim's exporter (exportedWorld.xml): body_type static, the height in
// <dim>, an empty <state>, groups on the ground.
TEST(FromXml, GroundInRaisimsExportedForm) {
  FromXmlResult r = convert(world("<ground name=\"g\" body_type=\"static\" collision_group=\"2147483648\" "
                                  "collision_mask=\"4294967295\"><dim height=\"0.5\"/><state/></ground>"));
  ASSERT_TRUE(r.ok()) << r.diagnostics[0].message;
  EXPECT_TRUE(r.diagnostics.empty()) << r.diagnostics[0].message;
  EXPECT_TRUE(r.notConverted.empty());
  EXPECT_EQ(bodies(r), "object /World/g ground 0 0 0.5 1 0 0 0 10 10 1 0 0 0 default - false true false - static true "
                       "2147483648 4294967295\n");
  FromXmlResult both = convert(world("<ground height=\"0.5\"><dim height=\"0.5\"/></ground>"));
  EXPECT_TRUE(both.ok());
  FromXmlResult differ = convert(world("<ground height=\"1\">\n<dim height=\"0.5\"/></ground>"));
  ASSERT_NE(find(differ, "RS8110"), nullptr);
  EXPECT_EQ(find(differ, "RS8110")->message, "<dim> height: differs from the ground's height attribute (1)");
  EXPECT_EQ(find(differ, "RS8110")->line, 4u);
  FromXmlResult dynamic = convert(world("<ground body_type=\"dynamic\"/>"));
  ASSERT_NE(find(dynamic, "RS8110"), nullptr);
  EXPECT_EQ(find(dynamic, "RS8110")->message, "<ground> body_type: 'dynamic': a ground is static");
  // RaiSim's ground reader ignores <state>: a pose there is listed, not the height.
  FromXmlResult posed = convert(world("<ground name=\"p\"><state pos=\"1 2 3\" quat=\"0 1 0 0\"/></ground>"));
  ASSERT_TRUE(posed.ok());
  EXPECT_NE(bodies(posed).find("object /World/p ground 0 0 0 1 0 0 0 "), std::string::npos) << bodies(posed);
  EXPECT_EQ(posed.notConverted,
            (std::vector<std::string>{"ground 'p' <state>: pos (a ground's height is its height)",
                                      "ground 'p' <state>: quat (a ground is level)"}));
}

// heightMapUsingPng.xml: heightScale / heightOffset, no x_sample/y_sample
// (the PNG's width and height are the sample counts).
TEST(FromXml, HeightmapPngInRaisimsSpelling) {
  fs::path dir = fs::temp_directory_path() / "rscene_from_xml_png_alias";
  fs::create_directories(dir);
  asset::Image image;
  image.width = 3;
  image.height = 2;
  image.rgba = {0, 0, 0, 255, 255, 0, 0, 255, 51, 0, 0, 255,      // top row (+y)
                102, 0, 0, 255, 204, 0, 0, 255, 255, 0, 0, 255};  // bottom row (y = 0)
  std::ofstream(dir / "h.png", std::ios::binary) << asset::encodePng(image);
  FromXmlOptions options;
  options.outputDir = dir.string();
  FromXmlResult r = convert(world("<heightmap name=\"terrain\" png=\"" + (dir / "h.png").string() +
                                  "\" xSize=\"6\" ySize=\"4\" centerX=\"1\" centerY=\"2\" heightOffset=\"-10\" "
                                  "heightScale=\"5\"/>"),
                            options);
  ASSERT_TRUE(r.ok()) << r.diagnostics[0].message;
  EXPECT_TRUE(r.diagnostics.empty()) << r.diagnostics[0].message;
  EXPECT_EQ(bodies(r), "terrain_region /World/terrain 3 2 6 4 1 2 0 contactMaterial=default sourceKind=png "
                       "sourcePath=h.png pngHeightScale=5 pngHeightOffset=-10 heights=-8,-6,-5,-10,-5,-9\n");
  FromXmlResult counts = convert(world("<heightmap png=\"" + (dir / "h.png").string() +
                                       "\" xSize=\"6\" ySize=\"4\" centerX=\"1\" centerY=\"2\" heightOffset=\"0\" "
                                       "heightScale=\"1\" x_sample=\"3\" y_sample=\"5\"/>"));
  ASSERT_TRUE(counts.ok());
  ASSERT_EQ(counts.diagnostics.size(), 1u);
  EXPECT_EQ(counts.diagnostics[0].message,
            "<heightmap>: y_sample 5 differs from the PNG's 2 pixels: the pixels are the samples, not resampled");
  EXPECT_NE(bodies(counts).find("terrain_region /World/heightmap 3 2 "), std::string::npos) << bodies(counts);
  FromXmlResult noScale = convert(world("<heightmap png=\"" + (dir / "h.png").string() +
                                        "\" xSize=\"6\" ySize=\"4\" centerX=\"1\" centerY=\"2\" heightOffset=\"0\"/>"));
  ASSERT_NE(find(noScale, "RS8112"), nullptr);
  EXPECT_EQ(find(noScale, "RS8112")->message, "<heightmap>: 'z_scale' is required");
}

// RaiSim's exporter writes stretch_type stretch_only / both /
// compression_only; only what rscene wires do converts silently.
TEST(FromXml, WireStretchTypesInRaisimsSpelling) {
  std::string spheres = "<sphere name=\"a\" mass=\"1\"><dim radius=\"1\"/></sphere>"
                        "<sphere name=\"b\" mass=\"1\"><dim radius=\"1\"/></sphere>";
  auto wire = [&](const std::string& type) {
    return convert(world(spheres, "<wire name=\"w\" type=\"stiff\" length=\"2\" stretch_type=\"" + type +
                                      "\"><object1 name=\"a\"/><object2 name=\"b\"/></wire>"));
  };
  for (const char* same : {"stretch_only", "STRETCH_ONLY", "STRETCH_RESISTANT_ONLY", "Stretch_Resistant_Only"}) {
    FromXmlResult r = wire(same);
    ASSERT_TRUE(r.ok()) << same;
    EXPECT_TRUE(r.diagnostics.empty()) << same;
    EXPECT_TRUE(r.notConverted.empty()) << same;
  }
  for (const char* other : {"both", "compression_only", "COMPRESSION_RESISTANT_ONLY", "BOTH"}) {
    FromXmlResult r = wire(other);
    ASSERT_TRUE(r.ok()) << other;
    EXPECT_EQ(r.notConverted,
              std::vector<std::string>{"wire 'w': stretch_type " + std::string(other) +
                                       " (rscene wires resist stretch only)"});
  }
}

// exportedWorld.xml: <raisim Version>, an empty <dim/> in an
// articulatedSystem, vectors with commas and spaces.
TEST(FromXml, RaisimsExporterForms) {
  FromXmlResult r = convert("<raisim Version=\"1.1.3\">\n<gravity value=\"0.000000, 0.000000, -9.810000\" />\n"
                            "<objects><articulatedSystem name=\"r\" urdf_path=\"/nonexistent/a.urdf\"><dim />"
                            "<state qpos=\"0.000000, 0.000000, 1.000000\" qvel=\"0, 0, 0\"/></articulatedSystem>"
                            "<sphere name=\"s\" mass=\"0.8\" com=\"0.000000, 0.000000, 0.000000\"><dim radius=\"0.1\"/>"
                            "<state pos=\"0.3, 0, 3\" quat=\"1, 0, 0, 0\" lin_vel=\"0, 0, 0\" ang_vel=\"0, 0, 0\"/>"
                            "</sphere></objects></raisim>\n");
  ASSERT_TRUE(r.ok()) << r.diagnostics[0].message;
  for (const Diagnostic& d : r.diagnostics) EXPECT_EQ(d.code, "RS8113") << d.message;  // the robot file only
  EXPECT_TRUE(r.notConverted.empty()) << r.notConverted[0];
  EXPECT_NE(r.text.find("gravity 0 0 -9.81\n"), std::string::npos) << r.text;
  EXPECT_NE(bodies(r).find("object /World/s sphere 0.3 0 3 1 0 0 0 1 1 1 0.1 0 0.8 "), std::string::npos) << bodies(r);
  FromXmlResult dimAttr = convert(world("<articulatedSystem urdf_path=\"/nonexistent/a.urdf\"><dim x=\"1\"/>"
                                        "</articulatedSystem>"));
  ASSERT_NE(find(dimAttr, "RS8111"), nullptr);
}

// Values rscene-validate, rscene-sim and rscene-to-xml would refuse are
// refused in the XML's words, at the attribute, and nothing is written.
TEST(FromXml, ValuesTheOtherToolsRefuseAreErrorsAtTheirAttribute) {
  struct Case {
    const char* xml;
    const char* message;
    unsigned column;
  } cases[] = {
      {"<sphere mass=\"1\"><dim radius=\"-1\"/></sphere>", "<dim> radius: -1 is not a positive length", 23},
      {"<sphere mass=\"1\"><dim radius=\"0\"/></sphere>", "<dim> radius: 0 is not a positive length", 23},
      {"<box mass=\"1\"><dim x=\"1\" y=\"-2\" z=\"1\"/></box>", "<dim> y: -2 is not a positive length", 26},
      {"<capsule mass=\"1\"><dim radius=\"1\" height=\"-3\"/></capsule>", "<dim> height: -3 is not a positive length",
       35},
      {"<sphere mass=\"-5\"><dim radius=\"1\"/></sphere>", "<sphere> mass: -5 is not a positive mass", 9},
      {"<sphere mass=\"1\"><dim radius=\"1\"/><state pos=\"0 0 0\" quat=\"0 0 0 0\"/></sphere>",
       "<state> quat: the zero quaternion is no orientation", 54},
      {"<compound mass=\"1\"><children><cylinder><dim radius=\"1\" height=\"0\"/></cylinder></children></compound>",
       "<dim> height: 0 is not a positive length", 56},
  };
  for (const Case& c : cases) {
    FromXmlResult r = convert(world(c.xml));
    EXPECT_FALSE(r.ok()) << c.xml;
    EXPECT_TRUE(r.text.empty()) << c.xml;
    const Diagnostic* d = find(r, "RS8110");
    ASSERT_NE(d, nullptr) << c.xml;
    EXPECT_EQ(d->message, c.message);
    EXPECT_EQ(d->file, "w.xml");
    EXPECT_EQ(d->line, 3u) << c.xml;
    EXPECT_EQ(d->column, c.column) << c.xml;
  }
  FromXmlResult dt = convert("<raisim><timeStep value=\"-0.1\"/><objects/></raisim>");
  ASSERT_NE(find(dt, "RS8110"), nullptr);
  EXPECT_EQ(find(dt, "RS8110")->message, "<timeStep> value: -0.1 is not a positive time step");
  EXPECT_TRUE(dt.text.empty());
}

// Whatever else the scene checks refuse comes back as RS8125 at the
// element (and attribute) that made the record, naming the check's code.
TEST(FromXml, RecordsTheSceneChecksRefuseAreErrorsAtTheirElement) {
  FromXmlResult wire = convert(world("<sphere name=\"a\" mass=\"1\"><dim radius=\"1\"/></sphere>\n"
                                     "<sphere name=\"b\" mass=\"1\"><dim radius=\"1\"/></sphere>",
                                     "<wire type=\"stiff\" length=\"-1\"><object1 name=\"a\"/><object2 name=\"b\"/></wire>\n"));
  EXPECT_TRUE(wire.text.empty());
  const Diagnostic* d = find(wire, "RS8125");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->file, "w.xml");
  EXPECT_EQ(d->line, 6u);
  EXPECT_EQ(d->column, 20u);  // length=
  EXPECT_EQ(d->message.rfind("<wire> length: ", 0), 0u) << d->message;
  EXPECT_NE(d->message.find("(RS4011 in the converted scene)"), std::string::npos) << d->message;

  FromXmlResult far = convert(world("<sphere mass=\"1\"><dim radius=\"1\"/><state pos=\"1e300 0 0\"/></sphere>"));
  ASSERT_NE(find(far, "RS8125"), nullptr);
  EXPECT_EQ(find(far, "RS8125")->message.rfind("<state> pos: ", 0), 0u);
  EXPECT_EQ(find(far, "RS8125")->line, 3u);
  EXPECT_TRUE(far.text.empty());

  FromXmlResult g = convert("<raisim>\n<gravity value=\"1e300 0 0\"/><objects/></raisim>");
  ASSERT_NE(find(g, "RS8125"), nullptr);
  EXPECT_EQ(find(g, "RS8125")->line, 2u);
  EXPECT_EQ(find(g, "RS8125")->message.rfind("<gravity> value: ", 0), 0u);
}

TEST(FromXml, ZeroQuaternionInARobotsQposIsAnErrorAtQpos) {
  fs::path dir = ownDir("rscene_from_xml_robot");
  fs::create_directories(dir);
  writeRobot(dir / "arm.urdf");
  FromXmlOptions options;
  options.outputDir = dir.string();
  std::string urdf = (dir / "arm.urdf").string();
  FromXmlResult r = convert(world("<articulatedSystem urdf_path=\"" + urdf +
                                  "\">\n<state qpos=\"0 0 1 0 0 0 0 0.5\"/></articulatedSystem>"),
                            options);
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(r.text.empty());
  bool atQpos = false;
  for (const Diagnostic& d : r.diagnostics)
    if (d.code == "RS8125" && d.line == 4 && d.column == 8 && d.message.rfind("<state> qpos: ", 0) == 0 &&
        d.message.find("RS4009") != std::string::npos)  // validate's one error for it (lib/core's zero quaternion)
      atQpos = true;
  std::string all;
  for (const Diagnostic& d : r.diagnostics)
    all += d.code + " " + std::to_string(d.line) + ":" + std::to_string(d.column) + " " + d.message + "\n";
  EXPECT_TRUE(atQpos) << all;
  // A unit quaternion converts.
  FromXmlResult ok = convert(world("<articulatedSystem urdf_path=\"" + urdf +
                                   "\"><state qpos=\"0 0 1 1 0 0 0 0.5\"/></articulatedSystem>"),
                             options);
  EXPECT_TRUE(ok.ok()) << ok.diagnostics[0].message;
}

// A missing mesh is converted (it may be made later), with a warning at
// file_name, as an unreadable robot file is.
TEST(FromXml, MissingMeshFileIsAWarning) {
  FromXmlResult r = convert(world("<mesh mass=\"1\" file_name=\"/nonexistent/m.obj\"/>"));
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(r.text.empty());
  const Diagnostic* d = find(r, "RS8113");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->severity, Severity::Warning);
  EXPECT_EQ(d->line, 3u);
  EXPECT_EQ(d->column, 16u);
  EXPECT_EQ(d->message, "<mesh> file_name: mesh file '/nonexistent/m.obj' not found: rscene-sim will refuse the body until it exists");
}

TEST(FromXml, NegativeZeroIsWrittenZeroHiddenIsInvisibleAndVelocitiesAreNamedAsWritten) {
  // RaiSim's maps/office1.xml writes quaternions with -0.000000 and hides
  // its colliders with appearance="hidden".
  FromXmlResult r = convert(world(
      "<box name=\"c\" mass=\"1\" appearance=\"hidden\"><dim x=\"1\" y=\"1\" z=\"1\"/>"
      "<state pos=\"-0.000000 0 0.5\" quat=\"1 -0.000000 0 -0\" linVel=\"1 0 0\"/></box>"
      "<compound name=\"k\" mass=\"1\" appearance=\"hidden\" com=\"0 0 0\"><children><sphere>"
      "<dim radius=\"0.5\"/></sphere></children></compound>"));
  ASSERT_TRUE(r.ok()) << (r.diagnostics.empty() ? "" : r.diagnostics[0].message);
  EXPECT_EQ(r.text.find(" -0 "), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("object /World/c box 0 0 0.5 1 0 0 0 1 1 1 0 0 1 default - false false false - dynamic"),
            std::string::npos)
      << r.text;
  EXPECT_NE(r.text.find("compound /World/k 0 0 0 1 0 0 0 1 1 1 1 dynamic false true"), std::string::npos) << r.text;
  EXPECT_NE(std::find(r.notConverted.begin(), r.notConverted.end(), "box 'c': linVel"), r.notConverted.end())
      << joined(r.notConverted);
  for (const std::string& n : r.notConverted) EXPECT_EQ(n.find("appearance"), std::string::npos) << n;
}

}  // namespace
}  // namespace rscene::xml
