// The scene model's checks (scene/check.hpp) through rscene-validate's full
// check (scene/validate.hpp): each code triggers on its scene and not on a
// fine one, and a condition core and scene both see is reported once.
#include "scene/check.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/loader.hpp"
#include "scene/validate.hpp"

namespace rscene {
namespace {

const std::string H = "raisim_engine_scene 2\n";

// An object in the 25-field layout.
std::string object(const std::string& prim, const std::string& scale = "1 1 1", const std::string& radius = "0.5",
                   const std::string& mass = "1", const std::string& mode = "dynamic", const std::string& keys = "",
                   const std::string& path = "/World/a", const std::string& mesh = "-") {
  return "object " + path + " " + prim + " 0 0 1 1 0 0 0 " + scale + " " + radius + " 1 " + mass +
         " default engine_default false true false " + mesh + " " + mode + " true 1 18446744073709551615" +
         (keys.empty() ? "" : " " + keys) + "\n";
}
std::string replaced(std::string s, const std::string& from, const std::string& to) {
  return s.replace(s.find(from), from.size(), to);
}
const std::string K = "compound /World/k 0 0 1 1 0 0 0 1 1 1 2 dynamic true true\n";
// A static ground at z = 0.
const std::string G = "object /World/g ground 0 0 0 1 0 0 0 10 10 1 1 0 0 default engine_default false true true - static true 1 18446744073709551615\n";
// A 3 x 3 x 3 box fill of grains (radius 0.05, spacing 0.1) stable at the
// default time step in 4 substeps, with `keys` after (a later key wins).
std::string granular(const std::string& keys, const std::string& substeps = "4", const std::string& radius = "0.05",
                     const std::string& spacing = "0.1") {
  return H + "granular /World/S sand 0 0 0.2 1 0 0 0 1 1 1 boxMin=0,0,0 boxMax=0.3,0.3,0.3 radius=" + radius +
         " spacing=" + spacing + " substeps=" + substeps + " " + keys + "\n";
}
std::string deformable(const std::string& keys) {
  return H + "deformable /World/D cloth present.obj 0 0 1 1 0 0 0 1 1 1 " + keys + "\n";
}
std::string child(const std::string& prim, const std::string& keys) {
  return "compound_child /World/k " + prim + " 0 0 0 1 0 0 0 1 1 1 " + keys + "\n";
}

Diagnostics validate(const std::string& text, bool files = false) {
  CheckOptions o;
  o.checkFiles = files;
  o.fileExists = [](const std::string& p) { return p.find("present") != std::string::npos; };
  Document doc;
  return validateScene(text, o, doc);
}

std::string describe(const Diagnostics& ds) {
  std::string s;
  for (const Diagnostic& d : ds)
    s += d.code + " " + std::to_string(d.line) + ":" + std::to_string(d.column) + " " + d.message + "\n";
  return s;
}

std::vector<std::string> codes(const Diagnostics& ds) {
  std::vector<std::string> out;
  for (const Diagnostic& d : ds) out.push_back(d.code);
  return out;
}

struct Case {
  const char* code;
  std::string bad, good;
  bool files = false;
};

std::vector<Case> cases() {
  const std::string beside = replaced(object("box", "1 1 1", "0.5", "1", "dynamic", "", "/World/b"), " 0 0 1 ", " 2 0 1 ");
  return {
      {"RS4008", H + object("box", "1 1 1", "0.5", "0"), H + object("box", "1 1 1", "0.5", "0", "static")},
      {"RS7001", H + "point_cloud /World/p points=0,0,0;1,1,1 colors=1,0,0\n",
       H + "point_cloud /World/p points=0,0,0;1,1,1 colors=1,0,0;0,1,0\n"},
      {"RS7003", H + object("box", "1 0 1"), H + object("box", "1 2 1")},
      {"RS7004", H + object("mesh"), H + object("mesh", "1 1 1", "0.5", "1", "dynamic", "", "/World/a", "present.obj")},
      {"RS7008", H + "time_step 0\n", H + "time_step 0.001\n"},
      {"RS7009", H + K + child("ground", ""), H + K + child("box", "")},
      {"RS7020", H + object("box", "1 1 1", "0.5", "4.9e-324"), H + object("box", "1 1 1", "0.5", "1e-3")},
      {"RS7022", H + "time_step 1e-12\n", H + "time_step 1e-9\n"},
      {"RS7090", H + object("box", "1 1 1", "0.5", "1", "dynamic", "customInertia=true inertiaDiagonal=0.1,0,0.1"),
       H + object("box", "1 1 1", "0.5", "1", "dynamic", "customInertia=true inertiaDiagonal=0.1,1e15,0.1")},
      {"RS7090", H + "compound /World/k 0 0 1 1 0 0 0 1 1 1 2 dynamic true true inertiaDiagonal=1,1,-1\n" + child("box", ""),
       H + "compound /World/k 0 0 1 1 0 0 0 1 1 1 2 dynamic true true inertiaDiagonal=1,1,1\n" + child("box", "")},
      // Issue 10: validate refuses what would make rscene-sim stop with RS7024.
      {"RS7020", H + object("box", "1 1 1", "0.5", "1e300"), H + object("box", "1 1 1", "0.5", "1e15")},
      {"RS7022", H + "time_step 1e300\n", H + "time_step 1\n"},
      {"RS7026", H + "gravity 0 0 -1e300\n", H + "gravity 0 0 -1e12\n"},
      {"RS7026", H + "terrain_region /World/T 3 3 10 10 0 0 0 heights=0,0,0,0,1e308,0,0,0,0\n",
       H + "terrain_region /World/T 3 3 10 10 0 0 0 heights=0,0,0,0,1e12,0,0,0,0\n"},
      {"RS7027", H + "solver 2147483647 0 0.2 accurate\n", H + "solver 10000 0 0.2 accurate\n"},
      {"RS7027", H + "contact_material default default -1 0 0 0 0 0 0\n",
       H + "contact_material default default 0.8 0 0 0 0 0 0\n"},
      // (a spring's ends collide: /World/b beside /World/a, not inside it, RS7013)
      {"RS7027",
       H + object("box") + beside + "wire /World/w compliant /World/a /World/b 1 stiffness=1e308\n",
       H + object("box") + beside + "wire /World/w compliant /World/a /World/b 1 stiffness=1e15\n"},
      {"RS7028", H + "camera /World/C 0 0 0 1 0 0 0 45 0.05 200 -1 10 rgb true\n",
       H + "camera /World/C 0 0 0 1 0 0 0 45 0.05 200 16384 10 rgb true\n"},
      {"RS7026", H + object("box", "1e300 1 1"), H + object("box", "1e12 1 1")},
      {"RS7026",
       H + object("box") + object("box", "1 1 1", "0.5", "1", "dynamic", "", "/World/b") +
           "wire /World/w stiff /World/a /World/b 1 localPositionA=1e308,0,0\n",
       H + object("box") + object("box", "1 1 1", "0.5", "1", "dynamic", "", "/World/b") +
           "wire /World/w stiff /World/a /World/b 1 localPositionA=1e12,0,0\n"},
      // Issue 23: the granular and deformable rules are the scene model's,
      // so validate reports what sim and render refuse, at the same key.
      {"RS7088", granular("normalDamping=-1"), granular("normalDamping=1")},
      {"RS7088", granular("", "0"), granular("", "1000")},
      {"RS7082", granular("maxParticles=10"), granular("maxParticles=27")},
      {"RS7082", granular("", "4", "0"), granular("", "4", "0.04")},
      {"RS7089", granular("", "4", "0.05", "0.04"), granular("", "4", "0.05", "0.1")},
      {"RS7087", granular("normalStiffness=1e12"), granular("normalStiffness=1e5")},
      {"RS7086", granular("", "1"), granular("", "3")},
      // Hostile input round two: grains inside the ground (a plane at z = 1
      // over a bed at 0.2), cohesion whose well is deeper than the contacts hold.
      {"RS7091", H + object("ground", "1 1 1", "0.5", "0", "static", "", "/World/G") + granular("").substr(H.size()),
       H + "object /World/G ground 0 0 -1 1 0 0 0 1 1 1 0.5 1 0 default engine_default false true false - static true 1 "
           "18446744073709551615\n" + granular("").substr(H.size())},
      {"RS7092", granular("cohesionStiffness=1e9 cohesionMaxDistance=0.05"),
       granular("cohesionStiffness=10 cohesionMaxDistance=0.05")},
      // Hostile input round two, trial: grains may not start faster than
      // 1e4 m/s (velocity, or a spin's surface speed: radius 0.05 here).
      {"RS7088", granular("velocity=1e9,0,0"), granular("velocity=1e4,0,0")},
      {"RS7088", granular("angularVelocity=0,0,3e5"), granular("angularVelocity=0,0,1e5")},
      // A 1000 kg crate on a 1 kg one sinks through it (RS7014, at the
      // heavy one's mass); 100:1 holds.
      {"RS7014",
       H + G + replaced(object("box", "1 1 1", "0.5", "1", "dynamic", "", "/World/light"), " 0 0 1 ", " 0 0 0.5 ") +
           replaced(object("box", "1 1 1", "0.5", "1000", "dynamic", "", "/World/heavy"), " 0 0 1 ", " 0 0 1.5 "),
       H + G + replaced(object("box", "1 1 1", "0.5", "1", "dynamic", "", "/World/light"), " 0 0 1 ", " 0 0 0.5 ") +
           replaced(object("box", "1 1 1", "0.5", "100", "dynamic", "", "/World/heavy"), " 0 0 1 ", " 0 0 1.5 ")},
      // A dynamic body starting 100 m under the ground (RS7015), not a
      // run-time "fell below" (RS7012).
      {"RS7015", H + G + replaced(object("box"), " 0 0 1 ", " 0 0 -100 "), H + G + replaced(object("box"), " 0 0 1 ", " 0 0 0.5 ")},
      {"RS7081", deformable("totalMass=0"), deformable("totalMass=2")},
      {"RS7081", deformable("particleMode=filled particleSpacing=0"), deformable("particleMode=filled")},
      // One outputPath rule for validate, sim and render (issue 23): a NUL
      // would cut the name (two views, one file), a camera writes a PNG file.
      {"RS7069", H + "camera /World/C 0 0 0 1 0 0 0 45 0.05 200 64 48 rgb true outputPath=a.png%00x\n",
       H + "camera /World/C 0 0 0 1 0 0 0 45 0.05 200 64 48 rgb true outputPath=a.png\n"},
      {"RS7069", H + "camera /World/C 0 0 0 1 0 0 0 45 0.05 200 64 48 rgb true outputPath=shots/a.jpg\n",
       H + "camera /World/C 0 0 0 1 0 0 0 45 0.05 200 64 48 rgb true outputPath=shots/a.PNG\n"},
      {"RS7069", H + "camera /World/C 0 0 0 1 0 0 0 45 0.05 200 64 48 rgb true outputPath=shots/\n",
       H + "camera /World/C 0 0 0 1 0 0 0 45 0.05 200 64 48 rgb true outputPath=shots/a\n"},
      {"RS7004", "raisim_engine_scene 2\ndeformable /World/D cloth - 0 0 1 1 0 0 0 1 1 1\n", deformable("")},
      {"RS2006", deformable("solverMode=gauss"), deformable("solverMode=PBD")},
      {"RS2006", granular("normalContactModel=hooke"), granular("normalContactModel=LINEAR")},
      {"RS7011",
       H + object("box") + "point_cloud /World/r points=0,0,0\n" + "wire /World/w stiff /World/a /World/r 1\n",
       H + object("box") + object("box", "1 1 1", "0.5", "1", "dynamic", "", "/World/b") +
           "wire /World/w stiff /World/a /World/b 1\n"},
  };
}

TEST(SceneCheck, EachCodeTriggersOnItsSceneAndNotOnTheFineOne) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.code);
    Diagnostics bad = validate(c.bad, c.files);
    EXPECT_EQ(codes(bad), std::vector<std::string>{c.code}) << describe(bad);
    for (const Diagnostic& d : bad) {
      const CheckInfo* info = checkInfo(d.code);
      ASSERT_NE(info, nullptr) << d.code;
      EXPECT_EQ(d.severity, info->severity);
      EXPECT_GT(d.line, 0u);
      EXPECT_GT(d.column, 0u);
    }
    Diagnostics good = validate(c.good, c.files);
    EXPECT_TRUE(good.empty()) << describe(good);
  }
}

// One typo, one error (issue 23): a body record whose value does not parse
// is not judged again by the model, which would read the fallback.
TEST(SceneCheck, AValueThatDoesNotParseIsOneErrorNotAlsoTheModels) {
  struct Typo {
    std::string text, code;
  };
  const Typo typos[] = {
      {H + object("box", "1 0.8x 1"), "RS2001"},  // not also a zero-size box (RS7003)
      {H + object("sphere", "1 1 1", "0.5q"), "RS2001"},  // not also a zero radius
      {H + object("box", "1 1 1", "0.5", "2kg"), "RS2001"},  // not also a massless body (RS4008)
      {granular("", "4", "0.05", "0.043m"), "RS2001"},  // not also a fill past maxParticles (RS7082)
      {granular("normalStiffness=5e4N", "1"), "RS2001"},  // not also substeps raised (RS7086)
      {"raisim_engine_scene 2\ntime_step 0.002s\n" + granular("", "1").substr(H.size()), "RS2001"},
  };
  for (const Typo& t : typos) {
    SCOPED_TRACE(t.text);
    Diagnostics found = validate(t.text);
    EXPECT_EQ(codes(found), std::vector<std::string>{t.code}) << describe(found);
  }
}

// With --check-files, validate judges a deformable with its mesh as sim
// does: through the SurfaceReader the tool passes (here one in memory).
TEST(SceneCheck, ADeformableIsJudgedWithItsMeshOnlyWithCheckFiles) {
  const std::string text = deformable("pinnedVertices=0,7");
  SurfaceReader triangle = [](const std::string&, TriangleSurface& out, std::string&) {
    out.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    out.triangles = {{0, 1, 2}};
    return true;
  };
  SurfaceReader broken = [](const std::string&, TriangleSurface&, std::string& error) {
    error = "line 3: face index 9 is past the 3 vertices";
    return false;
  };
  auto run = [&](const SurfaceReader& reader, bool files) {
    CheckOptions o;
    o.checkFiles = files;
    o.fileExists = [](const std::string& p) { return p.find("present") != std::string::npos; };
    Document doc;
    CollectDiagnostics all;
    validateScene(text, o, doc, all, {}, reader);
    return all.all;
  };
  Diagnostics pinned = run(triangle, true);
  ASSERT_EQ(codes(pinned), std::vector<std::string>{"RS7081"}) << describe(pinned);
  EXPECT_NE(pinned[0].message.find("pinnedVertices 7 is not a vertex"), std::string::npos) << pinned[0].message;
  EXPECT_EQ(pinned[0].column, text.find("0,7") - H.size() + 1);  // at the value, as every key error
  Diagnostics bad = run(broken, true);
  ASSERT_EQ(codes(bad), std::vector<std::string>{"RS7080"}) << describe(bad);
  EXPECT_EQ(bad[0].column, text.find("present.obj") - H.size() + 1);
  EXPECT_TRUE(run(broken, false).empty());  // without --check-files no file is read
}

// With --check-files, validate reads each body mesh as sim and render do
// (the MeshReader the tool passes: here one in memory).
TEST(SceneCheck, ABodyMeshThatDoesNotReadIsRS7007OnlyWithCheckFiles) {
  const std::string text = H + object("mesh", "1 1 1", "0.5", "1", "dynamic", "", "/World/a", "present.obj");
  MeshReader broken = [](const std::string&, std::string& error) {
    error = "no triangles in mesh file";
    return false;
  };
  auto run = [&](bool files) {
    CheckOptions o;
    o.checkFiles = files;
    o.fileExists = [](const std::string& p) { return p.find("present") != std::string::npos; };
    Document doc;
    CollectDiagnostics all;
    validateScene(text, o, doc, all, {}, {}, broken);
    return all.all;
  };
  Diagnostics bad = run(true);
  ASSERT_EQ(codes(bad), std::vector<std::string>{"RS7007"}) << describe(bad);
  EXPECT_EQ(bad[0].column, text.find("present.obj") - H.size() + 1);
  EXPECT_TRUE(run(false).empty());
}

TEST(SceneCheck, EveryCodeOfTheSceneLayerHasACase) {
  std::set<std::string> covered{"RS5001",   // MissingCollisionMeshIsReportedOnceWithCheckFiles
                                "RS7080",   // ADeformableIsJudgedWithItsMeshOnlyWithCheckFiles
                                "RS7007",   // ABodyMeshThatDoesNotReadIsRS7007OnlyWithCheckFiles
                                "RS7021",   // AnOrientationThatDoesNotNormaliseIsRefused
                                // sensor_check_test.cpp: SensorCheck.EachBoundFiresAtItsFieldAndNotWithinIt
                                "RS7064", "RS7065", "RS7066", "RS7067", "RS7068", "RS7069",
                                // SensorCheck.ParentObjectMustNameABody, .TwoEnabledSensorsWithOneOutputPath
                                "RS7063", "RS7070",
                                // SensorCheck.OrthoScaleFlatLidarAndUnusedSegmentation
                                "RS7072", "RS7073", "RS7074"};
  for (const Case& c : cases()) covered.insert(c.code);
  for (const CheckInfo& info : checkTable()) {
    if (info.layer != CheckLayer::Scene) continue;
    EXPECT_TRUE(covered.count(std::string(info.code))) << info.code;
  }
}

// An orientation that does not normalise is RS7021 (an error: no simulator
// can use it) beside the validator's RS4010 warning for any non-unit length.
TEST(SceneCheck, AnOrientationThatDoesNotNormaliseIsRefused) {
  Diagnostics ds = validate(H + replaced(object("box"), "0 0 1 1 0 0 0", "0 0 1 1e308 1e308 0 0"));
  EXPECT_EQ(codes(ds), (std::vector<std::string>{"RS4010", "RS7021"})) << describe(ds);
  EXPECT_EQ(codes(validate(H + replaced(object("box"), "0 0 1 1 0 0 0", "0 0 1 2 0 0 0"))),
            std::vector<std::string>{"RS4010"});
}

TEST(SceneCheck, ReportsAtTheFieldAUserWouldChange) {
  Diagnostics ds = validate(H + object("box", "1 1 1", "0.5", "0"));
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].line, 2u);
  EXPECT_EQ(ds[0].field, "mass");
  EXPECT_EQ(ds[0].message, "dynamic body '/World/a' needs a mass > 0");
  ds = validate(H + object("sphere", "-1 1 1"));
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS7003");
  EXPECT_EQ(ds[0].field, "radius");
}

TEST(SceneCheck, IssueCasesHaveOneVerdict) {
  // Negative scale and zero box sides are zero or negative physical sizes.
  EXPECT_EQ(codes(validate(H + object("box", "-1 1 1"))), std::vector<std::string>{"RS7003"});
  EXPECT_EQ(codes(validate(H + object("sphere", "1 1 1", "-0.5"))), std::vector<std::string>{"RS7003"});
  EXPECT_EQ(codes(validate(H + "time_step -0.01\n")), std::vector<std::string>{"RS7008"});
  // A half_space is static like a ground (compat-notes.md): its mass is unused.
  EXPECT_TRUE(validate(H + object("half_space", "1 1 1", "0.5", "0")).empty());
  EXPECT_EQ(codes(validate(H + K + child("sphere", ""))), std::vector<std::string>{"RS7003"});
  EXPECT_TRUE(validate(H + K + child("sphere", "radius=0.2")).empty());
}

TEST(SceneCheck, CompoundChildSizesAreInTheCompoundsScale) {
  // A box child without a size is its scale: a zero compound scale is a
  // zero side, as the simulator would build it.
  std::string k0 = "compound /World/k 0 0 1 1 0 0 0 1 0 1 2 dynamic true true\n";
  EXPECT_EQ(codes(validate(H + k0 + child("box", ""))), std::vector<std::string>{"RS7003"});
  EXPECT_TRUE(validate(H + K + child("box", "")).empty());
}

TEST(SceneCheck, MissingCollisionMeshIsReportedOnceWithCheckFiles) {
  std::string text = H + object("mesh", "1 1 1", "0.5", "1", "dynamic", "", "/World/a", "gone.obj");
  EXPECT_TRUE(validate(text).empty());
  Diagnostics ds = validate(text, true);
  EXPECT_EQ(codes(ds), std::vector<std::string>{"RS5001"}) << describe(ds);
}

TEST(SceneCheck, WireToAMissingBodyIsReportedOnce) {
  Diagnostics ds = validate(H + object("box") + "wire /World/w stiff /World/a nobody 1\n");
  EXPECT_EQ(codes(ds), std::vector<std::string>{"RS3012"}) << describe(ds);
}

TEST(SceneCheck, CheckSceneAloneFindsWhatSimRefuses) {
  LoadResult loaded = parse(H + object("box", "1 1 1", "0.5", "0") + object("box", "1 0 1", "0.5", "1", "dynamic", "", "/World/b"));
  ASSERT_TRUE(loaded.ok());
  Scene scene;
  Diagnostics ds;
  ASSERT_TRUE(buildScene(loaded.document, {}, scene, ds));
  EXPECT_FALSE(checkScene(loaded.document, scene, {}, ds));
  EXPECT_EQ(codes(ds), (std::vector<std::string>{"RS4008", "RS7003"}));
}

// rscene-validate builds only the bodies checkScene() needs, and skips
// objects that cannot fail it; wires to them still resolve.
TEST(SceneCheck, BodiesOnlyBuildKeepsWhatWiresName) {
  std::string visual = object("box", "1 1 1", "0.5", "1", "visual_only", "", "/World/v");
  std::string hidden = object("box", "1 1 1", "0.5", "1", "dynamic", "", "/World/h");
  hidden.replace(hidden.find(" true 1 "), 8, " false 1 ");  // collidable=false: visual-only
  std::string wires = "wire /World/w1 stiff /World/a /World/v 1\nwire /World/w2 stiff /World/a /World/h 1\n"
                      "wire /World/w3 stiff /World/a - 1\n";
  Diagnostics ds = validate(H + object("box") + visual + hidden + wires);
  EXPECT_EQ(codes(ds), (std::vector<std::string>{"RS7011", "RS7011"})) << describe(ds);
  // (the three boxes share one place, but only /World/a collides: no RS7013)
  LoadResult loaded = parse(H + object("box") + visual + hidden + wires);
  for (bool bodiesOnly : {false, true}) {
    SceneOptions so;
    so.bodiesOnly = bodiesOnly;
    Scene scene;
    Diagnostics built;
    ASSERT_TRUE(buildScene(loaded.document, so, scene, built));
    ASSERT_EQ(scene.wires.size(), 3u);
    EXPECT_EQ(scene.wires[0].endB, WireEnd::NotSimulated);
    EXPECT_EQ(scene.wires[1].endB, WireEnd::NotSimulated);
    EXPECT_EQ(scene.wires[2].endB, WireEnd::World);
    EXPECT_EQ(scene.wires[2].endA, WireEnd::Body);
    EXPECT_TRUE(scene.wires[2].simulated());
    // The visual-only two are plain; the dynamic box is kept for the ground
    // rule (scene/start_pose.hpp).
    EXPECT_EQ(scene.objects.size(), bodiesOnly ? 1u : 3u);
  }
}

TEST(SceneCheck, FindingsMergeInLineOrder) {
  Diagnostics ds = validate(H + object("box", "1 1 1", "0.5", "0") + "objcet /World/x\n");
  EXPECT_EQ(codes(ds), (std::vector<std::string>{"RS4008", "RS3001"})) << describe(ds);
}


// RS7013 from the scene model: a dynamic primitive starting more than 1 cm
// below a ground or half_space, as rscene-sim's first step would find it.
std::string atZ(const std::string& prim, const std::string& z, const std::string& scale = "1 1 1",
                const std::string& radius = "0.5", const std::string& orientation = "1 0 0 0",
                const std::string& mask = "18446744073709551615") {
  return "object /World/b " + prim + " 0 0 " + z + " " + orientation + " " + scale + " " + radius +
         " 1 1 default engine_default false true false - dynamic true 1 " + mask + "\n";
}

int count(const Diagnostics& ds, const std::string& code) {
  int n = 0;
  for (const Diagnostic& d : ds) n += d.code == code;
  return n;
}

TEST(GroundStart, PrimitiveBelowTheGroundWarnsAtItsPosition) {
  Diagnostics ds = validate(H + G + atZ("box", "0.3"));  // 1 m box, centre 0.3: 0.2 m inside
  ASSERT_EQ(count(ds, "RS7013"), 1) << describe(ds);
  for (const Diagnostic& d : ds)
    if (d.code == "RS7013") {
      EXPECT_EQ(d.severity, Severity::Warning);
      EXPECT_EQ(d.line, 3u);
      EXPECT_NE(d.message.find("dynamic body '/World/b' starts 0.2 m inside '/World/g'"), std::string::npos) << d.message;
    }
}

TEST(GroundStart, EachPrimitiveByItsLowestPoint) {
  EXPECT_EQ(count(validate(H + G + atZ("box", "0.495")), "RS7013"), 0);  // 5 mm: contact
  EXPECT_EQ(count(validate(H + G + atZ("box", "0.5")), "RS7013"), 0);
  EXPECT_EQ(count(validate(H + G + atZ("sphere", "0.45")), "RS7013"), 1);   // radius 0.5
  EXPECT_EQ(count(validate(H + G + atZ("sphere", "0.495")), "RS7013"), 0);
  // A box turned 45 degrees about x reaches 0.5 * sqrt(2) down.
  const std::string turned = "0.9238795 0.3826834 0 0";
  EXPECT_EQ(count(validate(H + G + atZ("box", "0.6", "1 1 1", "0.5", turned)), "RS7013"), 1);
  EXPECT_EQ(count(validate(H + G + atZ("box", "0.71", "1 1 1", "0.5", turned)), "RS7013"), 0);
  // Capsule (radius 0.2, height 1 between the caps' centres) upright: 0.7 down.
  EXPECT_EQ(count(validate(H + G + atZ("capsule", "0.65", "1 1 1", "0.2")), "RS7013"), 1);
  EXPECT_EQ(count(validate(H + G + atZ("capsule", "0.7", "1 1 1", "0.2")), "RS7013"), 0);
  // Cylinder (radius 0.2, height 1) lying on its side: 0.2 down.
  const std::string lying = "0.7071068 0.7071068 0 0";
  EXPECT_EQ(count(validate(H + G + atZ("cylinder", "0.15", "1 1 1", "0.2", lying)), "RS7013"), 1);
  EXPECT_EQ(count(validate(H + G + atZ("cylinder", "0.2", "1 1 1", "0.2", lying)), "RS7013"), 0);
  // A half_space is a ground too; static bodies and no ground at all are not judged.
  EXPECT_EQ(count(validate(H + replaced(G, " ground ", " half_space ") + atZ("sphere", "0")), "RS7013"), 1);
  EXPECT_EQ(count(validate(H + G + replaced(atZ("sphere", "0"), " dynamic ", " static ")), "RS7013"), 0);
  EXPECT_EQ(count(validate(H + atZ("sphere", "-3")), "RS7013"), 0);
}

TEST(GroundStart, APairTheFilterSeparatesIsNoOverlap) {
  EXPECT_EQ(count(validate(H + G + atZ("sphere", "0", "1 1 1", "0.5", "1 0 0 0", "0")), "RS7013"), 0);
}

TEST(GroundStart, UnderAParentTheWorldPoseCounts) {
  // Under a static body 3 m up the sphere at z = 0.45 stands 3.45 m up
  // (the parent collides with nothing: the pair rule would judge them).
  const std::string parent =
      replaced(replaced(atZ("box", "3", "1 1 1", "0.5", "1 0 0 0", "0"), " dynamic ", " static "), "/World/b", "/World/up");
  std::string lifted = replaced(atZ("sphere", "0.45"), "\n", " parentGroupId=up\n");
  Diagnostics ds = validate(H + G + replaced(parent, "\n", " id=up\n") + lifted);
  EXPECT_EQ(count(ds, "RS7013"), 0) << describe(ds);
  EXPECT_EQ(count(validate(H + G + atZ("sphere", "0.45")), "RS7013"), 1);
}


// RS7013 from the scene model's pair rule: two dynamic box, sphere or
// capsule objects starting more than 1 cm inside each other.
std::string body(const std::string& path, const std::string& prim, const std::string& xyz,
                 const std::string& scale = "1 1 1", const std::string& radius = "0.5",
                 const std::string& orientation = "1 0 0 0", const std::string& mode = "dynamic",
                 const std::string& group = "1", const std::string& mask = "18446744073709551615") {
  return "object " + path + " " + prim + " " + xyz + " " + orientation + " " + scale + " " + radius +
         " 1 1 default engine_default false true false - " + mode + " true " + group + " " + mask + "\n";
}
// The RS7013 messages, one per line.
std::string overlaps(const std::string& text) {
  std::string out;
  for (const Diagnostic& d : validate(text))
    if (d.code == "RS7013") out += std::to_string(d.line) + ": " + d.message.substr(0, d.message.find(';')) + "\n";
  return out;
}

TEST(BodyStart, TwoBoxesNameBothAndTheDepth) {
  // The issue's crate: a 1 m cube on the ground, a box 2.6 cm inside it.
  Diagnostics ds = validate(H + G + body("/World/cube", "box", "0 0 0.5") + body("/World/box", "box", "0.2 0 1.474"));
  ASSERT_EQ(count(ds, "RS7013"), 1) << describe(ds);
  for (const Diagnostic& d : ds)
    if (d.code == "RS7013") {
      EXPECT_EQ(d.severity, Severity::Warning);
      EXPECT_EQ(d.line, 4u);  // the later of two dynamic bodies
      EXPECT_NE(d.message.find("dynamic body '/World/box' starts 0.026 m inside '/World/cube'"), std::string::npos)
          << d.message;
    }
  // Resting on it (5 mm: contact) and touching: nothing.
  EXPECT_EQ(overlaps(H + G + body("/World/cube", "box", "0 0 0.5") + body("/World/box", "box", "0.2 0 1.495")), "");
  EXPECT_EQ(overlaps(H + G + body("/World/cube", "box", "0 0 0.5") + body("/World/box", "box", "1 0 0.5")), "");
}

TEST(BodyStart, EachPairOfShapesByItsExactDepth) {
  auto one = [](const std::string& a, const std::string& b) { return overlaps(H + a + b); };
  const std::string unit = body("/World/a", "box", "0 0 0");
  // Spheres (radius 0.5): centres 0.98 apart are 2 cm in, 0.995 apart 5 mm.
  EXPECT_EQ(one(body("/World/a", "sphere", "0 0 0"), body("/World/b", "sphere", "0.98 0 0")),
            "3: dynamic body '/World/b' starts 0.02 m inside '/World/a'\n");
  EXPECT_EQ(one(body("/World/a", "sphere", "0 0 0"), body("/World/b", "sphere", "0 0.995 0")), "");
  // Sphere and box: by the nearest point of the box; a centre inside the
  // box must leave through the nearest face.
  EXPECT_EQ(one(unit, body("/World/b", "sphere", "0.98 0 0")), "3: dynamic body '/World/b' starts 0.02 m inside '/World/a'\n");
  EXPECT_EQ(one(unit, body("/World/b", "sphere", "0.995 0 0")), "");
  EXPECT_EQ(one(unit, body("/World/b", "sphere", "0.9 0.9 0")), "");  // 0.566 from the corner
  EXPECT_EQ(one(unit, body("/World/b", "sphere", "0.8 0.8 0")), "3: dynamic body '/World/b' starts 0.0757 m inside '/World/a'\n");
  EXPECT_EQ(one(unit, body("/World/b", "sphere", "0.3 0 0")), "3: dynamic body '/World/b' starts 0.7 m inside '/World/a'\n");
  // Boxes: a box turned 45 degrees about z reaches 0.707 along x.
  const std::string turned = "0.9238795 0 0 0.3826834";
  EXPECT_EQ(one(unit, body("/World/b", "box", "1.177 0 0", "1 1 1", "0.5", turned)),
            "3: dynamic body '/World/b' starts 0.0301 m inside '/World/a'\n");
  EXPECT_EQ(one(unit, body("/World/b", "box", "1.2 0 0", "1 1 1", "0.5", turned)), "");
  // Two edges crossing: b turned 45 degrees about x and about z sits on a
  // turned edge; only the edge-edge axis sees them apart.
  EXPECT_EQ(one(body("/World/a", "box", "0 0 0", "1 1 1", "0.5", "0.9238795 0.3826834 0 0"),
                body("/World/b", "box", "0 0 1.42", "1 1 1", "0.5", "0.9238795 0 0.3826834 0")),
            "");
  EXPECT_EQ(one(body("/World/a", "box", "0 0 0", "1 1 1", "0.5", "0.9238795 0.3826834 0 0"),
                body("/World/b", "box", "0 0 1.38", "1 1 1", "0.5", "0.9238795 0 0.3826834 0")),
            "3: dynamic body '/World/b' starts 0.0342 m inside '/World/a'\n");
  // Capsules (radius 0.2, 1 m between the caps' centres): side by side
  // 0.38 apart, and crossing (each must leave by both radii).
  const std::string up = body("/World/a", "capsule", "0 0 0", "1 1 1", "0.2");
  const std::string lying = "0.7071068 0 0.7071068 0";  // its axis along x
  EXPECT_EQ(one(up, body("/World/b", "capsule", "0.38 0 0", "1 1 1", "0.2")),
            "3: dynamic body '/World/b' starts 0.02 m inside '/World/a'\n");
  EXPECT_EQ(one(up, body("/World/b", "capsule", "0.395 0 0", "1 1 1", "0.2")), "");
  EXPECT_EQ(one(up, body("/World/b", "capsule", "0 0 0.3", "1 1 1", "0.2", lying)),
            "3: dynamic body '/World/b' starts 0.4 m inside '/World/a'\n");
  EXPECT_EQ(one(up, body("/World/b", "sphere", "0 0.2 0.8")), "3: dynamic body '/World/b' starts 0.339 m inside '/World/a'\n");
  // Capsule and box: on its cap, across the box (out sideways by half a
  // side and the radius), and lying on a face.
  EXPECT_EQ(one(unit, body("/World/b", "capsule", "0 0 1.18", "1 1 1", "0.2")),
            "3: dynamic body '/World/b' starts 0.02 m inside '/World/a'\n");
  EXPECT_EQ(one(unit, body("/World/b", "capsule", "0 0 1.195", "1 1 1", "0.2")), "");
  EXPECT_EQ(one(unit, body("/World/b", "capsule", "0 0 0", "1 1 1", "0.2")),
            "3: dynamic body '/World/b' starts 0.7 m inside '/World/a'\n");
  EXPECT_EQ(one(unit, body("/World/b", "capsule", "0.3 0 0.68", "1 1 1", "0.2", lying)),
            "3: dynamic body '/World/b' starts 0.02 m inside '/World/a'\n");
  EXPECT_EQ(one(unit, body("/World/b", "capsule", "1.6 0 0.5", "1 1 1", "0.2", lying)), "");  // beyond its end
}

TEST(BodyStart, PairsThatNeverCollideAreNotJudged) {
  const std::string a = body("/World/a", "box", "0 0 0");
  const std::string in = body("/World/b", "box", "0.5 0 0");  // half inside
  EXPECT_NE(overlaps(H + a + in), "");
  // Neither dynamic.
  EXPECT_EQ(overlaps(H + replaced(a, " dynamic ", " static ") + replaced(in, " dynamic ", " kinematic ")), "");
  // A static or kinematic partner is rscene-sim's (validate does not build them).
  EXPECT_EQ(overlaps(H + replaced(a, " dynamic ", " static ") + in), "");
  // Visual only, collidable=false, or groups outside each other's masks.
  EXPECT_EQ(overlaps(H + replaced(a, " dynamic ", " visual_only ") + in), "");
  auto b = [](const std::string& group, const std::string& mask) {
    return body("/World/b", "box", "0.5 0 0", "1 1 1", "0.5", "1 0 0 0", "dynamic", group, mask);
  };
  EXPECT_EQ(overlaps(H + replaced(a, " dynamic true ", " dynamic false ") + in), "");
  EXPECT_EQ(overlaps(H + a + b("2", "2")), "");  // b's mask leaves a's group (1) out
  EXPECT_EQ(overlaps(H + replaced(a, " 18446744073709551615", " 18446744073709551613") + b("2", "3")), "");  // a's leaves b's out
  EXPECT_NE(overlaps(H + a + b("2", "3")), "");
  // A stiff wire joins them (rscene-sim does not collide its ends); a
  // compliant one is a spring and does.
  EXPECT_EQ(overlaps(H + a + in + "wire /World/w stiff /World/a /World/b 1\n"), "");
  EXPECT_NE(overlaps(H + a + in + "wire /World/w compliant /World/a /World/b 1\n"), "");
  // Shapes without an exact test are rscene-sim's: a cylinder, a mesh.
  EXPECT_EQ(overlaps(H + a + body("/World/b", "cylinder", "0.5 0 0", "1 1 1", "0.2")), "");
}

TEST(BodyStart, TheGroundRuleAndThePairRuleGiveOneWarningPerBodyNamingTheDeepest) {
  // Both below the ground and inside each other: b is 0.2 m in the
  // ground and 0.5 m in a, and is warned once, for a.
  EXPECT_EQ(overlaps(H + G + body("/World/a", "box", "0 0 0.3") + body("/World/b", "box", "0.5 0 0.3")),
            "3: dynamic body '/World/a' starts 0.2 m inside '/World/g'\n"
            "4: dynamic body '/World/b' starts 0.5 m inside '/World/a'\n");
  // deeper in the ground than in its neighbour: the ground
  EXPECT_EQ(overlaps(H + G + body("/World/a", "box", "0 0 0.3") + body("/World/b", "box", "0.9 0 0.1")),
            "3: dynamic body '/World/a' starts 0.2 m inside '/World/g'\n"
            "4: dynamic body '/World/b' starts 0.4 m inside '/World/g'\n");
}

TEST(BodyStart, APileIsOneWarningPerBodyNamingTheDeepest) {
  // Ten spheres in one place: 45 pairs, 9 warnings (each but the first
  // starts inside an earlier one), each naming the first of its deepest.
  std::string text = H;
  for (int k = 0; k < 10; ++k) text += body("/World/s" + std::to_string(k), "sphere", "0 0 0");
  Diagnostics ds = validate(text);
  EXPECT_EQ(count(ds, "RS7013"), 9) << describe(ds);
  std::set<std::uint32_t> lines;
  for (const Diagnostic& d : ds)
    if (d.code == "RS7013") lines.insert(d.line);
  EXPECT_EQ(lines.size(), 9u);
  EXPECT_EQ(lines.count(2), 0u);  // /World/s0
  EXPECT_NE(overlaps(text).find("11: dynamic body '/World/s9' starts 1 m inside '/World/s0'"), std::string::npos)
      << overlaps(text);
}

// 20,000 boxes in two layers, the upper resting 5 mm into the lower
// (contact, not overlap), side by side touching: no warning; one box
// moved 3 cm into its neighbour is the one warning, wherever it is.
TEST(BodyStart, ABroadPhaseOverTwentyThousandBoxesFindsTheOneOverlap) {
  auto scene = [](int moved) {
    std::string s = H + G;
    char line[200];
    for (int k = 0; k < 20000; ++k) {
      const int layer = k / 10000, i = k % 100, j = (k / 100) % 100;
      const double x = i + (k == moved ? 0.03 : 0.0), z = 0.5 + layer * 0.995;
      std::snprintf(line, sizeof line,
                    "object /World/b%d box %.17g %d %.17g 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true "
                    "false - %s true 1 18446744073709551615\n",
                    k, x, j, z, k % 7 == 0 ? "static" : "dynamic");
      s += line;
    }
    return s;
  };
  EXPECT_EQ(overlaps(scene(-1)), "");
  // b12345 (upper layer, i 45, j 23) moved 3 cm along x: into b12346
  // and resting 5 mm on b2345 and b2346 (contact).
  EXPECT_EQ(overlaps(scene(12345)), "12349: dynamic body '/World/b12346' starts 0.03 m inside '/World/b12345'\n");
}

// RS7014: dynamic bodies touching at start whose masses are more than
// 100 times apart, at the heavier one's mass, one warning per heavy body.
std::string weighing(const std::string& path, const std::string& xyz, const std::string& mass,
                     const std::string& mode = "dynamic", const std::string& prim = "box") {
  return replaced(body(path, prim, xyz, "1 1 1", "0.5", "1 0 0 0", mode), " 1 1 default", " 1 " + mass + " default");
}
std::string ratios(const std::string& text) {
  std::string out;
  for (const Diagnostic& d : validate(text))
    if (d.code == "RS7014") out += std::to_string(d.line) + ":" + std::to_string(d.column) + ": " + d.message + "\n";
  return out;
}

TEST(MassRatioStart, AHeavyCrateOnALightOneWarnsAtTheHeavyOnesMass) {
  // The trial's crates: 1000 kg resting on 1 kg.
  Diagnostics ds = validate(H + G + weighing("/World/light", "0 0 0.5", "1") + weighing("/World/heavy", "0 0 1.5", "1000"));
  ASSERT_EQ(count(ds, "RS7014"), 1) << describe(ds);
  for (const Diagnostic& d : ds)
    if (d.code == "RS7014") {
      EXPECT_EQ(d.severity, Severity::Warning);
      EXPECT_EQ(d.line, 4u);
      // the mass field: the 17th token of `object`
      const std::string line = weighing("/World/heavy", "0 0 1.5", "1000");
      EXPECT_EQ(d.column, line.find(" 1000 ") + 2) << d.column;
      EXPECT_EQ(d.message,
                "dynamic body '/World/heavy' (1000 kg) starts touching '/World/light' (1 kg), 1e+03 times lighter (more "
                "than 100): the contact solver cannot hold such a pair, and the heavy body sinks through the light one");
    }
  // Whichever lies on top, the warning is at the heavier body.
  EXPECT_EQ(ratios(H + G + weighing("/World/heavy", "0 0 0.5", "1000") + weighing("/World/light", "0 0 1.5", "1"))
                .substr(0, 2),
            "3:");
  // Side by side, touching, or 5 mm apart: in contact; 2 cm apart: not.
  EXPECT_NE(ratios(H + G + weighing("/World/a", "0 0 0.5", "500") + weighing("/World/b", "1.005 0 0.5", "2")), "");
  EXPECT_EQ(ratios(H + G + weighing("/World/a", "0 0 0.5", "500") + weighing("/World/b", "1.02 0 0.5", "2")), "");
  // Within the bound; a static or kinematic partner holds any mass.
  EXPECT_EQ(ratios(H + G + weighing("/World/a", "0 0 0.5", "1") + weighing("/World/b", "0 0 1.5", "100")), "");
  EXPECT_EQ(ratios(H + G + weighing("/World/a", "0 0 0.5", "1", "static") + weighing("/World/b", "0 0 1.5", "1e4")), "");
  EXPECT_EQ(ratios(H + G + weighing("/World/a", "0 0 0.5", "1", "kinematic") + weighing("/World/b", "0 0 1.5", "1e4")), "");
  // Spheres too; a heavy body on three light ones is one warning, naming the largest ratio.
  EXPECT_NE(ratios(H + G + weighing("/World/a", "0 0 0.5", "1", "dynamic", "sphere") +
                   weighing("/World/b", "0 0 1.5", "1000", "dynamic", "sphere")),
            "");
  std::string three = H + G + weighing("/World/l1", "-1 0 0.5", "2") + weighing("/World/l2", "0 0 0.5", "1") +
                      weighing("/World/l3", "1 0 0.5", "3") + replaced(weighing("/World/plank", "0 0 1.5", "1000"), " 1 1 1 ", " 3 1 1 ");
  const std::string found = ratios(three);
  EXPECT_EQ(std::count(found.begin(), found.end(), '\n'), 1) << found;
  EXPECT_NE(found.find("starts touching '/World/l2' (1 kg)"), std::string::npos) << found;
}

// RS7015: a dynamic body that starts more than 10 m under the lowest
// ground or half_space is refused at its position (rscene-sim would take
// it out of the world at its first step), not also RS7013.
TEST(BelowWorldStart, ABodyStartingTenMetresUnderTheGroundIsRefusedAtItsPosition) {
  Diagnostics ds = validate(H + G + atZ("box", "-100"));
  EXPECT_EQ(codes(ds), std::vector<std::string>{"RS7015"}) << describe(ds);
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].severity, Severity::Error);
  EXPECT_EQ(ds[0].line, 3u);
  EXPECT_EQ(ds[0].column, atZ("box", "-100").find(" 0 0 -100") + 2);
  EXPECT_EQ(ds[0].message,
            "dynamic body '/World/b' starts at z = -100, below the world's lower bound z = -10 (10 m under the lowest "
            "ground, '/World/g'): rscene-sim would take it out of the world at its first step");
  // 9.9 m under: inside the ground (RS7013, a warning), still in the world.
  EXPECT_EQ(codes(validate(H + G + atZ("box", "-9.9"))), std::vector<std::string>{"RS7013"});
  EXPECT_EQ(codes(validate(H + G + atZ("box", "-10.1"))), std::vector<std::string>{"RS7015"});
  // The lowest plane counts, whatever its filter; no plane, no bound here
  // (rscene-sim judges other static geometry); static bodies stay anywhere.
  const std::string low = replaced(replaced(G, "/World/g", "/World/low"), " 0 0 0 1 0 0 0 10", " 0 0 -200 1 0 0 0 10");
  EXPECT_EQ(count(validate(H + G + low + atZ("box", "-100")), "RS7015"), 0);
  EXPECT_EQ(count(validate(H + atZ("box", "-100")), "RS7015"), 0);
  EXPECT_EQ(count(validate(H + G + replaced(atZ("box", "-100"), " dynamic ", " static ")), "RS7015"), 0);
  // Compounds and meshes by their position.
  Diagnostics c = validate(H + G + "compound /World/k 0 0 -50 1 0 0 0 1 1 1 2 dynamic true true\n" + child("box", ""));
  EXPECT_EQ(codes(c), std::vector<std::string>{"RS7015"}) << describe(c);
}

}  // namespace
}  // namespace rscene
