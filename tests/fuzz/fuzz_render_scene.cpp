// Feeds arbitrary bytes to rscene-render's scene preparation without a GL
// context: load, then render::buildRenderScene (buildScene, checkScene,
// prepareScene).  Asset paths resolve against an empty disk.
//
// Invariants, besides not crashing: every finding has a registered code;
// when the build succeeds, what the renderer will index is in range
// (material of each drawable, terrain and batch; one color and bound per
// terrain sample and instance) and every transform and bound it will
// upload is finite.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/check.hpp"
#include "core/loader.hpp"
#include "render/render_scene.hpp"

namespace {

[[noreturn]] void fail(const char* invariant, const std::string& detail) {
  std::fprintf(stderr, "fuzz_render_scene: invariant broken: %s\n%s\n", invariant, detail.c_str());
  std::abort();
}

void checkMaterial(int material, const rscene::render::RenderScene& out, const char* what) {
  if (material < 0 || static_cast<std::size_t>(material) >= out.materials.size())
    fail("material indices are in range", std::string(what) + " uses material " + std::to_string(material) + " of " +
                                              std::to_string(out.materials.size()));
}

void checkBox(const Eigen::AlignedBox3d& box, const char* what) {
  if (!box.isEmpty() && !(box.min().allFinite() && box.max().allFinite()))
    fail("bounds are finite", what);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rscene::LoadResult loaded = rscene::parse(std::string(reinterpret_cast<const char*>(data), size));
  if (!loaded.ok()) return 0;
  rscene::SceneOptions options;
  options.sceneDir = "/scene";
  options.exists = [](const std::string&) { return false; };
  rscene::render::RenderScene out;
  rscene::Diagnostics ds;
  bool ok = rscene::render::buildRenderScene(loaded.document, options, out, ds);
  for (const rscene::Diagnostic& d : ds)
    if (!rscene::checkInfo(d.code)) fail("render codes are registered", d.code + ": " + d.message);
  if (!ok) return 0;
  if (out.materials.empty()) fail("materials[0] is engine_default", "no materials");
  for (const rscene::render::Drawable& d : out.drawables) {
    checkMaterial(d.material, out, "a drawable");
    if (!d.world.matrix().allFinite()) fail("drawable transforms are finite", "line " + std::to_string(d.line));
    checkBox(d.bounds, "a drawable");
  }
  for (const rscene::render::TerrainMesh& t : out.terrains) {
    checkMaterial(t.material, out, "a terrain");
    auto samples = static_cast<std::size_t>(t.xSamples) * static_cast<std::size_t>(t.ySamples);
    if (t.positions.size() != samples || t.colors.size() != samples)
      fail("one position and color per terrain sample",
           std::to_string(t.positions.size()) + " positions, " + std::to_string(t.colors.size()) + " colors, " +
               std::to_string(samples) + " samples");
    checkBox(t.bounds, "a terrain");
  }
  for (const rscene::render::Instanced& b : out.instanced) {
    checkMaterial(b.material, out, "an instanced batch");
    if (b.instanceBounds.size() != b.worlds.size())
      fail("one bound per instance", std::to_string(b.instanceBounds.size()) + " vs " + std::to_string(b.worlds.size()));
    if (!b.colors.empty() && b.colors.size() != b.worlds.size())
      fail("instance colors are per instance or none",
           std::to_string(b.colors.size()) + " vs " + std::to_string(b.worlds.size()));
    for (const Eigen::Affine3d& w : b.worlds)
      if (!w.matrix().allFinite()) fail("instance transforms are finite", "line " + std::to_string(b.line));
  }
  for (const rscene::render::PointBatch& p : out.pointClouds) checkBox(p.bounds, "a point cloud");
  checkBox(out.bounds, "the scene");
  return 0;
}
