// What a contacts() query costs: a bed of 20,000 grains (radius 1 cm, in
// contact) on the ground plane, on a static box, on a convex hull and on
// a static mesh of 8,192 triangles, each queried in turn as a granular
// substep does.
// Prints ns per query (figures are measured, not asserted: the machine's
// load moves them); asserts that every grain found its one contact.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/loader.hpp"
#include "scene/scene.hpp"
#include "sim/bullet_surfaces.hpp"
#include "sim/world.hpp"

using namespace rscene;
using namespace rscene::sim;
using Eigen::Vector3d;
namespace fs = std::filesystem;

namespace {

const std::string kGrain = "granular /World/Grain particles 0 0 0 1 0 0 0 1 1 1 positions=0,0,90 radii=0.01\n";

std::string meshFile() {
  fs::path dir = fs::path(testing::TempDir()) / "surfaces_cost";
  fs::create_directories(dir);
  fs::path obj = dir / "grid64.obj";
  std::ofstream f(obj);
  const int n = 64;  // 64 x 64 squares over 6 x 4 m: 8,192 triangles
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) f << "v " << -3 + 6.0 * x / n << ' ' << -2 + 4.0 * y / n << " 0\n";
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      int a = 1 + y * (n + 1) + x, b = a + 1, c = a + n + 2, d = a + n + 1;
      f << "f " << a << ' ' << b << ' ' << c << "\nf " << a << ' ' << c << ' ' << d << "\n";
    }
  return obj.string();
}

void measure(const char* what, const std::string& body) {
  LoadResult loaded = parse("raisim_engine_scene 1\ngravity 0 0 0\n" + body + kGrain);
  ASSERT_TRUE(loaded.ok());
  Scene scene;
  Diagnostics diags;
  ASSERT_TRUE(buildScene(loaded.document, {}, scene, diags));
  std::unique_ptr<World> world = World::create(scene, diags);
  ASSERT_TRUE(world);
  BulletSurfaces& s = *world->particleSurfaces();
  std::vector<Vector3d> grains;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 200; ++x) grains.emplace_back(-2 + 0.02 * x + 0.001, -1 + 0.02 * y + 0.001, 0.009);
  s.prepare(Eigen::AlignedBox3d(Vector3d(-2.1, -1.1, -0.1), Vector3d(2.1, 1.1, 0.1)), 1, ~std::uint64_t{0}, "");
  std::vector<SurfaceContact> out;
  out.reserve(grains.size());
  // The best of ten passes: the other processes on the machine only add.
  const int repeat = 10;
  std::size_t found = 0;
  double best = 1e300;
  for (int k = 0; k < repeat; ++k) {
    out.clear();
    auto start = std::chrono::steady_clock::now();
    for (const Vector3d& g : grains) s.contacts(g, 0.01, 0.001, out);
    best = std::min(best, std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count());
    found = out.size();
  }
  EXPECT_EQ(found, grains.size()) << what;
  std::printf("contacts() on %-36s %7.1f ns per query (20,000 grains, best of %d passes)\n", what,
              best / static_cast<double>(grains.size()), repeat);
}

}  // namespace

TEST(SurfacesCost, GroundBoxAndMeshBeds) {
  measure("the ground plane", "object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 0.5 1 0 default engine_default "
                              "false true false - static true 1 18446744073709551615\n");
  measure("a static box", "object /World/Slab box 0 0 -0.5 1 0 0 0 6 4 1 0.5 1 0 default engine_default false true "
                          "false - static true 1 18446744073709551615\n");
  // A kinematic mesh object is a convex hull (its face planes over a
  // face, GJK/EPA near an edge): the unit cube scaled to 4 m, top at z = 0.
  measure("a convex hull", "object /World/Hull mesh 0 0 -2 1 0 0 0 4 4 4 0.5 1 1 default engine_default false "
                                 "true false " + std::string(RSCENE_TEST_DATA) + "/render_assets/crate.obj"
                                 " kinematic true 1 18446744073709551615\n");
  measure("a static mesh of 8,192 triangles", "object /World/Mesh mesh 0 0 0 1 0 0 0 1 1 1 0.5 1 0 default "
                                              "engine_default false true false " + meshFile() +
                                              " static true 1 18446744073709551615\n");
}
