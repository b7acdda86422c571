// Robots drawn on the CPU backend: models built in code of coloured
// primitives (and a mesh fixture), placed by robot::linkPoses, must show
// their colours at the pixels where their links project.
//
// The camera sits at the origin looking along +x (image left = +y, up =
// +z), 60 degrees vertical fov, 200x200: a point (5, y, z) lands at pixel
// (100 - y * k, 100 - z * k) with k = 100 / (5 tan 30) = 34.64 px per metre.
#include <gtest/gtest.h>

#include <cmath>

#include "gl_test_context.hpp"
#include "asset/cache.hpp"
#include "core/loader.hpp"
#include "render/camera.hpp"
#include "render/gl_context.hpp"
#include "render/render_scene.hpp"
#include "render/renderer.hpp"
#include "render/robot_drawables.hpp"
#include "robot/kinematics.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

constexpr double kPxPerMetre = 100 / (5 * 0.57735026918962576);

const char* kScene =
    "raisim_engine_scene 1\n"
    "environment 0 0 0 0.3 0.3 0.3 0 true true 10 - backgroundMode=plain_color colorMode=linear\n"
    "camera /World/Cam 0 0 0 1 0 0 0 60 0.05 100 200 200 rgb true id=cam\n"
    "light /World/Sun 1 0 0 3 type=directional\n";

robot::Visual boxVisual(const Eigen::Vector3d& at, double side, std::optional<Eigen::Vector4d> color) {
  robot::Visual v;
  v.origin.position = at;
  v.geometry.kind = robot::GeometryKind::Box;
  v.geometry.size = Eigen::Vector3d::Constant(side);
  v.color = color;
  return v;
}

const Eigen::Vector4d kRed(0.9, 0.05, 0.05, 1), kGreen(0.05, 0.9, 0.05, 1), kBlue(0.05, 0.05, 0.9, 1);

// base (red box at the link origin) --j1 revolute about x--> arm (green box
// 1 m up its z axis).
robot::Model twoLinkArm(bool floating) {
  robot::Model m;
  m.name = "arm";
  m.sourceFile = "/robots/arm.urdf";
  m.floatingBase = floating;
  m.links.resize(2);
  m.links[0].name = "base";
  m.links[0].visuals.push_back(boxVisual({0, 0, 0}, 0.6, kRed));
  m.links[0].childJoints = {0};
  m.links[1].name = "arm";
  m.links[1].visuals.push_back(boxVisual({0, 0, 1}, 0.4, kGreen));
  m.links[1].parentJoint = 0;
  robot::Joint j;
  j.name = "j1";
  j.type = robot::JointType::Revolute;
  j.parentLink = 0;
  j.childLink = 1;
  j.axis = Eigen::Vector3d::UnitX();
  m.joints.push_back(j);
  return m;
}

struct Shot {
  bool ok = false;
  Image image;
  Diagnostics diags;
  RenderScene scene;
};

// Renders `model` at coordinate `q` (base at `base` when fixed), `copies`
// times, each 1 m further along +y, all through one asset cache on `fs`.
Shot shoot(const robot::Model& model, const Eigen::VectorXd& q, const Pose& base = {}, RenderOptions options = {},
           const std::string& cameraSel = "cam", const FileSystem& fs = diskFileSystem(), int copies = 1) {
  Shot s;
  if (!context()) return s;
  LoadResult loaded = parse(kScene);
  EXPECT_TRUE(loaded.ok());
  EXPECT_TRUE(buildRenderScene(loaded.document, {}, s.scene, s.diags));
  robot::Coordinates c;
  EXPECT_TRUE(robot::makeCoordinates(model, {}, c).empty());
  EXPECT_EQ(q.size(), c.coordinateDim);
  options.width = options.height = 200;
  asset::AssetCache assets(fs, assetLimits(options));
  options.assets = &assets;
  RobotDrawer drawer(s.scene, assets);
  for (int k = 0; k < copies; ++k) {
    Pose b = base;
    b.position.y() += k;
    drawer.add(model, robot::linkPoses(model, c, b, q));
  }
  Camera cam;
  std::string err;
  EXPECT_TRUE(chooseCamera(s.scene, cameraSel, cam, &err)) << err;
  if (cam.path == "auto") cam = autoCamera(s.scene, 1.0);
  s.ok = renderScene(s.scene, cam, options, s.image, s.diags);
  return s;
}

Pose at(double x, double y, double z) {
  Pose p;
  p.position = {x, y, z};
  return p;
}

// Pixel of world point (5, y, z) for the identity camera.
int px(double y) { return int(std::lround(100 - y * kPxPerMetre)); }
int py(double z) { return int(std::lround(100 - z * kPxPerMetre)); }

enum class Hue { Red, Green, Blue, Grey, Black };

Hue hueAt(const Image& im, int x, int y) {
  const std::uint8_t* p = im.pixel(x, y);
  int r = p[0], g = p[1], b = p[2];
  if (r + g + b < 30) return Hue::Black;
  if (r > 2 * g + 20 && r > 2 * b + 20) return Hue::Red;
  if (g > 2 * r + 20 && g > 2 * b + 20) return Hue::Green;
  if (b > 2 * r + 20 && b > 2 * g + 20) return Hue::Blue;
  if (std::abs(r - g) < 12 && std::abs(g - b) < 12) return Hue::Grey;
  return Hue::Black;
}

}  // namespace

TEST(RobotRender, FixedBaseLinksShowTheirColoursAtTheirPlaces) {
  robot::Model m = twoLinkArm(false);
  Shot s = shoot(m, Eigen::VectorXd::Zero(1), at(5, 0, 0));
  ASSERT_TRUE(s.ok);
  EXPECT_EQ(hueAt(s.image, px(0), py(0)), Hue::Red);
  EXPECT_EQ(hueAt(s.image, px(0), py(1)), Hue::Green);    // 1 m above the base
  EXPECT_EQ(hueAt(s.image, px(0), py(0.5)), Hue::Black);  // the gap between them
  EXPECT_EQ(hueAt(s.image, px(-1), py(0)), Hue::Black);
}

TEST(RobotRender, JointCoordinateMovesTheChildLink) {
  robot::Model m = twoLinkArm(false);
  Eigen::VectorXd q(1);
  q << M_PI / 2;  // about +x: the arm's +z turns to -y, the image's right
  Shot s = shoot(m, q, at(5, 0, 0));
  ASSERT_TRUE(s.ok);
  EXPECT_EQ(hueAt(s.image, px(0), py(0)), Hue::Red);
  EXPECT_EQ(hueAt(s.image, px(-1), py(0)), Hue::Green);
  EXPECT_EQ(hueAt(s.image, px(0), py(1)), Hue::Black);
}

TEST(RobotRender, FloatingBaseStandsWhereItsCoordinateSays) {
  robot::Model m = twoLinkArm(true);
  Eigen::VectorXd q(8);
  q << 5, 0.8, -0.5, 1, 0, 0, 0, 0;  // position, quaternion w x y z, j1
  Shot s = shoot(m, q, at(100, 100, 100));  // a floating base ignores the record's pose
  ASSERT_TRUE(s.ok);
  EXPECT_EQ(hueAt(s.image, px(0.8), py(-0.5)), Hue::Red);
  EXPECT_EQ(hueAt(s.image, px(0.8), py(0.5)), Hue::Green);
  EXPECT_EQ(hueAt(s.image, px(0), py(0)), Hue::Black);
}

TEST(RobotRender, CapsuleLengthIsBetweenHemisphereCentres) {
  // RaiSim's convention: radius 0.2, length 1 reaches 0.7 m above and below
  // its centre (a cylinder of 1 m and two hemispheres).
  robot::Model m;
  m.floatingBase = false;
  m.links.resize(1);
  robot::Visual v;
  v.geometry.kind = robot::GeometryKind::Capsule;
  v.geometry.radius = 0.2;
  v.geometry.length = 1.0;
  v.color = kBlue;
  m.links[0].visuals.push_back(v);
  Shot s = shoot(m, Eigen::VectorXd::Zero(0), at(5, 0, 0));
  ASSERT_TRUE(s.ok);
  int top = 0;
  while (top < 100 && hueAt(s.image, 100, top) != Hue::Blue) ++top;
  // The silhouette's top, seen from 5 m: atan(0.5 / 5) + asin(0.2 / |(5, 0.5)|).
  double angle = std::atan(0.1) + std::asin(0.2 / std::hypot(5.0, 0.5));
  double expected = 100 - std::tan(angle) / std::tan(M_PI / 6) * 100;
  EXPECT_NEAR(top, expected, 1.5);
  EXPECT_EQ(hueAt(s.image, 100, 100), Hue::Blue);
}

TEST(RobotRender, PrimitiveWithoutColourIsGrey) {
  robot::Model m;
  m.floatingBase = false;
  m.links.resize(1);
  m.links[0].visuals.push_back(boxVisual({0, 0, 0}, 0.5, std::nullopt));
  robot::Visual sphere;
  sphere.origin.position = {0, 0, 1};
  sphere.geometry.kind = robot::GeometryKind::Sphere;
  sphere.geometry.radius = 0.25;
  m.links[0].visuals.push_back(sphere);
  Shot s = shoot(m, Eigen::VectorXd::Zero(0), at(5, 0, 0));
  ASSERT_TRUE(s.ok);
  EXPECT_EQ(hueAt(s.image, px(0), py(0)), Hue::Grey);
  EXPECT_EQ(hueAt(s.image, px(0), py(1)), Hue::Grey);
}

TEST(RobotRender, MeshKeepsItsOwnMaterialUnlessTheFileColoursIt) {
  // crate.obj is a unit cube with a green MTL material.
  std::string crate = std::string(RSCENE_TEST_DATA) + "/render_assets/crate.obj";
  robot::Model m;
  m.floatingBase = false;
  m.links.resize(1);
  robot::Visual own;
  own.geometry.kind = robot::GeometryKind::Mesh;
  own.geometry.meshPath = crate;
  own.geometry.meshScale = {0.5, 0.5, 0.5};
  own.origin.position = {0, 0.8, 0};
  robot::Visual red = own;
  red.origin.position = {0, -0.8, 0};
  red.color = kRed;
  m.links[0].visuals = {own, red};
  Shot s = shoot(m, Eigen::VectorXd::Zero(0), at(5, 0, 0));
  ASSERT_TRUE(s.ok);
  EXPECT_EQ(hueAt(s.image, px(0.8), py(0)), Hue::Green);
  EXPECT_EQ(hueAt(s.image, px(-0.8), py(0)), Hue::Red);
  EXPECT_EQ(hueAt(s.image, px(0), py(0)), Hue::Black);
  // The mesh's own bounds (0.5 m cubes), not a unit box, frame the robot.
  EXPECT_NEAR(s.scene.bounds.sizes().y(), 2.1, 1e-6);
  EXPECT_NEAR(s.scene.bounds.sizes().z(), 0.5, 1e-6);
}

TEST(RobotRender, AutoCameraFramesTheRobot) {
  robot::Model m = twoLinkArm(false);
  Shot s = shoot(m, Eigen::VectorXd::Zero(1), at(30, -20, 4), {}, "auto");
  ASSERT_TRUE(s.ok);
  int red = 0, green = 0;
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 200; ++x) {
      Hue h = hueAt(s.image, x, y);
      red += h == Hue::Red;
      green += h == Hue::Green;
    }
  EXPECT_GT(red, 200);  // both links on screen, at a size one can see
  EXPECT_GT(green, 100);
  EXPECT_TRUE(s.scene.bounds.contains(Eigen::Vector3d(30, -20, 5)));
}

TEST(RobotRender, MissingMeshNamesTheRobotFileAndLine) {
  robot::Model m;
  m.floatingBase = false;
  m.sourceFile = "/robots/arm.urdf";
  m.links.resize(1);
  robot::Visual v;
  v.geometry.kind = robot::GeometryKind::Mesh;
  v.geometry.meshPath = "/nonexistent/link.dae";
  v.line = 17;
  m.links[0].visuals.push_back(v);
  Shot s = shoot(m, Eigen::VectorXd::Zero(0), at(5, 0, 0));
  EXPECT_FALSE(s.ok);
  ASSERT_FALSE(s.diags.empty());
  const Diagnostic& d = s.diags.back();
  EXPECT_EQ(d.severity, Severity::Error);
  EXPECT_EQ(d.code, "RS5001");
  EXPECT_EQ(d.file, "/robots/arm.urdf");
  EXPECT_EQ(d.line, 17u);
  EXPECT_EQ(d.message, "mesh file '/nonexistent/link.dae' does not exist");

  // Allowed: a warning and a small magenta box at the visual, not a 1 m one.
  RenderOptions allow;
  allow.allowMissingAssets = true;
  Shot placeholder = shoot(m, Eigen::VectorXd::Zero(0), at(5, 0, 0), allow);
  ASSERT_TRUE(placeholder.ok);
  EXPECT_EQ(placeholder.diags.back().severity, Severity::Warning);
  const std::uint8_t* c = placeholder.image.pixel(100, 100);
  EXPECT_GT(c[0], 100);
  EXPECT_GT(c[2], 100);
  EXPECT_LT(c[1], 40);
  EXPECT_EQ(hueAt(placeholder.image, px(0), py(0.2)), Hue::Black);  // 0.1 m: gone 0.2 m up
}

TEST(RobotRender, SixteenRobotsReadEachMeshFileOnce) {
  MemoryFileSystem fs;
  fs.addFile("/m/link.obj", "mtllib link.mtl\nv -0.1 -0.1 0\nv 0.1 -0.1 0\nv 0 0.1 0\nusemtl c\nf 1 2 3\n");
  fs.addFile("/m/link.mtl", "newmtl c\nKd 0.2 0.3 0.9\n");
  robot::Model m;
  m.floatingBase = false;
  m.links.resize(2);
  m.links[0].childJoints = {0};
  m.links[1].parentJoint = 0;
  robot::Joint j;
  j.type = robot::JointType::Fixed;
  j.parentLink = 0;
  j.childLink = 1;
  j.origin.position = {0, 0, 0.5};
  m.joints.push_back(j);
  robot::Visual v;
  v.geometry.kind = robot::GeometryKind::Mesh;
  v.geometry.meshPath = "/m/link.obj";
  m.links[0].visuals = {v, v};  // the same file twice in a link, and in every link
  m.links[1].visuals = {v};
  Shot s = shoot(m, Eigen::VectorXd::Zero(0), at(5, -8, 0), {}, "cam", fs, 16);
  ASSERT_TRUE(s.ok);
  EXPECT_EQ(s.scene.drawables.size(), 48u);
  EXPECT_EQ(fs.reads(), 2);  // link.obj and link.mtl, for bounds and drawing alike
}

TEST(RobotRender, MirroredMeshIsLitLikeTheOriginal) {
  // scale -1 on y turns the triangles' winding; culling the wrong faces
  // would show the unlit inside of the far wall.
  std::string crate = std::string(RSCENE_TEST_DATA) + "/render_assets/crate.obj";
  robot::Model m;
  m.floatingBase = false;
  m.links.resize(1);
  robot::Visual v;
  v.geometry.kind = robot::GeometryKind::Mesh;
  v.geometry.meshPath = crate;
  v.geometry.meshScale = {0.5, 0.5, 0.5};
  v.origin.position = {0, 0.8, 0};
  robot::Visual mirrored = v;
  mirrored.geometry.meshScale = {0.5, -0.5, 0.5};
  mirrored.origin.position = {0, -0.8, 0};
  m.links[0].visuals = {v, mirrored};
  Shot s = shoot(m, Eigen::VectorXd::Zero(0), at(5, 0, 0));
  ASSERT_TRUE(s.ok);
  const std::uint8_t* a = s.image.pixel(px(0.8), py(0));
  const std::uint8_t* b = s.image.pixel(px(-0.8), py(0));
  EXPECT_GT(a[1], 100);
  EXPECT_NEAR(int(b[1]), int(a[1]), 8);
}

TEST(RobotRender, UrdfMaterialTextureAndStlMesh) {
  // A box with the URDF material's texture (a 2x2 checker of yellow and
  // blue, no colour: drawn as it is) and an STL tetrahedron, which has no
  // material of its own: white, unless the file colours it.
  std::string assets = std::string(RSCENE_TEST_DATA) + "/render_assets/";
  robot::Model m;
  m.floatingBase = false;
  m.links.resize(1);
  robot::Visual box = boxVisual({0, 0, 0}, 1.0, std::nullopt);
  box.texture = assets + "checker.png";
  robot::Visual stl;
  stl.geometry.kind = robot::GeometryKind::Mesh;
  stl.geometry.meshPath = assets + "tetra.stl";
  stl.geometry.meshScale = {0.6, 0.6, 0.6};
  stl.origin.position = {-0.3, -1.2, 0.6};  // above right of the box
  robot::Visual redStl = stl;
  redStl.origin.position.y() = 0.6;  // above left
  redStl.color = kRed;
  m.links[0].visuals = {box, stl, redStl};
  Shot s = shoot(m, Eigen::VectorXd::Zero(0), at(5, 0, 0));
  ASSERT_TRUE(s.ok);
  // The two upper corners of the box's face: one yellow, one blue.
  const std::uint8_t* a = s.image.pixel(px(0.35), py(0.35));
  const std::uint8_t* b = s.image.pixel(px(-0.35), py(0.35));
  EXPECT_GT(std::abs(int(a[2]) - int(b[2])), 80) << int(a[2]) << " " << int(b[2]);
  EXPECT_GT(std::abs(int(a[0]) - int(b[0])), 80) << int(a[0]) << " " << int(b[0]);
  EXPECT_EQ(hueAt(s.image, px(-1.2 + 0.2), py(0.75)), Hue::Grey);
  EXPECT_EQ(hueAt(s.image, px(1.2 - 0.4), py(0.75)), Hue::Red);
}
