// rscene-lidar-bench SCENE [X Y Z] - one 64 x 1024 LiDAR scan of a scene's
// collision geometry (bench/lidar/run.sh; issue 12 "Speed": the warehouse
// under 20 ms), by lib/sim's exact ray casts (1 and 2 threads) and, as the
// baseline in the same run, by Bullet's btCollisionWorld::rayTest per ray
// on the same world.  Prints the best of BENCH_LIDAR_REPEAT scans (default
// 10; the Bullet baseline: 3) and how far the two disagree.
//
// The scan: 64 channels over 45 degrees (-22.5..22.5), 1024 samples, 0.1 to
// 100 m, from (X, Y, Z) (default 10 -1 1.2, an aisle of the warehouse).
#include <btBulletDynamicsCommon.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "asset/cache.hpp"
#include "core/loader.hpp"
#include "scene/scene.hpp"
#include "sim/lidar.hpp"
#include "sim/world.hpp"

using namespace rscene;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  if (argc != 2 && argc != 5) {
    std::fprintf(stderr, "usage: rscene-lidar-bench SCENE [X Y Z]\n");
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) {
    std::fprintf(stderr, "rscene-lidar-bench: cannot read %s\n", argv[1]);
    return 2;
  }
  LoadResult loaded = parse(text.str());
  Document& doc = loaded.document;
  Scene scene;
  Diagnostics ds;
  SceneOptions so;
  std::string path = argv[1];
  so.sceneDir = path.find('/') == std::string::npos ? "." : path.substr(0, path.rfind('/'));
  asset::AssetCache assets;
  if (!loaded.ok() || !buildScene(doc, so, scene, ds)) {
    std::fprintf(stderr, "rscene-lidar-bench: %s does not load\n", argv[1]);
    return 2;
  }
  sim::skipBodiesWithMissingMeshes(doc, scene, assets, ds);  // the corpus has no mesh files
  sim::WorldOptions wo;
  wo.assets = &assets;
  std::unique_ptr<sim::World> world = sim::World::create(scene, ds, wo);
  if (!world) {
    std::fprintf(stderr, "rscene-lidar-bench: the world does not build\n");
    return 2;
  }
  SensorParams p;
  p.lidarChannels = 64, p.lidarSamples = 1024;
  p.lidarMinPitch = -22.5, p.lidarMaxPitch = 22.5;
  p.lidarMinRange = 0.1, p.lidarMaxRange = 100;
  Pose at{{10, -1, 1.2}, Eigen::Quaterniond::Identity()};
  if (argc == 5) at.position = {std::atof(argv[2]), std::atof(argv[3]), std::atof(argv[4])};
  const char* r = std::getenv("BENCH_LIDAR_REPEAT");
  int repeat = r ? std::max(1, std::atoi(r)) : 10;

  auto t0 = Clock::now();
  sim::RayGeometry geometry(*world);
  double buildMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  std::vector<Eigen::Vector3d> dirs = sim::lidarDirections(p);
  auto best = [&](int threads, std::vector<Eigen::Vector3f>& points) {
    double ms = 1e30;
    for (int i = 0; i < repeat; ++i) {
      sim::LidarScanOptions o;
      o.threads = threads;
      auto a = Clock::now();
      points = sim::scanLidar(geometry, at, p, dirs, o);
      ms = std::min(ms, std::chrono::duration<double, std::milli>(Clock::now() - a).count());
    }
    return ms;
  };
  std::vector<Eigen::Vector3f> one, two;
  double ms1 = best(1, one), ms2 = best(2, two);

  // Baseline: Bullet's closest-hit ray test per ray, same rays.
  const btCollisionWorld& cw = world->collisionWorld();
  std::vector<double> bullet(dirs.size());
  double msBullet = 1e30;
  for (int i = 0; i < std::min(repeat, 3); ++i) {
    auto a = Clock::now();
    btVector3 from(at.position.x(), at.position.y(), at.position.z());
    for (std::size_t k = 0; k < dirs.size(); ++k) {
      Eigen::Vector3d d = at.orientation * dirs[k];
      btVector3 to = from + btVector3(d.x(), d.y(), d.z()) * p.lidarMaxRange;
      btCollisionWorld::ClosestRayResultCallback cb(from, to);
      cw.rayTest(from, to, cb);
      bullet[k] = cb.hasHit() ? cb.m_closestHitFraction * p.lidarMaxRange : NAN;
    }
    msBullet = std::min(msBullet, std::chrono::duration<double, std::milli>(Clock::now() - a).count());
  }
  // Agreement: rays both see, within 1 mm; rays only one sees.
  std::size_t both = 0, onlyOne = 0, far = 0;
  double worst = 0;
  for (std::size_t k = 0; k < dirs.size(); ++k) {
    double ours = geometry.cast(at.position, at.orientation * dirs[k], p.lidarMaxRange);
    bool a = ours >= p.lidarMinRange && ours <= p.lidarMaxRange, b = bullet[k] >= p.lidarMinRange;
    if (a && b) {
      ++both;
      double e = std::abs(ours - bullet[k]);
      worst = std::max(worst, e);
      far += e > 1e-3;
      if (e > 1e-3 && std::getenv("BENCH_LIDAR_VERBOSE"))
        std::printf("ray %zu dir %g %g %g: rscene %.6f bullet %.6f\n", k, dirs[k].x(), dirs[k].y(), dirs[k].z(), ours,
                    bullet[k]);
    } else if (a != b) {
      ++onlyOne;
    }
  }
  std::printf("lidar scan 64x1024 of %s: %zu solids, %zu triangles (read in %.1f ms)\n", argv[1], geometry.solidCount(),
              geometry.triangleCount(), buildMs);
  std::printf("  %-28s %9.2f ms  %zu points\n", "rscene exact, 1 thread", ms1, one.size());
  std::printf("  %-28s %9.2f ms  %zu points  %s (target < 20 ms)\n", "rscene exact, 2 threads", ms2, two.size(),
              ms2 < 20 ? "PASS" : "MISS");
  std::printf("  %-28s %9.2f ms  (%.1fx slower than 2 threads)\n", "Bullet rayTest per ray", msBullet, msBullet / ms2);
  std::printf("  agreement with Bullet: %zu rays both hit (worst %.2g m, %zu beyond 1 mm), %zu only one hit\n", both,
              worst, far, onlyOne);
  return 0;
}
