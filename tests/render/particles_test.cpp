// Deformables and granular records in rscene-render (lib/render/
// deformed_surface): a cloth drawn from its OBJ surface in file order with
// area-weighted normals, and, along a trajectory, each frame's points
// replacing the cloth's vertices and the grains' centres; what is drawn is
// where the frame puts it, not at rest.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/loader.hpp"
#include "gl_test_context.hpp"
#include "render/deformed_surface.hpp"
#include "render/render_scene.hpp"
#include "render/renderer.hpp"
#include "render/view.hpp"
#include "robot/trajectory_read.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

TEST(DeformedSurface, NormalsAreAreaWeightedPerVertex) {
  // Two triangles sharing the edge 0-1: one in the z=0 plane (area 2),
  // one in the x=0 plane (area 0.5); the shared vertices lean 4:1 to +z.
  DeformedSurface s;
  s.positions = {{0, 0, 0}, {0, 2, 0}, {2, 0, 0}, {0, 0, 0.5f}};
  s.triangles = {{0, 2, 1}, {0, 1, 3}};
  MeshData m = surfaceMesh(s);
  ASSERT_EQ(m.vertexCount(), 4u);
  ASSERT_EQ(m.indices, (std::vector<std::uint32_t>{0, 2, 1, 0, 1, 3}));
  auto normal = [&](std::size_t i) { return Eigen::Vector3f(m.vertices[i * 8 + 3], m.vertices[i * 8 + 4], m.vertices[i * 8 + 5]); };
  // Triangle 0,2,1: (p2-p0)x(p1-p0) = (2,0,0)x(0,2,0) = (0,0,4);
  // triangle 0,1,3: (0,2,0)x(0,0,0.5) = (1,0,0).
  Eigen::Vector3f shared = Eigen::Vector3f(1, 0, 4).normalized();
  EXPECT_TRUE(normal(0).isApprox(shared, 1e-6f)) << normal(0).transpose();
  EXPECT_TRUE(normal(1).isApprox(shared, 1e-6f));
  EXPECT_TRUE(normal(2).isApprox(Eigen::Vector3f::UnitZ(), 1e-6f));
  EXPECT_TRUE(normal(3).isApprox(Eigen::Vector3f::UnitX(), 1e-6f));
  EXPECT_EQ(m.vertices[1 * 8 + 1], 2.f);  // positions as given (world)
  // A vertex of no triangle, or a collapsed one: +z, never NaN.
  s.positions.push_back({9, 9, 9});
  s.triangles.push_back({0, 0, 0});
  MeshData more = surfaceMesh(s);
  EXPECT_EQ(more.vertices[4 * 8 + 5], 1.f);
}

// A 3 x 3 grid of vertices (2 x 2 quads, 8 triangles), 1 m square in the
// file's y-z plane, centred on the origin: facing a camera that looks
// along +x.
const char* kClothObj =
    "# cloth\n"
    "v 0 -0.5 -0.5\nv 0 0 -0.5\nv 0 0.5 -0.5\n"
    "v 0 -0.5 0\nv 0 0 0\nv 0 0.5 0\n"
    "v 0 -0.5 0.5\nv 0 0 0.5\nv 0 0.5 0.5\n"
    "f 1 2 5 4\nf 2 3 6 5\nf 4 5 8 7\nf 5 6 9 8\n";

class Particles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("rscene_particles_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "cloth.obj") << kClothObj;
    std::ofstream(dir_ / "cloth.OBJ.stl") << "solid x\nendsolid x\n";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Camera at the origin looking along +x (200 x 200, 60 degrees); a red
  // cloth at x = 5; two grains of radius 0.2 whose frame is at (5, 1.5, 1).
  bool build(const std::string& mesh = "cloth.obj", const std::string& kind = "cloth", const std::string& keys = "") {
    LoadResult loaded = parse(
        "raisim_engine_scene 1\n"
        "environment 0 0 0 0.2 0.2 0.2 0 true true 10 - backgroundMode=plain_color colorMode=linear\n"
        "material red 0.8 0.1 0.1 1 0 0.6 0 0 0 0 false - - - - - - id=red\n"
        "camera /World/Cam 0 0 0 1 0 0 0 60 0.05 100 200 200 rgb true id=cam\n"
        "light /World/Sun 1 0.4 -0.4 3 type=directional\n"
        "deformable /World/Cloth " + kind + " " + mesh + " 5 0 0 1 0 0 0 1 1 1 material=red" + keys + "\n"
        "granular /World/Sand particles 5 1.5 1 1 0 0 0 1 1 1 boxMin=0,0,0 boxMax=0.4,0.8,0.4 radius=0.2 spacing=0.4\n");
    EXPECT_TRUE(loaded.ok());
    doc_ = std::move(loaded.document);
    SceneOptions so;
    so.sceneDir = dir_.string();
    diags_.clear();
    return buildRenderScene(doc_, so, scene_, render_, diags_);
  }

  Image draw(Renderer& r) {
    View v;
    v.name = "/World/Cam";
    v.camera = render_.cameras.at(0);
    v.passes = {Pass::Color};
    ViewImages out;
    Diagnostics d;
    EXPECT_TRUE(r.render(v, out, d)) << (d.empty() ? "" : d[0].message);
    return std::move(out.color);
  }

  // Where a world point lands (the camera at the origin, 60 degrees, 200 px).
  static std::pair<int, int> pixelOf(double x, double y, double z) {
    double f = 100 / std::tan(30 * 3.14159265358979 / 180);
    return {int(std::lround(100 - f * y / x)), int(std::lround(100 - f * z / x))};
  }
  static bool cloth(const Image& im, std::pair<int, int> at) {
    const std::uint8_t* p = im.pixel(at.first, at.second);
    return p[0] > 60 && p[0] > 2 * p[1] && p[0] > 2 * p[2];
  }
  static bool sand(const Image& im, std::pair<int, int> at) {
    const std::uint8_t* p = im.pixel(at.first, at.second);
    return p[0] > 60 && p[1] > p[0] / 2 && p[2] > p[0] / 4;
  }
  static bool background(const Image& im, std::pair<int, int> at) {
    const std::uint8_t* p = im.pixel(at.first, at.second);
    return p[0] + p[1] + p[2] == 0;
  }

  std::filesystem::path dir_;
  Document doc_;
  Scene scene_;
  RenderScene render_;
  Diagnostics diags_;
};

TEST_F(Particles, ClothAtRestIsItsObjSurfaceInFileOrder) {
  ASSERT_TRUE(build()) << (diags_.empty() ? "" : diags_[0].message);
  ASSERT_EQ(render_.surfaces.size(), 1u);
  ASSERT_EQ(render_.deformableSurfaces, std::vector<int>{0});
  const DeformedSurface& s = render_.surfaces[0];
  ASSERT_EQ(s.positions.size(), 9u);
  EXPECT_EQ(s.triangles.size(), 8u);
  EXPECT_EQ(s.positions[2], Eigen::Vector3f(5, 0.5f, -0.5f));  // file order, placed at the record's pose
  const Drawable& d = render_.drawables[s.drawable];
  EXPECT_EQ(d.surface, 0);
  EXPECT_TRUE(d.doubleSided);
  EXPECT_TRUE(d.bounds.contains(Eigen::Vector3d(5, 0.5, 0.5)));
  ASSERT_EQ(render_.granularBatches, std::vector<int>{int(render_.instanced.size()) - 1});
  robot::ParticleCounts counts = particleCounts(render_);
  EXPECT_EQ(counts.deformables, std::vector<std::int64_t>{9});
  EXPECT_EQ(counts.granulars, std::vector<std::int64_t>{2});
  EXPECT_EQ(trajectoryLimits(render_).maxPoints, 9u);
  // A mesh that is no OBJ cannot be a deformable's particles: refused at
  // meshPath with rscene-sim's (and validate --check-files') RS7080.
  EXPECT_FALSE(build("cloth.OBJ.stl"));
  ASSERT_FALSE(diags_.empty());
  EXPECT_EQ(diags_[0].code, "RS7080");
  EXPECT_EQ(diags_[0].line, 6u);
}

TEST_F(Particles, TrajectoryFramesMoveTheClothAndTheGrains) {
  if (!context()) return;
  ASSERT_TRUE(build()) << (diags_.empty() ? "" : diags_[0].message);
  // Frame 0: the cloth 1.5 m to the left, its centre vertex pulled 0.3 m
  // towards the camera; the grains up in the middle.  Frame 1: the cloth
  // down to the right, the grains to the left.
  auto clothLine = [](double t, double dy, double dz, double pull) {
    std::ostringstream s;
    s << "{\"time\":" << t << ",\"path\":\"/World/Cloth\",\"points\":[";
    for (int k = 0; k < 9; ++k) {
      double y = -0.5 + 0.5 * (k % 3), z = -0.5 + 0.5 * (k / 3);
      s << (k ? "," : "") << "[" << (k == 4 ? 5 - pull : 5) << "," << y + dy << "," << z + dz << "]";
    }
    s << "]}\n";
    return s.str();
  };
  std::string trajectory =
      clothLine(0, 1.5, 0, 0.3) + "{\"time\":0,\"path\":\"/World/Sand\",\"points\":[[5,0,1.5],[5,-0.5,1.5]]}\n" +
      clothLine(0.5, -1.5, -1, 0) + "{\"time\":0.5,\"path\":\"/World/Sand\",\"points\":[[5,1.2,-1.5],[5,1.7,-1.5]]}\n";
  std::istringstream in(trajectory);
  robot::TrajectoryReader reader(in, "t.jsonl", trajectoryLimits(render_));
  robot::TrajectoryPoser poser(scene_, render_.robotModels, particleCounts(render_));
  robot::BodyPoses poses = robot::restPoses(scene_, render_.robotModels);
  robot::ParticlePositions particles;
  Diagnostics d;
  std::unique_ptr<Renderer> renderer = Renderer::create(render_, RenderOptions{}, d);
  ASSERT_TRUE(renderer) << (d.empty() ? "" : d[0].message);

  Image rest = draw(*renderer);
  const auto clothRest = pixelOf(5, 0, 0), grainRest = pixelOf(5.2, 1.7, 1.2);
  EXPECT_TRUE(cloth(rest, clothRest));
  EXPECT_TRUE(sand(rest, grainRest));

  std::vector<Image> frames;
  robot::TrajectoryFrame frame;
  while (reader.next(frame, d)) {
    ASSERT_TRUE(poser.apply(frame, "t.jsonl", poses, d, &particles)) << d[0].message;
    poseScene(render_, {&poses.objects, &poses.compounds, &poses.robotLinks, &particles});
    renderer->updatePoses();
    // As rscene-render does per frame: the grains re-tessellated for the
    // view (fewer segments than create()'s 48: another mesh bound).
    renderer->setParticleViews({render_.cameras.at(0)});
    frames.push_back(draw(*renderer));
  }
  ASSERT_FALSE(reader.failed()) << d[0].message;
  ASSERT_EQ(frames.size(), 2u);
  if (const char* out = std::getenv("RSCENE_PARTICLES_PNG")) {  // to look at the frames: a folder
    for (std::size_t i = 0; i < frames.size(); ++i) {
      std::string png = encodePng(frames[i]);
      ASSERT_FALSE(png.empty());
      std::ofstream(std::string(out) + "/frame" + std::to_string(i) + ".png", std::ios::binary) << png;
    }
  }
  // Frame 0: the cloth where the frame puts it (its pulled centre too),
  // nothing at rest; the grains up in the middle.
  EXPECT_TRUE(cloth(frames[0], pixelOf(4.7, 1.5, 0)));
  EXPECT_TRUE(cloth(frames[0], pixelOf(5, 1.2, 0.3)));
  EXPECT_TRUE(background(frames[0], pixelOf(5, -0.3, 0)));
  EXPECT_TRUE(sand(frames[0], pixelOf(5, 0, 1.5)));
  EXPECT_TRUE(sand(frames[0], pixelOf(5, -0.5, 1.5)));
  EXPECT_TRUE(background(frames[0], grainRest));
  // Frame 1: everything moved again.
  EXPECT_TRUE(cloth(frames[1], pixelOf(5, -1.5, -1)));
  EXPECT_TRUE(background(frames[1], pixelOf(4.7, 1.5, 0)));
  EXPECT_TRUE(sand(frames[1], pixelOf(5, 1.2, -1.5)));
  EXPECT_TRUE(sand(frames[1], pixelOf(5, 1.7, -1.5)));
  EXPECT_TRUE(background(frames[1], pixelOf(5, 0, 1.5)));
  // The pulled centre vertex of frame 0 shades the cloth unevenly (its
  // normals tilt); frame 1's flat cloth is even.
  auto spread = [&](const Image& im, double dy, double dz) {
    int lo = 255, hi = 0;
    for (double y : {-0.3, -0.1, 0.1, 0.3})
      for (double z : {-0.3, -0.1, 0.1, 0.3}) {
        auto [px, py] = pixelOf(5, y + dy, z + dz);
        lo = std::min<int>(lo, im.pixel(px, py)[0]);
        hi = std::max<int>(hi, im.pixel(px, py)[0]);
      }
    return hi - lo;
  };
  EXPECT_GT(spread(frames[0], 1.5, 0), 3 * std::max(spread(frames[1], -1.5, -1), 1));
}

TEST_F(Particles, AFemVolumesFillParticlesAreNotDrawn) {
  // An open sheet is no volume to fill (sim and validate refuse it, RS7081);
  // as a surface-mode fem its particles are the sheet's, strutted.
  EXPECT_FALSE(build("cloth.obj", "fem"));
  ASSERT_FALSE(diags_.empty());
  EXPECT_EQ(diags_[0].code, "RS7081");
  ASSERT_TRUE(build("cloth.obj", "fem", " particleMode=surface"));
  ASSERT_EQ(render_.surfaces.size(), 1u);
  EXPECT_TRUE(render_.surfaces[0].mayFill);
  EXPECT_FALSE(render_.drawables[render_.surfaces[0].drawable].doubleSided);  // a closed volume
  // How many fill particles the solver makes is its own: lines of any length up to the defaults.
  EXPECT_EQ(trajectoryLimits(render_).maxPoints, robot::TrajectoryLimits{}.maxPoints);
  robot::ParticlePositions particles;
  particles.deformables.resize(1);
  particles.deformables[0].given = true;
  particles.deformables[0].version = 1;
  for (int k = 0; k < 12; ++k) particles.deformables[0].points.emplace_back(k, 0, 1);
  std::uint64_t before = render_.surfaces[0].version;
  poseScene(render_, {nullptr, nullptr, nullptr, &particles});
  const DeformedSurface& s = render_.surfaces[0];
  EXPECT_EQ(s.version, before + 1);
  ASSERT_EQ(s.positions.size(), 9u);  // the surface's 9 vertices, the 3 fill particles left out
  EXPECT_EQ(s.positions[8], Eigen::Vector3f(8, 0, 1));
  EXPECT_TRUE(render_.drawables[s.drawable].bounds.contains(Eigen::Vector3d(8, 0, 1)));
  EXPECT_FALSE(render_.drawables[s.drawable].bounds.contains(Eigen::Vector3d(11, 0, 1)));
}

TEST_F(Particles, AFrameWithTheWrongCountIsRefusedAtItsLine) {
  ASSERT_TRUE(build());
  std::istringstream in("{\"time\":0,\"path\":\"/World/Sand\",\"points\":[[5,0,1.5]]}\n");
  robot::TrajectoryReader reader(in, "t.jsonl", trajectoryLimits(render_));
  robot::TrajectoryPoser poser(scene_, render_.robotModels, particleCounts(render_));
  robot::BodyPoses poses = robot::restPoses(scene_, render_.robotModels);
  robot::ParticlePositions particles;
  robot::TrajectoryFrame frame;
  Diagnostics d;
  ASSERT_TRUE(reader.next(frame, d));
  EXPECT_FALSE(poser.apply(frame, "t.jsonl", poses, d, &particles));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].code, "RS9047");
  EXPECT_EQ(d[0].message, "'/World/Sand' has 2 particles, the line gives 1 points");
  // Counts poseScene is handed anyway do not move what is drawn.
  particles.granulars.resize(1);
  particles.granulars[0] = {true, 1, {Eigen::Vector3d(0, 0, 0)}};
  Eigen::Affine3d before = render_.instanced[std::size_t(render_.granularBatches[0])].worlds[0];
  poseScene(render_, {nullptr, nullptr, nullptr, &particles});
  EXPECT_TRUE(render_.instanced[std::size_t(render_.granularBatches[0])].worlds[0].isApprox(before));
}

}  // namespace
