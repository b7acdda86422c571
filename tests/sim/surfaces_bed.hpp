// The grain beds of surfaces_bed_test.cpp, shared with its benchmark
// (bench/sim/surfaces.cpp): 20,000 grains of radius 1 cm resting in
// contact with one surface (the ground plane, a static box, a convex hull,
// a static mesh of 8,192 triangles), queried as a granular substep does.
// The test asserts what the queries find, the benchmark times them.
#pragma once
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "core/loader.hpp"
#include "scene/scene.hpp"
#include "sim/bullet_surfaces.hpp"
#include "sim/world.hpp"

namespace rscene::sim::test {

// Writes dir/grid64.obj, 64 x 64 squares over 6 x 4 m at z = 0 (8,192
// triangles), and returns its path.
inline std::string writeGridMesh(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::filesystem::path obj = dir / "grid64.obj";
  std::ofstream f(obj);
  const int n = 64;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) f << "v " << -3 + 6.0 * x / n << ' ' << -2 + 4.0 * y / n << " 0\n";
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      int a = 1 + y * (n + 1) + x, b = a + 1, c = a + n + 2, d = a + n + 1;
      f << "f " << a << ' ' << b << ' ' << c << "\nf " << a << ' ' << c << ' ' << d << "\n";
    }
  return obj.string();
}

struct SurfaceCase {
  std::string what;
  std::string body;  // the object record under the grains
};

// The four surfaces; `crateObj` is tests/data/render_assets/crate.obj, the
// unit cube, and `gridObj` writeGridMesh's file.
inline std::vector<SurfaceCase> surfaceCases(const std::string& crateObj, const std::string& gridObj) {
  return {
      {"the ground plane", "object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 0.5 1 0 default engine_default "
                           "false true false - static true 1 18446744073709551615\n"},
      {"a static box", "object /World/Slab box 0 0 -0.5 1 0 0 0 6 4 1 0.5 1 0 default engine_default false true "
                       "false - static true 1 18446744073709551615\n"},
      // A kinematic mesh object is a convex hull (its face planes over a
      // face, GJK/EPA near an edge): the unit cube scaled to 4 m, top at z = 0.
      {"a convex hull", "object /World/Hull mesh 0 0 -2 1 0 0 0 4 4 4 0.5 1 1 default engine_default false true "
                        "false " + crateObj + " kinematic true 1 18446744073709551615\n"},
      {"a static mesh of 8,192 triangles", "object /World/Mesh mesh 0 0 0 1 0 0 0 1 1 1 0.5 1 0 default "
                                           "engine_default false true false " + gridObj +
                                               " static true 1 18446744073709551615\n"},
  };
}

// A world of one surface and a grain record, its particle surfaces
// prepared over the bed, and the bed's 200 x 100 grain centres 9 mm up
// (each grain overlaps the surface by 1 mm).
struct Bed {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<World> world;
  BulletSurfaces* surfaces = nullptr;
  std::vector<Eigen::Vector3d> grains;
  std::string error;  // set when the bed could not be built
};

inline Bed makeBed(const std::string& body) {
  Bed bed;
  LoadResult loaded = parse("raisim_engine_scene 1\ngravity 0 0 0\n" + body +
                            "granular /World/Grain particles 0 0 0 1 0 0 0 1 1 1 positions=0,0,90 radii=0.01\n");
  bed.scene = std::make_unique<Scene>();
  Diagnostics diags;
  if (!loaded.ok() || !buildScene(loaded.document, {}, *bed.scene, diags)) {
    bed.error = "the scene does not build";
    return bed;
  }
  bed.world = World::create(*bed.scene, diags);
  if (!bed.world) {
    bed.error = "World::create failed";
    return bed;
  }
  bed.surfaces = bed.world->particleSurfaces();
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 200; ++x) bed.grains.emplace_back(-2 + 0.02 * x + 0.001, -1 + 0.02 * y + 0.001, 0.009);
  bed.surfaces->prepare(Eigen::AlignedBox3d(Eigen::Vector3d(-2.1, -1.1, -0.1), Eigen::Vector3d(2.1, 1.1, 0.1)), 1,
                        ~std::uint64_t{0}, "");
  return bed;
}

// One substep's queries: every grain's contacts, appended to `out`.
inline void queryAll(Bed& bed, std::vector<SurfaceContact>& out) {
  for (const Eigen::Vector3d& g : bed.grains) bed.surfaces->contacts(g, 0.01, 0.001, out);
}

}  // namespace rscene::sim::test
