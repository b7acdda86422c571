// One scene that triggers each check and one that is fine, for every code
// of the table (check_codes.cpp).  A fine scene must give no finding at all.
#include <gtest/gtest.h>

#include <set>

#include "core/check.hpp"

namespace rscene {
namespace {

struct Case {
  const char* code;
  std::string bad;
  std::string good;
  Profile profile = Profile::Engine2;
};

const std::string H = "raisim_engine_scene 2\n";
const std::string H1 = "raisim_engine_scene 1\n";
// A dynamic 1 kg box at the origin, in the 25-field layout.
std::string box(const std::string& path = "/World/a", const std::string& keys = "", const std::string& mass = "1",
                const std::string& quat = "1 0 0 0", const std::string& material = "engine_default",
                const std::string& contact = "default", const std::string& mode = "dynamic",
                const std::string& radius = "0.5") {
  return "object " + path + " box 0 0 0 " + quat + " 1 1 1 " + radius + " 1 " + mass + " " + contact + " " +
         material + " false true false - " + mode + " true 1 18446744073709551615" + (keys.empty() ? "" : " " + keys) +
         "\n";
}
const std::string G = "group /World/g id=g\n";
std::string terrain(const std::string& counts = "3 3", const std::string& sizes = "2 2", const std::string& keys = "") {
  return "terrain_region /World/t " + counts + " " + sizes + " 0 0 0 id=t" + (keys.empty() ? "" : " " + keys) + "\n";
}
std::string camera(const std::string& fovNearFar) {
  return "camera /World/c 0 0 0 1 0 0 0 " + fovNearFar + " 640 480 rgb true\n";
}
const std::string IV = "instanced_visual /World/i box instances=0,0,0,1,0,0,0,1,1,1";

std::vector<Case> cases() {
  return {
      {"RS1001", "time_step 0.1\n", H},
      {"RS1002", "raisim_engine_scene 3\n", H},
      {"RS1003", H + "asset_root a%zz\n", H + "asset_root a%20b\n"},
      {"RS1004", H + std::string("asset_root a\0b\n", 15), H + "asset_root ab\n"},
      {"RS1005", H + "asset_root a\xff\n", H + "asset_root a\xc3\xa9\n"},
      {"RS1006", H + "asset_root a\x01\n", H + "asset_root a%01\n"},
      {"RS1007", H + "time_step\n", H + "time_step 0.1\n"},
      {"RS1008", H + "asset_root id=x .\n", H + "asset_root .\n"},
      {"RS1009", H + "scene_graph =true\n", H + "scene_graph inheritedTransforms=true\n"},
      {"RS1101", H + box("/World/a", "id=x id=y"), H + box("/World/a", "id=y")},
      {"RS2001", H + "time_step fast\n", H + "time_step 0.1\n"},
      {"RS2002", H + "time_step nan\n", H + "time_step 1e300\n"},
      {"RS2003", H + "solver 1.5 1e-07 0.2 accurate\n", H + "solver 80 1e-07 0.2 accurate\n"},
      {"RS2004", H + "compound /World/k 0 0 0 1 0 0 0 1 1 1 1 static true true collisionGroup=-1\n",
       H + "compound /World/k 0 0 0 1 0 0 0 1 1 1 1 static true true collisionGroup=18446744073709551615\n"},
      {"RS2005", H + "scene_graph inheritedTransforms=maybe\n", H + "scene_graph inheritedTransforms=no\n"},
      {"RS2006", H + box("/World/a", "", "1", "1 0 0 0", "engine_default", "default", "dynamik"),
       H + box("/World/a", "", "1", "1 0 0 0", "engine_default", "default", "MOVABLE")},
      {"RS2007", H + "solver 80 1e-07 0.2 turbo\n", H + "solver 80 1e-07 0.2 fast\n"},
      {"RS2008", H + "light /World/l 0 0 -1 1 color=1,1\n", H + "light /World/l 0 0 -1 1 color=1,1,1,0.5\n"},
      {"RS2009", H + terrain("2 2", "2 2", "heights=1,,2,3"), H + terrain("2 2", "2 2", "heights=1,2;2,3")},
      {"RS3001", H + "objcet /World/a\n", H},
      {"RS3002", H + box("/World/a", "colour=1"), H + box("/World/a", "semanticClass=wall")},
      {"RS3003", H + box("/World/a", "id=a") + box("/World/a", "id=b"), H + box("/World/a", "id=a") + box("/World/b", "id=b")},
      {"RS3004", H + box("/World/a", "id=x") + box("/World/b", "id=x"), H + box("/World/a", "id=x") + box("/World/b")},
      {"RS3005", H + box("/Other/a"), H + box("/World/a")},
      {"RS3006", H + box("/World/a", "parentGroupId=nothing"), H + G + box("/World/a", "parentGroupId=/World/g")},
      {"RS3007", H + box("/World/p") + box("/World/a", "parentGroupId=object_/World/p"),
       H + "scene_graph inheritedTransforms=false\n" + box("/World/p") + box("/World/a", "parentGroupId=object_/World/p")},
      {"RS3008", H + box("/World/a", "", "1", "1 0 0 0", "steel"), H + "material steel 0.5 0.5 0.5 1 0 0.5 0 0 0 0 false - - - - - -\n" + box("/World/a", "", "1", "1 0 0 0", "steel")},
      {"RS3009", H + box("/World/a", "", "1", "1 0 0 0", "engine_default", "ice"),
       H + "contact_material ice rubber 0.1 0 0 0.1 0.001 0 0\n" + box("/World/a", "", "1", "1 0 0 0", "engine_default", "ice")},
      {"RS3010", H + "articulated /World/r anymal 0 0 0 1 0 0 0 true true\n",
       H + "articulated_resource anymal ANYmal anymal.urdf\narticulated /World/r anymal 0 0 0 1 0 0 0 true true\n"},
      {"RS3011", H + terrain("3 3", "2 2", "baseTexture=5"),
       H + "terrain_texture 5 sand Sand\n" + terrain("3 3", "2 2", "baseTexture=5")},
      {"RS3012", H + box("/World/a") + "wire /World/w stiff object_/World/a nobody 1\n",
       H + box("/World/a") + box("/World/b") + "wire /World/w stiff object_/World/a /World/b 1\n"},
      {"RS3013", H + "instanced_visual /World/i box terrainBinding=nowhere\n", H + terrain() + "instanced_visual /World/i box terrainBinding=t\n"},
      {"RS3014", H + box("/World/a") + "prefab_override /World/nothing property=visible value=false\n",
       H + box("/World/a") + "prefab_override /World/a property=visible value=false\n"},
      {"RS3015", H + "terrain_splat_layer t weights=\n" + terrain(), H + terrain() + "terrain_splat_layer t weights=\n"},
      {"RS3016", H + "gravity 0 0 -9.81\ngravity 0 0 -1.62\n", H + "gravity 0 0 -1.62\n"},
      {"RS3017", H + "group /World/g1 id=g1 parentId=g2\ngroup /World/g2 id=g2 parentId=g1\n",
       H + "group /World/g1 id=g1\ngroup /World/g2 id=g2 parentId=g1\n"},
      {"RS4001", H + terrain("1 3"), H + terrain("2 3")},
      {"RS4002", H + terrain("16384 16384"), H + terrain("4096 4096")},
      {"RS4003", H + terrain("3 3", "2 2", "heights=1,2,3"), H + terrain("3 3", "2 2", "heights=0,0,0,0,0,0,0,0,0 wetness=")},
      {"RS4004", H + IV + ",2\n", H + IV + "\n"},
      {"RS4005", H + IV + " colorWeights=1,2\n", H + IV + " colorWeights=0.5\n"},
      {"RS4006", H + terrain("2 2", "2 2", "vertexColors=1,0,0"), H + terrain("2 2", "2 2", "vertexColors=1,0,0;0,1,0;0,0,1;1,1,1,1")},
      {"RS4007", H + "articulated_resource r r r.urdf\narticulated /World/r r 0 0 0 1 0 0 0 true true generalizedCoordinate=0,0,0 generalizedVelocity=0\n",
       H + "articulated_resource r r r.urdf\narticulated /World/r r 0 0 0 1 0 0 0 true true generalizedCoordinate=0,0,0,1,0,0,0 generalizedVelocity=0,0,0,0,0,0\n"},
      {"RS4009", H + box("/World/a", "", "1", "0 0 0 0"), H + box("/World/a", "", "1", "0 1 0 0")},
      {"RS4010", H + box("/World/a", "", "1", "1 0 0 0.1"), H + box("/World/a", "", "1", "0.7071068 0 0 0.7071068")},
      // Body sizes (object radius, child size) are the scene model's, RS7003.
      {"RS4011", H + "light /World/l 0 0 -1 1 range=-1\n", H + "light /World/l 0 0 -1 1 range=0\n"},
      {"RS4012", H + camera("60 10 1"), H + camera("60 0.1 100")},
      {"RS4013", H + camera("0.5 0.1 100"), H + camera("175 0.1 100")},
      {"RS4014", H + terrain("3 3", "0 2"), H + terrain("3 3", "0.5 2")},
      {"RS6001", H + "point_cloud /World/p\n", H + box("/World/p"), Profile::RaiSim},
      {"RS6002", H + box("/World/a", "id=x id=y"), H + box("/World/a", "id=y"), Profile::RaiSim},
      {"RS6003", H1 + "asset_root assets\n", H1 + "asset_root .\n", Profile::RaiSim},
      {"RS6004", H + box("/World/p") + box("/World/a", "parentGroupId=/World/p"),
       H + G + box("/World/a", "parentGroupId=g"), Profile::RaiSim},
      {"RS6005", H + terrain("3 3", "2 2", "collidable=false"), H + terrain("3 3", "2 2", "collidable=true"), Profile::RaiSim},
      {"RS6006", "", "", Profile::RaiSim},  // filled below: needs two terrains
      {"RS6007", H + IV + " grassPatch=true\n", H + IV + " grassPatch=true enabled=false\n", Profile::RaiSim},
      {"RS6008", H + box("/World/a") + box("/World/b") + "wire /World/w stiff /World/a /World/b 1 localIndexA=-1\n",
       H + box("/World/a") + box("/World/b") + "wire /World/w stiff /World/a /World/b 1 localIndexA=0\n", Profile::RaiSim},
      {"RS6009", H + "solver 80 1e-07 0.2 turbo\n", H + "solver 80 1e-07 0.2 Fast\n", Profile::RaiSim},
  };
}

Diagnostics run(const std::string& text, Profile profile, bool files = false) {
  CheckOptions o;
  o.profile = profile;
  o.checkFiles = files;
  o.fileExists = [](const std::string&) { return false; };
  Document doc;
  return validateText(text, o, doc);
}

std::string describe(const Diagnostics& ds) {
  std::string s;
  for (const Diagnostic& d : ds) s += d.code + " " + std::to_string(d.line) + ":" + std::to_string(d.column) + " " + d.message + "\n";
  return s;
}

bool has(const Diagnostics& ds, std::string_view code) {
  for (const Diagnostic& d : ds)
    if (d.code == code) return true;
  return false;
}

TEST(CheckCases, EachCodeTriggersOnItsSceneAndNotOnTheFineOne) {
  std::vector<Case> all = cases();
  for (Case& c : all) {
    if (std::string_view(c.code) == "RS6006") {
      // Two terrains so the layer's parent exists, but its own comes later.
      c.bad = H + terrain() + "terrain_splat_layer /World/u weights=\n" + "terrain_region /World/u 3 3 2 2 0 0 0\n";
      c.good = H + terrain() + "terrain_region /World/u 3 3 2 2 0 0 0\n" + "terrain_splat_layer /World/u weights=\n";
    }
    SCOPED_TRACE(c.code);
    Diagnostics bad = run(c.bad, c.profile);
    EXPECT_TRUE(has(bad, c.code)) << describe(bad);
    for (const Diagnostic& d : bad) {
      const CheckInfo* info = checkInfo(d.code);
      ASSERT_NE(info, nullptr) << d.code << " is not in the code table";
      EXPECT_EQ(d.severity, info->severity) << d.code;
      EXPECT_GT(d.line, 0u) << d.code;
    }
    Diagnostics good = run(c.good, c.profile);
    EXPECT_TRUE(good.empty()) << describe(good);
  }
}

TEST(CheckCases, EveryCodeOfTheValidatorHasACase) {
  std::set<std::string> covered{"RS5001"};  // check_files_test.cpp
  covered.insert("RS1010");                  // needs a 4 GiB input; loader_test covers the limit
  for (const char* c : {"RS1201", "RS1202", "RS1203", "RS1204", "RS1205", "RS1206", "RS1207", "RS1208"})
    covered.insert(c);  // the project file's codes: project_test.cpp has a case for each
  for (const Case& c : cases()) covered.insert(c.code);
  // Codes of the other layers have their cases beside them (tests/scene ...).
  for (const CheckInfo& info : checkTable()) {
    if (info.layer != CheckLayer::Core) continue;
    EXPECT_TRUE(covered.count(std::string(info.code))) << info.code;
  }
}

TEST(CheckCases, ACameraOnABodyIsNoRS3007) {
  // A camera whose parentGroupId names a body rides on it (README): meant.
  const std::string onBox = "camera /World/c 0 0 0 1 0 0 0 60 0.1 100 640 480 rgb true parentGroupId=/World/p\n";
  EXPECT_FALSE(has(run(H + box("/World/p") + onBox, Profile::Engine2), "RS3007"));
  const std::string robot = "articulated_resource res R r.urdf\narticulated /World/p res 0 0 0 1 0 0 0 true true\n";
  EXPECT_FALSE(has(run(H + robot + onBox, Profile::Engine2), "RS3007"));
  // Other parents and other kinds keep the warning.
  const std::string onLight = "camera /World/c 0 0 0 1 0 0 0 60 0.1 100 640 480 rgb true parentGroupId=/World/l\n";
  EXPECT_TRUE(has(run(H + "light /World/l 0 0 -1 1\n" + onLight, Profile::Engine2), "RS3007"));
  EXPECT_TRUE(has(run(H + box("/World/p") + box("/World/a", "parentGroupId=/World/p"), Profile::Engine2), "RS3007"));
}

TEST(CheckCases, NoObjectRadiusOrMassCheckInCore) {
  // The scene model decides what a body's size and mass mean (RS7003,
  // RS4008 in lib/scene); core's validator alone stays quiet about them.
  EXPECT_TRUE(run(H + box("/World/a", "", "0", "1 0 0 0", "engine_default", "default", "dynamic", "-1"),
                  Profile::Engine2)
                  .empty());
}

}  // namespace
}  // namespace rscene
