// rscene-to-xml's mapping (lib/xml/to_xml.hpp), record kind by record
// kind: the XML text written, read back with tinyxml2 (well-formed,
// attribute values exact), and the list of what is not exported.
#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/loader.hpp"
#include "scene/scene.hpp"
#include "xml/to_xml.hpp"
#include "xml/to_xml_writer.hpp"

namespace rscene::xml {
namespace {

const std::string H = "raisim_engine_scene 1\n";
const std::string kAll = "18446744073709551615";

// An object record: path primitive position orientation scale radius height
// mass contactMaterial material visualOnly visible locked meshPath bodyMode
// collidable collisionGroup collisionMask, then `keys`.
std::string object(const std::string& path, const std::string& primitive, const std::string& position,
                   const std::string& scale, const std::string& radius, const std::string& height,
                   const std::string& mass, const std::string& mode = "dynamic", const std::string& keys = "",
                   const std::string& group = "1", const std::string& mask = kAll, const std::string& contact = "default",
                   const std::string& mesh = "-", const std::string& collidable = "true") {
  return "object " + path + " " + primitive + " " + position + " 1 0 0 0 " + scale + " " + radius + " " + height + " " +
         mass + " " + contact + " - false true false " + mesh + " " + mode + " " + collidable + " " + group + " " + mask +
         (keys.empty() ? "" : " " + keys) + "\n";
}

struct Exported {
  ToXmlResult result;
  Diagnostics sceneDiagnostics;
  bool built = false;
};

Exported exportScene(const std::string& text, const ToXmlOptions& options = {}, const std::string& sceneDir = ".") {
  Exported e;
  LoadResult loaded = parse(text);
  EXPECT_TRUE(loaded.ok()) << text;
  Scene scene;
  SceneOptions so;
  so.sceneDir = sceneDir;
  e.built = buildScene(loaded.document, so, scene, e.sceneDiagnostics);
  e.result = sceneToXml(loaded.document, scene, options);
  return e;
}

// The document read back by tinyxml2; fails the test when not well-formed.
struct Parsed {
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLElement* root() const { return doc.FirstChildElement("raisim"); }
  // The element of `tag` under <objects> named `name`.
  const tinyxml2::XMLElement* body(const char* tag, const std::string& name) const {
    for (const auto* e = root()->FirstChildElement("objects")->FirstChildElement(tag); e;
         e = e->NextSiblingElement(tag))
      if (e->Attribute("name") && name == e->Attribute("name")) return e;
    return nullptr;
  }
};

void parseXml(const std::string& xml, Parsed& p) {
  ASSERT_EQ(p.doc.Parse(xml.c_str(), xml.size()), tinyxml2::XML_SUCCESS) << xml;
  ASSERT_NE(p.root(), nullptr);
}

std::string attr(const tinyxml2::XMLElement* e, const char* name) {
  if (!e) return "<no element>";
  const char* v = e->Attribute(name);
  return v ? v : "<absent>";
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(ToXml, TopLevelTimeStepGravityErpAndDefaultMaterial) {
  Exported e = exportScene(H + "time_step 0.0025\ngravity 0 -1.5 -9.8\n"
                               "solver 80 1e-07 0.3 accurate erp2=0.05 defaultFriction=0.6 defaultRestitution=0.2 "
                               "defaultRestitutionThreshold=0.01\n");
  ASSERT_TRUE(e.result.ok());
  EXPECT_EQ(e.result.xml,
            "<?xml version=\"1.0\" ?>\n"
            "<raisim version=\"1.0\">\n"
            "    <timeStep value=\"0.0025\"/>\n"
            "    <gravity value=\"0 -1.5 -9.8\"/>\n"
            "    <erp erp=\"0.3\" erp2=\"0.05\"/>\n"
            "    <material>\n"
            "        <default friction=\"0.6\" restitution=\"0.2\" restitution_threshold=\"0.01\"/>\n"
            "    </material>\n"
            "    <objects/>\n"
            "</raisim>\n");
  EXPECT_TRUE(e.result.notExported.empty()) << joined(e.result.notExported);
}

TEST(ToXml, AbsentRecordsAreTheSchemaDefaultsWrittenExplicitly) {
  Exported e = exportScene(H);
  ASSERT_TRUE(e.result.ok());
  Parsed p;
  parseXml(e.result.xml, p);
  EXPECT_EQ(attr(p.root()->FirstChildElement("timeStep"), "value"), "0.0025");  // the schema's, not RaiSim's
  EXPECT_EQ(attr(p.root()->FirstChildElement("gravity"), "value"), "0 0 -9.81");
  EXPECT_EQ(attr(p.root()->FirstChildElement("erp"), "erp"), "0.2");
  const auto* def = p.root()->FirstChildElement("material")->FirstChildElement("default");
  EXPECT_EQ(attr(def, "friction"), "0.8");
  EXPECT_EQ(attr(def, "restitution"), "0");
  EXPECT_EQ(attr(def, "restitution_threshold"), "0.001");
}

TEST(ToXml, PairPropWritesEveryAttribute) {
  Exported e = exportScene(H + "contact_material steel rubber 0.7 0.15 0.002 0.9 0.01 0.05 0.02\n"
                               );
  ASSERT_TRUE(e.result.ok());
  EXPECT_TRUE(contains(e.result.xml,
                       "        <pair_prop name1=\"steel\" name2=\"rubber\" friction=\"0.7\" restitution=\"0.15\" "
                       "restitution_threshold=\"0.002\" static_friction=\"0.9\" "
                       "static_friction_velocity_threshold=\"0.01\" rolling_friction=\"0.05\" "
                       "spinning_friction=\"0.02\"/>\n"))
      << e.result.xml;
  Parsed p;
  parseXml(e.result.xml, p);
  EXPECT_EQ(attr(p.root()->FirstChildElement("material")->FirstChildElement("pair_prop"), "name2"), "rubber");
}

TEST(ToXml, SphereElementText) {
  Exported e = exportScene(H + object("/World/Ball", "sphere", "1 2 3", "2 2 2", "0.25", "0", "1.5", "dynamic", "",
                                      "1", kAll, "rubber"));
  ASSERT_TRUE(e.result.ok());
  EXPECT_TRUE(contains(e.result.xml,
                       "    <objects>\n"
                       "        <sphere name=\"/World/Ball\" mass=\"1.5\" material=\"rubber\" body_type=\"dynamic\">\n"
                       "            <dim radius=\"0.5\"/>\n"
                       "            <state pos=\"1 2 3\" quat=\"1 0 0 0\"/>\n"
                       "        </sphere>\n"
                       "    </objects>\n"))
      << e.result.xml;
}

TEST(ToXml, BoxCapsuleCylinderSizesAndBodyTypes) {
  Exported e = exportScene(H + object("/World/Box", "box", "0 0 1", "0.5 1 2", "0", "0", "3", "static") +
                           object("/World/Cap", "capsule", "0 0 2", "2 1 3", "0.1", "0.5", "1", "kinematic") +
                           object("/World/Cyl", "cylinder", "0 0 3", "1 1 1", "0.3", "0.9", "2"));
  ASSERT_TRUE(e.result.ok()) << e.result.xml;
  Parsed p;
  parseXml(e.result.xml, p);
  const auto* box = p.body("box", "/World/Box");
  EXPECT_EQ(attr(box, "body_type"), "static");
  EXPECT_EQ(attr(box->FirstChildElement("dim"), "x"), "0.5");
  EXPECT_EQ(attr(box->FirstChildElement("dim"), "y"), "1");
  EXPECT_EQ(attr(box->FirstChildElement("dim"), "z"), "2");
  const auto* cap = p.body("capsule", "/World/Cap");
  EXPECT_EQ(attr(cap, "body_type"), "kinematic");
  EXPECT_EQ(attr(cap->FirstChildElement("dim"), "radius"), "0.2");  // radius x scale.x
  EXPECT_EQ(attr(cap->FirstChildElement("dim"), "height"), "1.5");  // height x scale.z
  const auto* cyl = p.body("cylinder", "/World/Cyl");
  EXPECT_EQ(attr(cyl->FirstChildElement("dim"), "radius"), "0.3");
  EXPECT_EQ(attr(cyl->FirstChildElement("dim"), "height"), "0.9");
  EXPECT_EQ(attr(cyl, "collision_group"), "<absent>");  // defaults are omitted
  EXPECT_EQ(attr(cyl, "collision_mask"), "<absent>");
}

TEST(ToXml, WorldPoseInertiaAndCentreOfMass) {
  Exported e = exportScene(H + "group /World id=folder_world\n"
                               "compound /World/Base 1 0 0 0 0 0 1 1 1 1 5 static "
                               "true true id=base\n"
                               "compound_child base box 0 0 0 1 0 0 0 1 1 1\n" +
                           object("/World/Base/Ball", "sphere", "1 0 0", "1 1 1", "0.1", "0", "1", "dynamic",
                                  "parentGroupId=base customInertia=true inertiaDiagonal=0.1,0.2,0.3 centerOfMass=0,0,0.05"));
  ASSERT_TRUE(e.result.ok()) << e.result.xml;
  Parsed p;
  parseXml(e.result.xml, p);
  const auto* ball = p.body("sphere", "/World/Base/Ball");
  ASSERT_NE(ball, nullptr) << e.result.xml;
  // The world pose: the parent compound's half turn about z carries +x to -x.
  EXPECT_EQ(attr(ball->FirstChildElement("state"), "pos"), "0 0 0") << e.result.xml;
  EXPECT_EQ(attr(ball->FirstChildElement("state"), "quat"), "0 0 0 1");
  EXPECT_EQ(attr(ball, "com"), "0 0 0.05");
  const auto* inertia = ball->FirstChildElement("inertia");
  EXPECT_EQ(attr(inertia, "xx"), "0.1");
  EXPECT_EQ(attr(inertia, "xy"), "0");
  EXPECT_EQ(attr(inertia, "yy"), "0.2");
  EXPECT_EQ(attr(inertia, "zz"), "0.3");
}

TEST(ToXml, GroupsAndMasksInTheThreeForms) {
  Exported e = exportScene(H + object("/World/A", "box", "0 0 0", "1 1 1", "0", "0", "1", "dynamic", "", "9", kAll) +
                           object("/World/B", "box", "0 0 2", "1 1 1", "0", "0", "1", "dynamic", "", kAll, "511") +
                           object("/World/C", "box", "0 0 4", "1 1 1", "0", "0", "1", "dynamic", "", "1", "6"));
  ASSERT_TRUE(e.result.ok());
  Parsed p;
  parseXml(e.result.xml, p);
  EXPECT_EQ(attr(p.body("box", "/World/A"), "collision_group"), "collision[0|3]");
  EXPECT_EQ(attr(p.body("box", "/World/A"), "collision_mask"), "<absent>");
  EXPECT_EQ(attr(p.body("box", "/World/B"), "collision_group"), "collision[-1]");
  EXPECT_EQ(attr(p.body("box", "/World/B"), "collision_mask"), "511");  // 9 bits: the decimal
  EXPECT_EQ(attr(p.body("box", "/World/C"), "collision_mask"), "collision[1|2]");
}

TEST(ToXml, CollisionBitsNotation) {
  EXPECT_EQ(collisionBits(~std::uint64_t{0}), "collision[-1]");
  EXPECT_EQ(collisionBits(1), "collision[0]");
  EXPECT_EQ(collisionBits(std::uint64_t{1} << 63 | 1), "collision[0|63]");
  EXPECT_EQ(collisionBits(255), "collision[0|1|2|3|4|5|6|7]");
  EXPECT_EQ(collisionBits(511), "511");
  EXPECT_EQ(collisionBits(0), "0");
}

TEST(ToXml, GroundAndHalfSpace) {
  Exported e = exportScene(H + object("/World/Floor", "ground", "0 0 -0.5", "10 10 1", "0", "0", "0", "static", "",
                                      "1", "3", "concrete") +
                           object("/World/Half", "half_space", "0 0 2", "1 1 1", "0", "0", "0", "static", "", "4"));
  ASSERT_TRUE(e.result.ok());
  EXPECT_TRUE(contains(e.result.xml,
                       "        <ground name=\"/World/Floor\" height=\"-0.5\" material=\"concrete\" "
                       "collision_mask=\"collision[0|1]\"/>\n"))
      << e.result.xml;
  // RaiSim's exporter writes a ground's collision_group, and so does this.
  EXPECT_TRUE(contains(e.result.xml, "<ground name=\"/World/Half\" height=\"2\" material=\"default\" "
                                     "collision_group=\"collision[2]\"/>"))
      << e.result.xml;
  EXPECT_EQ(joined(e.result.notExported), "");
}

TEST(ToXml, MeshPathRelativeToTheOutputOrAbsolute) {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / "rscene_to_xml_mesh";
  fs::create_directories(dir / "scene" / "meshes");
  fs::create_directories(dir / "out");
  std::ofstream(dir / "scene" / "meshes" / "a.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n";
  std::ofstream(dir / "scene" / "meshes" / "hull.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n";
  std::string rec = object("/World/M&M%20\"x\"", "mesh", "0 0 1", "1 2 3", "0", "0", "2", "dynamic",
                           "collisionMeshPath=meshes/hull.obj centerOfMass=0.1,0,0", "1", kAll, "default",
                           "meshes/a.obj");
  ToXmlOptions relative;
  relative.outputDir = (dir / "out").string();
  Exported e = exportScene(H + rec, relative, (dir / "scene").string());
  ASSERT_TRUE(e.result.ok()) << (e.sceneDiagnostics.empty() ? "" : e.sceneDiagnostics[0].message);
  Parsed p;
  parseXml(e.result.xml, p);
  const auto* mesh = p.body("mesh", "/World/M&M \"x\"");
  ASSERT_NE(mesh, nullptr) << e.result.xml;
  EXPECT_TRUE(contains(e.result.xml, "name=\"/World/M&amp;M &quot;x&quot;\""));
  EXPECT_EQ(attr(mesh, "file_name"), "[THIS_DIR]/../scene/meshes/hull.obj");  // the collision mesh
  EXPECT_EQ(attr(mesh, "scale"), "1 2 3");
  EXPECT_EQ(attr(mesh, "com"), "0.1 0 0");
  EXPECT_EQ(mesh->FirstChildElement("dim"), nullptr);

  ToXmlOptions absolute = relative;
  absolute.absolutePaths = true;
  Exported a = exportScene(H + rec, absolute, (dir / "scene").string());
  Parsed pa;
  parseXml(a.result.xml, pa);
  EXPECT_EQ(attr(pa.body("mesh", "/World/M&M \"x\""), "file_name"),
            (fs::absolute(dir) / "scene" / "meshes" / "hull.obj").lexically_normal().generic_string());
  fs::remove_all(dir);
}

TEST(ToXml, CompoundChildrenWithTheCompoundScaleMultipliedThrough) {
  Exported e = exportScene(
      H + "compound /World/Cart 1 2 3 1 0 0 0 2 1 3 12 dynamic true true id=cart centerOfMass=0,0,0.1 "
          "inertiaDiagonal=1,2,3 collisionGroup=2 contactMaterial=wood\n"
          "compound_child cart box 0.5 0 0 1 0 0 0 1 1 1 size=1,0.6,0.1\n"
          "compound_child cart sphere 0 0 1 1 0 0 0 0.5 1 1 radius=0.2 contactMaterial=rubber\n"
          "compound_child cart cylinder 0 1 0 0.7071067811865476 0.7071067811865476 0 0 1 1 1 radius=0.1 "
          "height=0.05\n");
  ASSERT_TRUE(e.result.ok()) << e.result.xml;
  EXPECT_TRUE(contains(e.result.xml,
                       "        <compound name=\"/World/Cart\" mass=\"12\" material=\"wood\" body_type=\"dynamic\" "
                       "collision_group=\"collision[1]\" com=\"0 0 0.1\">\n"
                       "            <inertia xx=\"1\" xy=\"0\" xz=\"0\" yy=\"2\" yz=\"0\" zz=\"3\"/>\n"
                       "            <children>\n"
                       "                <box material=\"wood\">\n"
                       "                    <dim x=\"2\" y=\"0.6\" z=\"0.30000000000000004\"/>\n"
                       "                    <state pos=\"1 0 0\" quat=\"1 0 0 0\"/>\n"
                       "                </box>\n"
                       "                <sphere material=\"rubber\">\n"
                       "                    <dim radius=\"0.2\"/>\n"
                       "                    <state pos=\"0 0 3\" quat=\"1 0 0 0\"/>\n"
                       "                </sphere>\n"
                       "                <cylinder material=\"wood\">\n"
                       "                    <dim radius=\"0.2\" height=\"0.15000000000000002\"/>\n"
                       "                    <state pos=\"0 1 0\" quat=\"0.7071067811865476 0.7071067811865476 0 0\"/>\n"
                       "                </cylinder>\n"
                       "            </children>\n"
                       "            <state pos=\"1 2 3\" quat=\"1 0 0 0\"/>\n"
                       "        </compound>\n"))
      << e.result.xml;
}

// RaiSim requires `com` on a compound; without centerOfMass rscene-sim
// uses the children's centroid weighted by their true volumes
// (scene/mass_properties.hpp), and to-xml writes that point.
TEST(ToXml, CompoundWithoutCenterOfMassGetsTheCentroidRsceneSimUses) {
  Exported e = exportScene(
      H + "compound /World/Cart 0 0 0 1 0 0 0 2 1 1 3 dynamic true true id=cart\n"
          "compound_child cart box 0 0 0.5 1 0 0 0 1 1 1 size=1,1,0.1\n"      // 2 x 1 x 0.1 = 0.2 at (0, 0, 0.5)
          "compound_child cart sphere 1 0 0 1 0 0 0 1 1 1 radius=0.5\n"       // r 1: 4/3 pi at (2, 0, 0)
          "compound_child cart capsule 0 1 0 1 0 0 0 1 1 1 radius=0.1 height=1\n"  // r 0.2: pi 0.04 (1 + 0.8/3) at (0, 1, 0)
          "compound_child cart cylinder 0 0 -1 1 0 0 0 1 1 1 radius=0.1 height=0.5\n"  // pi 0.04 x 0.5 at (0, 0, -1)
          "compound_child cart mesh 5 5 5 1 0 0 0 1 1 1 meshPath=hull.obj\n");  // not exported: not counted
  ASSERT_TRUE(e.result.ok()) << e.result.xml;
  Parsed p;
  parseXml(e.result.xml, p);
  const auto* c = p.body("compound", "/World/Cart");
  ASSERT_NE(c, nullptr) << e.result.xml;
  std::istringstream com(attr(c, "com"));
  double x = 0, y = 0, z = 0;
  ASSERT_TRUE(com >> x >> y >> z) << attr(c, "com");
  const double pi = 3.14159265358979323846;
  double sphere = 4.0 / 3.0 * pi, capsule = pi * 0.04 * (1 + 0.8 / 3), cylinder = pi * 0.04 * 0.5;
  double total = 0.2 + sphere + capsule + cylinder;
  EXPECT_NEAR(x, sphere * 2 / total, 1e-15);
  EXPECT_NEAR(y, capsule / total, 1e-15);
  EXPECT_NEAR(z, (0.2 * 0.5 - cylinder) / total, 1e-15);
  EXPECT_EQ(joined(e.result.notExported), "compound /World/Cart: mesh child");
  // A written centerOfMass is written as it is.
  Exported given = exportScene(H + "compound /World/C 0 0 0 1 0 0 0 1 1 1 3 dynamic true true id=c "
                                   "centerOfMass=0.5,0,0\ncompound_child c box 0 0 1 1 0 0 0 1 1 1 size=1,1,1\n");
  EXPECT_TRUE(contains(given.result.xml, "com=\"0.5 0 0\"")) << given.result.xml;
}

TEST(ToXml, HeightmapSamplesInRecordOrderWithTheCentreHeightAdded) {
  // Sample (x, y) is heights[y * xSamples + x]: x runs fastest.
  Exported e = exportScene(H + "terrain_region /World/T 3 2 4 2 1 -1 0.5 contactMaterial=grass "
                               "heights=0,1,2,10,11,12\n");
  ASSERT_TRUE(e.result.ok());
  EXPECT_TRUE(contains(e.result.xml,
                       "        <heightmap name=\"/World/T\" x_sample=\"3\" y_sample=\"2\" x_size=\"4\" y_size=\"2\" "
                       "center_x=\"1\" center_y=\"-1\" material=\"grass\" height=\"0.5 1.5 2.5 10.5 11.5 12.5\"/>\n"))
      << e.result.xml;
}

TEST(ToXml, ProceduralHeightmapWritesTerrainProperties) {
  Exported e = exportScene(H + "terrain_region /World/T 50 50 20 20 0 0 0 sourceKind=procedural "
                               "proceduralFrequency=0.2 proceduralZScale=3 proceduralOctaves=3 "
                               "proceduralLacunarity=2 proceduralGain=0.25 proceduralStepSize=0 proceduralSeed=7\n");
  ASSERT_TRUE(e.result.ok());
  Parsed p;
  parseXml(e.result.xml, p);
  const auto* h = p.body("heightmap", "/World/T");
  EXPECT_EQ(attr(h, "height"), "<absent>");
  const auto* tp = h->FirstChildElement("terrain_properties");
  EXPECT_EQ(attr(tp, "frequency"), "0.2");
  EXPECT_EQ(attr(tp, "z_scale"), "3");
  EXPECT_EQ(attr(tp, "fractal_octaves"), "3");
  EXPECT_EQ(attr(tp, "fractal_lacunarity"), "2");
  EXPECT_EQ(attr(tp, "fractal_gain"), "0.25");
  EXPECT_EQ(attr(tp, "step_size"), "0");
  EXPECT_EQ(attr(tp, "seed"), "7");
  EXPECT_EQ(attr(tp, "height_offset"), "<absent>");
}

const std::string kWalker = std::string(RSCENE_TEST_DATA) + "/robots/check/walker.urdf";
const std::string kTwoLink = std::string(RSCENE_TEST_DATA) + "/robots/urdf/two_link.urdf";

TEST(ToXml, ArticulatedWithWrittenCoordinatesKeepsThemAsWritten) {
  Exported e = exportScene(H + "articulated_resource walker_res Walker " + kWalker +
                           "\narticulated /World/Walker walker_res 0 0 0.5 1 0 0 0 true true id=walker "
                           "generalizedCoordinate=1,2,0.5,1,0,0,0,0.3,-0.6,0.3,-0.6 "
                           "generalizedVelocity=0.1,0,0,0,0,0,1,2,3,4 modules=a.urdf;b.urdf collisionGroup=4\n");
  ASSERT_TRUE(e.result.ok()) << (e.result.diagnostics.empty() ? "" : e.result.diagnostics[0].message);
  Parsed p;
  parseXml(e.result.xml, p);
  const auto* w = p.body("articulatedSystem", "/World/Walker");
  ASSERT_NE(w, nullptr) << e.result.xml;
  EXPECT_EQ(attr(w, "urdf_path").rfind("[THIS_DIR]/", 0), 0u) << attr(w, "urdf_path");
  EXPECT_TRUE(contains(attr(w, "urdf_path"), "robots/check/walker.urdf"));
  EXPECT_EQ(attr(w, "modules"), "a.urdf b.urdf");
  EXPECT_EQ(attr(w, "collision_group"), "collision[2]");
  EXPECT_EQ(attr(w->FirstChildElement("state"), "qpos"), "1 2 0.5 1 0 0 0 0.3 -0.6 0.3 -0.6");
  EXPECT_EQ(attr(w->FirstChildElement("state"), "qvel"), "0.1 0 0 0 0 0 1 2 3 4");
}

TEST(ToXml, ArticulatedWithoutCoordinatesUsesTheWorldPoseAndZeroJoints) {
  Exported e = exportScene(H + "articulated_resource walker_res Walker " + kWalker +
                           "\narticulated /World/Walker walker_res 1 2 3 0 0 0 1 true false id=walker\n");
  ASSERT_TRUE(e.result.ok());
  Parsed p;
  parseXml(e.result.xml, p);
  const auto* w = p.body("articulatedSystem", "/World/Walker");
  EXPECT_EQ(attr(w->FirstChildElement("state"), "qpos"), "1 2 3 0 0 0 1 0 0 0 0");
  // No generalizedVelocity: no qvel (from-xml would turn a written zero
  // qvel into a generalizedVelocity key the scene did not have).
  EXPECT_EQ(attr(w->FirstChildElement("state"), "qvel"), "<absent>");
  // collidable=false: rscene-sim gives the robot's bodies group and mask 0.
  EXPECT_EQ(attr(w, "collision_group"), "0");
  EXPECT_EQ(attr(w, "collision_mask"), "0");
}

TEST(ToXml, ArticulatedJointOrderIsUndoneIntoRaisimsOrder) {
  Exported e = exportScene(H + "articulated_resource walker_res Walker " + kWalker +
                           "\narticulated /World/Walker walker_res 0 0 0 1 0 0 0 true true "
                           "jointOrder=R_HIP;R_KNEE;L_HIP;L_KNEE generalizedCoordinate=0,0,0.5,1,0,0,0,3,4,1,2\n");
  ASSERT_TRUE(e.result.ok()) << (e.result.diagnostics.empty() ? "" : e.result.diagnostics[0].message);
  Parsed p;
  parseXml(e.result.xml, p);
  EXPECT_EQ(attr(p.body("articulatedSystem", "/World/Walker")->FirstChildElement("state"), "qpos"),
            "0 0 0.5 1 0 0 0 1 2 3 4");
}

TEST(ToXml, CorpusAnymalGetsItsModelsSizes) {
  std::string urdf = std::string(RSCENE_SHARED_DIR) + "/corpus/robots/anymal_c/urdf/anymal.urdf";
  if (!std::filesystem::exists(urdf)) GTEST_SKIP() << "no ../shared corpus";
  Exported e = exportScene(H + "articulated_resource a A " + urdf +
                           "\narticulated /World/A a 0 0 0.6 1 0 0 0 true true scale=2,2,2\n");
  ASSERT_TRUE(e.result.ok());
  Parsed p;
  parseXml(e.result.xml, p);
  const auto* state = p.body("articulatedSystem", "/World/A")->FirstChildElement("state");
  // A floating base (7) and twelve revolute joints; no velocity written.
  EXPECT_EQ(attr(state, "qpos"), "0 0 0.6 1 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0");
  EXPECT_EQ(attr(state, "qvel"), "<absent>");
  EXPECT_EQ(joined(e.result.notExported), "articulated /World/A: scale");
}

TEST(ToXml, FixedBaseAwayFromTheOriginIsListed) {
  std::string res = "articulated_resource arm_res Arm " + kTwoLink + "\n";
  Exported at = exportScene(H + res + "articulated /World/Arm arm_res 0 0 0 1 0 0 0 true true\n");
  ASSERT_TRUE(at.result.ok());
  EXPECT_TRUE(at.result.notExported.empty()) << joined(at.result.notExported);
  Exported away = exportScene(H + res + "articulated /World/Arm arm_res 1 0 0 1 0 0 0 true true\n");
  ASSERT_TRUE(away.result.ok());
  EXPECT_EQ(joined(away.result.notExported), "articulated /World/Arm: fixed-base pose");
}

TEST(ToXml, UnreadableRobotFileStillExportsItsPath) {
  ToXmlOptions absolute;
  absolute.absolutePaths = true;
  Exported e = exportScene(H + "articulated_resource r R /nonexistent/robot.urdf\n"
                               "articulated /World/R r 0 0 0 1 0 0 0 true true generalizedCoordinate=0,0,1,1,0,0,0\n",
                           absolute);
  ASSERT_TRUE(e.result.ok());
  ASSERT_EQ(e.result.diagnostics.size(), 1u);
  EXPECT_EQ(e.result.diagnostics[0].code, "RS8131");
  EXPECT_EQ(e.result.diagnostics[0].severity, Severity::Warning);
  Parsed p;
  parseXml(e.result.xml, p);
  const auto* r = p.body("articulatedSystem", "/World/R");
  EXPECT_EQ(attr(r, "urdf_path"), "/nonexistent/robot.urdf");
  EXPECT_EQ(attr(r->FirstChildElement("state"), "qpos"), "0 0 1 1 0 0 0");
  EXPECT_EQ(attr(r->FirstChildElement("state"), "qvel"), "<absent>");
}

TEST(ToXml, WireEndsAreBodyPaths) {
  Exported e = exportScene(H + object("/World/A", "sphere", "0 0 2", "1 1 1", "0.1", "0", "1", "dynamic", "id=a") +
                           object("/World/B", "sphere", "0 0 1", "1 1 1", "0.1", "0", "1", "dynamic", "id=b") +
                           "wire /World/W compliant a /World/B 1.5 localPositionA=0,0,-0.1 localPositionB=0,0.1,0 "
                           "stiffness=500 damping=2\n"
                           "wire /World/Hook stiff a - 1\n"
                           "wire /World/Off stiff a b 1 enabled=false\n");
  ASSERT_TRUE(e.result.ok());
  EXPECT_TRUE(contains(e.result.xml,
                       "    <wire name=\"/World/W\" type=\"compliant\" length=\"1.5\" stiffness=\"500\" "
                       "stretch_type=\"stretch_only\">\n"
                       "        <object1 name=\"/World/A\" local_index=\"0\" pos=\"0 0 -0.1\"/>\n"
                       "        <object2 name=\"/World/B\" local_index=\"0\" pos=\"0 0.1 0\"/>\n"
                       "    </wire>\n"))
      << e.result.xml;
  EXPECT_FALSE(contains(e.result.xml, "/World/Hook"));
  EXPECT_FALSE(contains(e.result.xml, "/World/Off"));
  EXPECT_EQ(joined(e.result.notExported), "1 wire not simulated, wire /World/W: damping, wire /World/Hook: end in the world");
}

TEST(ToXml, VisualOnlyBodiesAreNotExported) {
  Exported e = exportScene(H + object("/World/Ghost", "box", "0 0 0", "1 1 1", "0", "0", "1", "visual_only") +
                           object("/World/NoHit", "box", "0 0 0", "1 1 1", "0", "0", "1", "dynamic", "", "1", kAll,
                                  "default", "-", "false") +
                           object("/World/Real", "box", "0 0 0", "1 1 1", "0", "0", "1"));
  ASSERT_TRUE(e.result.ok());
  EXPECT_FALSE(contains(e.result.xml, "Ghost"));
  EXPECT_FALSE(contains(e.result.xml, "NoHit"));
  EXPECT_TRUE(contains(e.result.xml, "/World/Real"));
  EXPECT_EQ(joined(e.result.notExported), "2 visual-only bodies");
}

TEST(ToXml, SolverKeysWithoutAnAttributeAreListedWhenNotDefault) {
  Exported same = exportScene(H + "solver 80 1e-07 0.2 accurate sleepingEnabled=true\n");
  EXPECT_TRUE(same.result.notExported.empty()) << joined(same.result.notExported);
  Exported e = exportScene(H + "solver 100 1e-07 0.2 accurate erp2=0.1 sleepingEnabled=false maxContactsPerPair=4\n");
  EXPECT_EQ(joined(e.result.notExported), "solver iterations, solver maxContactsPerPair, solver sleepingEnabled");
}

TEST(ToXml, GalleryWarningListCountsEachKind) {
  std::ifstream in(std::string(RSCENE_SOURCE_DIR) + "/examples/gallery.rscene");
  std::stringstream text;
  text << in.rdbuf();
  Exported e = exportScene(text.str(), {}, std::string(RSCENE_SOURCE_DIR) + "/examples");
  ASSERT_TRUE(e.result.ok());
  EXPECT_EQ(joined(e.result.notExported),
            "5 lights, 1 camera, materials' looks, environment, weather, render settings, 4 groups, 1 sensor, "
            "1 visual-only body, 1 deformable, 1 granular, 2 instanced visuals, 1 point cloud, 2 probes, 1 decal, "
            "1 fog volume, 2 terrain layers");
  Parsed p;
  parseXml(e.result.xml, p);
}

TEST(ToXml, SameSceneSameBytes) {
  std::ifstream in(std::string(RSCENE_SOURCE_DIR) + "/examples/robot_cell.rscene");
  std::stringstream text;
  text << in.rdbuf();
  std::string dir = std::string(RSCENE_SOURCE_DIR) + "/examples";
  Exported a = exportScene(text.str(), {}, dir), b = exportScene(text.str(), {}, dir);
  ASSERT_TRUE(a.result.ok());
  EXPECT_FALSE(a.result.xml.empty());
  EXPECT_EQ(a.result.xml, b.result.xml);
}

TEST(ToXml, EscapesAndRefusesWhatXmlCannotHold) {
  std::string out;
  EXPECT_TRUE(escapeAttribute("a&b<c>d\"e\tf\n", out));
  EXPECT_EQ(out, "a&amp;b&lt;c&gt;d&quot;e&#9;f&#10;");
  out.clear();
  EXPECT_FALSE(escapeAttribute(std::string("x\x01y"), out));
  out.clear();
  EXPECT_TRUE(escapeAttribute("caf\xC3\xA9 \xE2\x82\xAC", out));  // UTF-8 passes through
  EXPECT_EQ(out, "caf\xC3\xA9 \xE2\x82\xAC");
  out.clear();
  EXPECT_FALSE(escapeAttribute("caf\xE9", out));  // Latin-1: not UTF-8
  EXPECT_EQ(out, "caf?");
  out.clear();
  EXPECT_FALSE(escapeAttribute("\xEF\xBF\xBF", out));
  // A name with a control character (a percent-encoded byte) is refused
  // where the record writes it (RS8132, line and column of the path).
  Exported e = exportScene(H + object("/World/a%01b", "box", "0 0 0", "1 1 1", "0", "0", "1"));
  ASSERT_FALSE(e.result.ok());
  ASSERT_EQ(e.result.diagnostics.size(), 1u);
  EXPECT_EQ(e.result.diagnostics[0].code, "RS8132");
  EXPECT_EQ(e.result.diagnostics[0].line, 2u);
  EXPECT_EQ(e.result.diagnostics[0].column, 8u);
  EXPECT_TRUE(contains(e.result.diagnostics[0].message, "control character")) << e.result.diagnostics[0].message;
  EXPECT_TRUE(e.result.xml.empty());
}

TEST(ToXml, NamesTheTemplateLanguageWouldReadAreRefusedAtTheirRecord) {
  // @@ (a parameter), {...} (an expression), [THIS_DIR] (a folder): from-xml
  // would fail or rename the body, so each is an error at its record's path.
  Exported e = exportScene(H + object("/World/ok", "box", "0 0 0", "1 1 1", "0", "0", "1") +
                           object("/World/@@p", "box", "2 0 0", "1 1 1", "0", "0", "1") +
                           object("/World/{1+1}", "box", "4 0 0", "1 1 1", "0", "0", "1") +
                           object("/World/[THIS_DIR]", "box", "6 0 0", "1 1 1", "0", "0", "1") +
                           object("/World/b}", "box", "8 0 0", "1 1 1", "0", "0", "1") +
                           object("/World/m", "box", "10 0 0", "1 1 1", "0", "0", "1", "dynamic", "", "1", kAll,
                                  "rubber@@x"));
  ASSERT_FALSE(e.result.ok());
  EXPECT_TRUE(e.result.xml.empty());
  ASSERT_EQ(e.result.diagnostics.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(e.result.diagnostics[i].code, "RS8132");
    EXPECT_EQ(e.result.diagnostics[i].line, i + 3) << e.result.diagnostics[i].message;
    EXPECT_GT(e.result.diagnostics[i].column, 0u);
  }
  EXPECT_TRUE(contains(e.result.diagnostics[0].message, "'@@'")) << e.result.diagnostics[0].message;
  EXPECT_TRUE(contains(e.result.diagnostics[1].message, "expression")) << e.result.diagnostics[1].message;
  EXPECT_TRUE(contains(e.result.diagnostics[2].message, "[THIS_DIR]")) << e.result.diagnostics[2].message;
  EXPECT_TRUE(contains(e.result.diagnostics[4].message, "contact material")) << e.result.diagnostics[4].message;
}

TEST(ToXml, NegativeZeroIsWrittenZeroAndHiddenBodiesKeepTheirAppearance) {
  Exported e = exportScene(H + "object /World/b box 0 -0 0.5 -0 0 0 1 1 1 1 0 0 1 default - false false false - "
                               "dynamic true 1 " + kAll + "\n");
  ASSERT_TRUE(e.result.ok()) << (e.result.diagnostics.empty() ? "" : e.result.diagnostics[0].message);
  EXPECT_FALSE(contains(e.result.xml, "\"-0") || contains(e.result.xml, " -0 ")) << e.result.xml;
  Parsed p;
  parseXml(e.result.xml, p);
  EXPECT_EQ(attr(p.body("box", "/World/b"), "appearance"), "hidden");
}

}  // namespace
}  // namespace rscene::xml
