// lib/sim and lib/asset: meshes through the shared cache (read once, from
// an in-memory disk).
#include <gtest/gtest.h>

#include <cmath>

#include "asset/cache.hpp"
#include "core/loader.hpp"
#include "core/scene.hpp"
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

// Loads `body`; with `assets`, meshes come from it.
std::unique_ptr<Run> make(const std::string& body, asset::AssetCache* assets = nullptr) {
  auto r = std::make_unique<Run>();
  LoadResult loaded = parse("raisim_engine_scene 1\n" + body);
  EXPECT_TRUE(loaded.ok());
  r->doc = std::move(loaded.document);
  SceneOptions so;
  so.baseDir = "/s";  // the scene's folder on the in-memory disk
  if (assets) so.exists = [assets](const std::string& p) { return assets->fileSystem().exists(p); };
  EXPECT_TRUE(buildScene(r->doc, so, r->scene, r->diags));
  // checkPhysics asks the real disk whether mesh files exist: a scene on
  // the in-memory disk skips it.
  if (!assets) {
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
  EXPECT_EQ(ds[0].message, "/World/Rock: cannot read mesh '/s/rock.obj': No such file or directory");
}
