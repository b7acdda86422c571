// Scene text in, a built World out: the one way the particle-system tests
// (deformable_world, granular_world, bullet_surfaces, particles_world)
// make their worlds.  Parsing and building the scene are expected to
// succeed; whether the world is made is each test's to assert.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "asset/cache.hpp"
#include "core/loader.hpp"
#include "robot/instance.hpp"
#include "scene/scene.hpp"
#include "sim/world.hpp"

namespace rscene::sim::test {

inline const std::string kGround =
    "object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 0.5 1 0 default engine_default false true false - static "
    "true 1 18446744073709551615\n";

inline std::string firstMessage(const Diagnostics& d) { return d.empty() ? "" : d[0].message; }

struct WorldRun {
  Document doc;
  Scene scene;
  Diagnostics diags;
  std::vector<robot::RobotInstance> robots;
  std::unique_ptr<World> world;
};

struct WorldRunOptions {
  asset::AssetCache* assets = nullptr;  // meshes from here (and its file system says what exists)
  std::string baseDir;                  // relative asset paths from here
  bool robots = false;                  // build the articulated systems (makeRobots)
  bool checkPhysics = false;            // run checkPhysics before building the world, expecting it to pass
};

// Fills `run` in place (the world points into its document and robots, so
// they never move).  `text` is the scene after its `raisim_engine_scene 1` line.
inline void buildWorld(WorldRun& run, const std::string& text, const WorldRunOptions& options = {}) {
  WorldRun* r = &run;
  LoadResult loaded = parse("raisim_engine_scene 1\n" + text);
  EXPECT_TRUE(loaded.ok()) << firstMessage(loaded.diagnostics);
  r->doc = std::move(loaded.document);
  SceneOptions so;
  so.baseDir = options.baseDir;
  if (asset::AssetCache* assets = options.assets)
    so.exists = [assets](const std::string& p) { return assets->fileSystem().exists(p); };
  EXPECT_TRUE(buildScene(r->doc, so, r->scene, r->diags)) << firstMessage(r->diags);
  if (options.checkPhysics) {
    EXPECT_TRUE(checkPhysics(r->doc, r->scene, r->diags)) << firstMessage(r->diags);
  }
  WorldOptions wo;
  wo.assets = options.assets;
  wo.document = &r->doc;
  if (options.robots) {
    EXPECT_TRUE(makeRobots(r->doc, r->scene, r->robots, r->diags)) << firstMessage(r->diags);
    wo.robots = &r->robots;
  }
  r->world = World::create(r->scene, r->diags, wo);
}

inline std::unique_ptr<WorldRun> buildWorld(const std::string& text, const WorldRunOptions& options = {}) {
  auto r = std::make_unique<WorldRun>();
  buildWorld(*r, text, options);
  return r;
}

}  // namespace rscene::sim::test
