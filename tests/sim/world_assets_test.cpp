// lib/sim and lib/asset: meshes through the shared cache (read once, from
// an in-memory disk), bodies left out for a missing mesh
// (--allow-missing-assets), and bodies that leave the world.
#include <gtest/gtest.h>

#include <cmath>

#include "asset/cache.hpp"
#include "core/loader.hpp"
#include "scene/scene.hpp"
#include "core/writer.hpp"
#include "sim/world.hpp"

using namespace rscene;
using namespace rscene::sim;

namespace {

std::string object(const std::string& path, const std::string& prim, double x, double y, double z,
                   const std::string& scale, double mass, const std::string& mode, const std::string& extra = "") {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "object %s %s %.17g %.17g %.17g 1 0 0 0 %s 0.5 1 %.17g default engine_default false true false - %s "
                "true 1 18446744073709551615 %s\n",
                path.c_str(), prim.c_str(), x, y, z, scale.c_str(), mass, mode.c_str(), extra.c_str());
  return buf;
}

const std::string kGround = object("/World/Ground", "ground", 0, 0, 0, "10 10 1", 0, "static");
const char* kCube =
    "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
    "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

struct Run {
  Document doc;
  Scene scene;
  Diagnostics diags;
  std::unique_ptr<World> world;
};

// Loads `body`; with `assets`, meshes come from it and missing ones are
// left out as rscene-sim --allow-missing-assets does.
std::unique_ptr<Run> make(const std::string& body, asset::AssetCache* assets = nullptr, bool allowMissing = false) {
  auto r = std::make_unique<Run>();
  LoadResult loaded = parse("raisim_engine_scene 1\n" + body);
  EXPECT_TRUE(loaded.ok());
  r->doc = std::move(loaded.document);
  SceneOptions so;
  so.baseDir = "/s";  // the scene's folder on the in-memory disk
  if (assets) so.exists = [assets](const std::string& p) { return assets->fileSystem().exists(p); };
  EXPECT_TRUE(buildScene(r->doc, so, r->scene, r->diags));
  if (allowMissing) skipBodiesWithMissingMeshes(r->doc, r->scene, *assets, r->diags);
  // checkPhysics asks the real disk whether mesh files exist: a scene on
  // the in-memory disk skips it unless missing meshes were left out.
  if (!assets || allowMissing) {
    EXPECT_TRUE(checkPhysics(r->doc, r->scene, r->diags)) << (r->diags.empty() ? "" : r->diags[0].message);
  }
  WorldOptions wo;
  wo.assets = assets;
  r->world = World::create(r->scene, r->diags, wo);
  EXPECT_TRUE(r->world);
  return r;
}

BodyState state(const World& w, const std::string& path) {
  for (const BodyState& s : w.states())
    if (s.path == path) return s;
  ADD_FAILURE() << "no body " << path;
  return {};
}

void steps(World& w, double seconds) {
  for (long i = 0, n = std::lround(seconds / w.timeStep()); i < n; ++i) w.step();
}

}  // namespace

TEST(SimAssets, TenBodiesNamingOneMeshReadItOnce) {
  MemoryFileSystem fs;
  fs.addFile("/s/cube.obj", kCube);
  asset::AssetCache cache(fs);
  std::string body = kGround;
  for (int i = 0; i < 10; ++i)
    body += object("/World/M" + std::to_string(i), "mesh", 2.0 * i, 0, 1, "0.4 0.4 0.4", 1, "dynamic",
                   "collisionMeshPath=cube.obj");
  body += object("/World/Floor", "mesh", 0, 5, 0, "1 1 1", 1, "static", "collisionMeshPath=cube.obj");
  auto r = make(body, &cache);
  EXPECT_EQ(fs.reads(), 1);
  steps(*r->world, 2);
  for (int i = 0; i < 10; ++i)  // each hull rests on the ground: hull margin 1 mm + contact slop
    EXPECT_NEAR(state(*r->world, "/World/M" + std::to_string(i)).position.z(), 0.2, 3e-3) << i;
}

TEST(SimAssets, MissingAndUnreadableMeshesAreLeftOutWithAWarning) {
  MemoryFileSystem fs;
  fs.addFile("/s/junk.obj", "this is not a mesh\n");
  asset::AssetCache cache(fs);
  std::string body = kGround + object("/World/Box", "box", 0, 0, 1, "0.4 0.4 0.4", 1, "dynamic") +
                     object("/World/Rock", "mesh", 3, 0, 1, "1 1 1", 2, "dynamic", "collisionMeshPath=rock.obj") +
                     object("/World/Junk", "mesh", 6, 0, 1, "1 1 1", 2, "dynamic", "collisionMeshPath=junk.obj") +
                     object("/World/Rock2", "mesh", 9, 0, 1, "1 1 1", 2, "static", "collisionMeshPath=rock.obj") +
                     "wire /World/W stiff /World/Box /World/Rock 1\n";
  auto r = make(body, &cache, true);
  ASSERT_EQ(r->diags.size(), 3u);
  const Diagnostic& rock = r->diags[0];
  EXPECT_EQ(rock.severity, Severity::Warning);
  EXPECT_EQ(rock.code, "RS5001");
  EXPECT_EQ(rock.line, 4u);
  EXPECT_GT(rock.column, 0u);  // at the collisionMeshPath key
  // One warning per file, at the first body naming it.
  EXPECT_EQ(rock.message, "mesh file '/s/rock.obj' does not exist; bodies '/World/Rock' and 1 other are not simulated");
  EXPECT_EQ(r->diags[1].code, "RS7007");
  EXPECT_EQ(r->diags[1].severity, Severity::Warning);
  EXPECT_EQ(r->diags[1].message.rfind("cannot read mesh '/s/junk.obj': ", 0), 0u) << r->diags[1].message;
  EXPECT_TRUE(r->diags[1].message.ends_with("; body '/World/Junk' is not simulated")) << r->diags[1].message;
  EXPECT_EQ(r->diags[2].line, 7u);  // the wire to the rock is skipped too
  EXPECT_EQ(r->diags[2].message, "wire '/World/W' is not attached: '/World/Rock' was left out for its mesh");
  EXPECT_EQ(r->world->bodyCount(), 1);
  std::string before = canonicalText(r->doc);
  steps(*r->world, 2);
  EXPECT_NEAR(state(*r->world, "/World/Box").position.z(), 0.2, 3e-3);  // the rest simulates
  r->world->writeBack(r->doc);
  std::string after = canonicalText(r->doc);
  auto line = [](const std::string& text, const std::string& path) {
    std::size_t at = text.find("object " + path + " ");
    return text.substr(at, text.find('\n', at) - at);
  };
  EXPECT_EQ(line(after, "/World/Rock"), line(before, "/World/Rock"));  // written back unchanged
  EXPECT_NE(line(after, "/World/Box"), line(before, "/World/Box"));
}

TEST(SimAssets, ACompoundWithAMissingMeshChildIsLeftOutWhole) {
  MemoryFileSystem fs;
  fs.addFile("/s/cube.obj", kCube);
  asset::AssetCache cache(fs);
  auto r = make(kGround +
                    "compound /World/C 0 0 1 1 0 0 0 1 1 1 2 dynamic true true\n"
                    "compound_child /World/C mesh -0.3 0 0 1 0 0 0 0.2 0.2 0.2 meshPath=cube.obj\n"
                    "compound_child /World/C mesh 0.3 0 0 1 0 0 0 0.2 0.2 0.2 meshPath=gone.obj\n" +
                    object("/World/Box", "box", 3, 0, 1, "0.4 0.4 0.4", 1, "dynamic"),
                &cache, true);
  ASSERT_EQ(r->diags.size(), 1u);
  EXPECT_EQ(r->diags[0].severity, Severity::Warning);
  EXPECT_EQ(r->diags[0].line, 5u);  // the child that names the missing file
  EXPECT_EQ(r->diags[0].message, "mesh file '/s/gone.obj' does not exist; body '/World/C' is not simulated");
  EXPECT_EQ(r->world->bodyCount(), 1);  // the box only
}

TEST(SimAssets, WithoutTheFlagAMissingMeshStaysAnError) {
  MemoryFileSystem fs;
  asset::AssetCache cache(fs);
  LoadResult loaded = parse("raisim_engine_scene 1\n" + object("/World/Rock", "mesh", 0, 0, 1, "1 1 1", 2, "static",
                                                               "collisionMeshPath=rock.obj"));
  Scene scene;
  Diagnostics ds;
  SceneOptions so;
  so.baseDir = "/s";  // the scene's folder on the in-memory disk
  ASSERT_TRUE(buildScene(loaded.document, so, scene, ds));
  WorldOptions wo;
  wo.assets = &cache;
  EXPECT_FALSE(World::create(scene, ds, wo));
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].severity, Severity::Error);
  EXPECT_EQ(ds[0].code, "RS7007");
  // Bare (no document), in the words a document gives it (reportAt).
  EXPECT_EQ(ds[0].message, "body '/World/Rock': cannot read mesh '/s/rock.obj': No such file or directory");
  EXPECT_EQ(ds[0].line, 0u);
}

TEST(SimAssets, ABodyFallingOffTheEdgeLeavesTheWorldAndTheRestComesToRest) {
  // A static platform (top at z = 0.5) with one box on it and one beside it.
  auto r = make(object("/World/Platform", "box", 0, 0, 0, "2 2 1", 1, "static") +
                object("/World/On", "box", 0, 0, 0.7, "0.4 0.4 0.4", 1, "dynamic") +
                object("/World/Off", "box", 3, 0, 0.7, "0.4 0.4 0.4", 1, "dynamic"));
  std::uint64_t leftAt = 0;
  for (int i = 0; i < 4000 && !r->world->atRest(); ++i) {
    r->world->step();
    if (!leftAt && !r->world->departures().empty()) leftAt = r->world->steps();
  }
  ASSERT_EQ(r->world->departures().size(), 1u);
  const Departure& d = r->world->departures()[0];
  EXPECT_EQ(d.path, "/World/Off");
  EXPECT_EQ(d.step, leftAt);
  // Lowest static geometry z = -0.5; it leaves 10 m under that.  Free fall
  // from 0.7 to -10.5: t = sqrt(2 * 11.2 / 9.81) = 1.511 s.
  EXPECT_NEAR(d.time, std::sqrt(2 * 11.2 / 9.81), 0.01);
  EXPECT_LT(d.position.z(), -10.5);
  EXPECT_GT(d.position.z(), -10.6);
  EXPECT_TRUE(r->world->atRest());  // the box on the platform sleeps; the departed one does not count
  BodyState off = state(*r->world, "/World/Off");
  EXPECT_TRUE(off.departed);
  EXPECT_EQ(off.position.z(), d.position.z());  // frozen at its last pose
  r->world->step();
  EXPECT_EQ(state(*r->world, "/World/Off").position.z(), d.position.z());
  Diagnostic w = departureWarning(r->doc, d);
  EXPECT_EQ(w.severity, Severity::Warning);
  EXPECT_EQ(w.code, "RS7012");
  EXPECT_EQ(w.line, 4u);
  EXPECT_EQ(w.message.rfind("dynamic body '/World/Off' left the world at step " + std::to_string(d.step), 0), 0u)
      << w.message;
}

TEST(SimAssets, ABodyLeavingTheBroadphaseBoundsLeavesTheWorld) {
  auto r = make("solver 80 1e-07 0.2 accurate broadphaseUseWorldBounds=true broadphaseWorldMin=-5,-5,-5 "
                "broadphaseWorldMax=5,5,5\n" +
                kGround + object("/World/B", "sphere", 0, 0, 0.5, "1 1 1", 1, "dynamic"));
  ASSERT_TRUE(r->world->setLinearVelocity("/World/B", Eigen::Vector3d(0, 20, 0)));
  steps(*r->world, 1);
  ASSERT_EQ(r->world->departures().size(), 1u);
  EXPECT_EQ(r->world->departures()[0].reason, "left the broadphase bounds");
  EXPECT_GT(r->world->departures()[0].position.y(), 5);
  EXPECT_LT(r->world->departures()[0].position.y(), 5.1);
}

// Hostile input round two, trial: a body that starts where it would leave
// the world at its first step is refused before it (RS7015), not reported
// as having fallen (RS7012).  Under a ground it is the scene model's rule
// (checkScene); under other static geometry and outside the broadphase
// bounds the world's.
TEST(SimAssets, ABodyStartingOutsideTheWorldIsRefusedAtItsPosition) {
  auto refused = [](const std::string& text) {
    ::Run r;
    LoadResult loaded = parse("raisim_engine_scene 1\n" + text);
    EXPECT_TRUE(loaded.ok());
    r.doc = std::move(loaded.document);
    EXPECT_TRUE(buildScene(r.doc, {}, r.scene, r.diags));
    EXPECT_TRUE(checkPhysics(r.doc, r.scene, r.diags)) << (r.diags.empty() ? "" : r.diags[0].message);
    WorldOptions wo;
    wo.document = &r.doc;
    EXPECT_FALSE(World::create(r.scene, r.diags, wo));
    return r.diags;
  };
  // A static box (bottom at z = -0.5) and a box 20 m down.
  Diagnostics ds = refused(object("/World/Floor", "box", 0, 0, 0, "1 1 1", 1, "static") +
                           object("/World/Deep", "box", 0, 0, -20, "0.4 0.4 0.4", 1, "dynamic"));
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS7015");
  EXPECT_EQ(ds[0].severity, Severity::Error);
  EXPECT_EQ(ds[0].line, 3u);
  EXPECT_GT(ds[0].column, 0u);
  EXPECT_EQ(ds[0].message,
            "dynamic body '/World/Deep' starts at z = -20, below the world's lower bound z = -10.5 (10 m under the "
            "lowest static geometry): rscene-sim would take it out of the world at its first step");
  ds = refused("solver 80 1e-07 0.2 accurate broadphaseUseWorldBounds=true broadphaseWorldMin=-5,-5,-5 "
               "broadphaseWorldMax=5,5,5\n" + kGround + object("/World/Far", "sphere", 0, 8, 0.5, "1 1 1", 1, "dynamic"));
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS7015");
  EXPECT_EQ(ds[0].message,
            "dynamic body '/World/Far' starts at (0, 8, 0.5), outside the solver's broadphase bounds: rscene-sim would "
            "take it out of the world at its first step");
  // Under a ground: the scene model's, the same code.
  ::Run r;
  r.doc = parse("raisim_engine_scene 1\n" + kGround + object("/World/Deep", "box", 0, 0, -100, "0.4 0.4 0.4", 1, "dynamic"))
              .document;
  EXPECT_TRUE(buildScene(r.doc, {}, r.scene, r.diags));
  EXPECT_FALSE(checkPhysics(r.doc, r.scene, r.diags));
  ASSERT_EQ(r.diags.size(), 1u);
  EXPECT_EQ(r.diags[0].code, "RS7015");
}

// Bullet keeps a body touching a kinematic one awake (the kinematic body
// never sleeps and wakes what it touches every step): such a body, and one
// resting on it, rest once they have been still for sleepingQuietSteps
// steps on a kinematic body that does not move (--until-rest stops).
TEST(SimRest, BodiesRestingOnAStillKinematicBodyAreAtRest) {
  const std::string table = object("/World/Table", "box", 0, 0, 0.25, "2 2 0.5", 1, "kinematic");
  auto r = make(table + object("/World/Crate", "box", 0, 0, 0.75, "0.5 0.5 0.5", 2, "dynamic") +
                object("/World/Top", "box", 0, 0, 1.25, "0.5 0.5 0.5", 2, "dynamic"));
  int n = 0;
  for (; n < 4000 && !r->world->atRest(); ++n) r->world->step();
  EXPECT_TRUE(r->world->atRest()) << "after " << n << " steps";
  EXPECT_LT(n, 1000);
  EXPECT_NEAR(state(*r->world, "/World/Crate").position.z(), 0.75, 0.005);
  EXPECT_NEAR(state(*r->world, "/World/Top").position.z(), 1.25, 0.005);
  // A body still falling onto it is not at rest.
  auto falling = make(table + object("/World/Crate", "box", 0, 0, 3, "0.5 0.5 0.5", 2, "dynamic"));
  falling->world->step();
  EXPECT_FALSE(falling->world->atRest());
  // With sleeping off no body rests, on a kinematic body either.
  auto awake = make("solver 80 1e-07 0.2 accurate sleepingEnabled=false\n" + table +
                    object("/World/Crate", "box", 0, 0, 0.75, "0.5 0.5 0.5", 2, "dynamic"));
  for (int i = 0; i < 1000; ++i) awake->world->step();
  EXPECT_FALSE(awake->world->atRest());
}

TEST(SimAssets, BodiesRestingOnTheGroundNeverLeave) {
  auto r = make(kGround + object("/World/B", "box", 0, 0, 0.2, "0.4 0.4 0.4", 1, "dynamic"));
  steps(*r->world, 3);
  EXPECT_TRUE(r->world->departures().empty());
}

// World::deepContacts(): what keeps atRest() false while the solver pushes
// a body out, and what rscene-sim's end-of-run warning (RS7002) names.
TEST(SimRest, ABodyDeepInTheGroundIsNamedUntilItIsPushedOut) {
  // A 1 m cube 30 cm into the ground (line 3), one resting on it (line 4).
  auto r = make(kGround + object("/World/Cube", "box", 0, 0, 0.2, "1 1 1", 10, "dynamic") +
                object("/World/Resting", "box", 4, 0, 0.25, "0.5 0.5 0.5", 2, "dynamic"));
  EXPECT_TRUE(r->world->deepContacts().empty());  // before the first step
  r->world->step();
  std::vector<DeepContact> deep = r->world->deepContacts();
  ASSERT_EQ(deep.size(), 1u);
  EXPECT_EQ(deep[0].recordIndex, 2);  // records[0] is the header
  EXPECT_EQ(deep[0].otherRecordIndex, 1);
  EXPECT_NEAR(deep[0].depth, 0.3, 0.01);
  EXPECT_FALSE(r->world->atRest());
  for (bool untilRest : {true, false}) {
    Diagnostic w = notAtRestWarning(r->doc, deep, r->world->time(), untilRest);
    EXPECT_EQ(w.code, "RS7002");
    EXPECT_EQ(w.severity, Severity::Warning);
    EXPECT_EQ(w.line, 3u);
    EXPECT_NE(w.message.find("dynamic body '/World/Cube' 0.3 m inside '/World/Ground'"), std::string::npos) << w.message;
    EXPECT_EQ(w.message.find("--until-rest") != std::string::npos, untilRest) << w.message;
  }
  for (int i = 0; i < 8000 && !r->world->atRest(); ++i) r->world->step();
  EXPECT_TRUE(r->world->atRest());
  EXPECT_TRUE(r->world->deepContacts().empty());
  EXPECT_NEAR(state(*r->world, "/World/Cube").position.z(), 0.5, 0.005);
}

TEST(SimRest, RestingContactsAreNeverDeep) {
  // A stack of three boxes on the ground, each resting on the one below.
  auto r = make(kGround + object("/World/A", "box", 0, 0, 0.25, "0.5 0.5 0.5", 20, "dynamic") +
                object("/World/B", "box", 0, 0, 0.75, "0.5 0.5 0.5", 20, "dynamic") +
                object("/World/C", "box", 0, 0, 1.25, "0.5 0.5 0.5", 20, "dynamic"));
  for (int i = 0; i < 400; ++i) {
    r->world->step();
    ASSERT_TRUE(r->world->deepContacts().empty()) << "step " << r->world->steps();
  }
}

TEST(SimRest, APairTheSceneModelJudgesIsNotWarnedTwice) {
  // Box in box: the scene model's RS7013 (scene/start_pose.hpp), not the
  // first step's; a cylinder in a box: the first step's alone.
  auto boxes = make(kGround + object("/World/A", "box", 0, 0, 0.5, "1 1 1", 1, "dynamic") +
                    object("/World/B", "box", 0.5, 0, 0.5, "1 1 1", 1, "dynamic"));
  boxes->world->step();
  EXPECT_TRUE(boxes->world->startOverlaps().empty());
  auto cylinder = make(kGround + object("/World/A", "box", 0, 0, 0.5, "1 1 1", 1, "dynamic") +
                       object("/World/B", "cylinder", 0.5, 0, 0.5, "1 1 1", 1, "dynamic"));
  cylinder->world->step();
  ASSERT_EQ(cylinder->world->startOverlaps().size(), 1u);
  EXPECT_GT(cylinder->world->startOverlaps()[0].depth, 0.3);
}
