// Views of rscene-render --all-cameras (lib/render/views): one per camera
// record and camera-like sensor with the passes, intrinsics and noise their
// records give, riding on their bodies and robot links; output patterns and
// the outputPath rules.  No GL: the views are data.
#include "render/views.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/loader.hpp"
#include "render/limits.hpp"
#include "robot/kinematics.hpp"
#include "scene/sensor_check.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

const char* kHeader =
    "raisim_engine_scene 2\n"
    "object /World/Box box 1 0 0.5 1 0 0 0 1 1 1 0.5 1 1.0 default - false true false - dynamic true 1 "
    "18446744073709551615 id=box\n";

struct Built {
  bool ok = false;
  Scene scene;
  RenderScene render;
  std::vector<robot::SensorSpec> sensors;
  robot::BodyPoses rest;
  std::vector<View> views;
  Diagnostics diags;
};

Built build(const std::string& body, const std::string& dir = ".") {
  Built b;
  LoadResult loaded = parse(kHeader + body);
  EXPECT_TRUE(loaded.ok());
  SceneOptions so;
  so.sceneDir = dir;
  b.ok = buildRenderScene(loaded.document, so, b.scene, b.render, b.diags);
  b.sensors = robot::collectSensors(loaded.document, b.scene, b.render.robotModels, b.diags);
  b.rest = robot::restPoses(b.scene, b.render.robotModels);
  b.views = collectViews(loaded.document, b.scene, b.render, b.sensors, b.rest, b.diags);
  return b;
}

TEST(Views, RenderModesGiveTheirPasses) {
  std::vector<Pass> p;
  EXPECT_TRUE(passesOfRenderMode("rgb", p));
  EXPECT_EQ(p, std::vector<Pass>{Pass::Color});
  EXPECT_TRUE(passesOfRenderMode("depth", p));
  EXPECT_EQ(p, std::vector<Pass>{Pass::Depth});
  EXPECT_TRUE(passesOfRenderMode("segmentation", p));
  EXPECT_EQ(p, std::vector<Pass>{Pass::Segmentation});
  EXPECT_TRUE(passesOfRenderMode("rgb_depth", p));
  EXPECT_EQ(p, (std::vector<Pass>{Pass::Color, Pass::Depth}));
  EXPECT_FALSE(passesOfRenderMode("thermal", p));
  EXPECT_EQ(p, std::vector<Pass>{Pass::Color});
}

TEST(Views, OneViewPerCameraAndCameraLikeSensor) {
  Built b = build(
      "camera /World/Front -3 0 1 1 0 0 0 60 0.1 50 320 240 rgbd true id=front\n"
      "camera /World/Off -3 0 1 1 0 0 0 60 0.1 50 320 240 rgb false id=off\n"
      "camera /World/Heat -3 0 1 1 0 0 0 60 0.1 50 320 240 thermal true id=heat\n"
      "sensor /World/Depth depth_camera box 0 0 1 1 0 0 0 id=depth width=64 height=48 calibrationFx=50 "
      "calibrationFy=51 calibrationCx=32 calibrationCy=24 nearPlane=0.2 farPlane=9 noiseStddev=0.01 noiseSeed=7 "
      "segmentation=true\n"
      "sensor /World/Color camera box 0 0 1 1 0 0 0 id=color\n"
      "sensor /World/Imu imu box 0 0 0 1 0 0 0 id=imu\n");
  ASSERT_TRUE(b.ok) << (b.diags.empty() ? "" : b.diags[0].message);
  ASSERT_EQ(b.views.size(), 5u);  // not the IMU
  EXPECT_EQ(b.views[0].name, "/World/Front");
  EXPECT_EQ(b.views[0].passes, (std::vector<Pass>{Pass::Color, Pass::Depth}));  // rgbd is rgb_depth
  EXPECT_FALSE(b.views[1].camera.enabled);
  EXPECT_EQ(b.views[2].passes, std::vector<Pass>{Pass::Color});
  ASSERT_EQ(b.diags.size(), 1u);
  EXPECT_EQ(b.diags[0].code, "RS9045");
  EXPECT_EQ(b.diags[0].severity, Severity::Warning);
  EXPECT_EQ(b.diags[0].line, 5u);
  EXPECT_EQ(b.diags[0].column, 53u);  // at "thermal"

  const View& depth = b.views[3];
  EXPECT_TRUE(depth.sensor);
  EXPECT_EQ(depth.id, "depth");
  EXPECT_EQ(depth.passes, (std::vector<Pass>{Pass::Depth, Pass::Segmentation}));
  EXPECT_EQ(depth.camera.width, 64);
  EXPECT_EQ(depth.camera.height, 48);
  EXPECT_EQ(depth.fx, 50);
  EXPECT_EQ(depth.fy, 51);
  EXPECT_EQ(depth.cx, 32);
  EXPECT_EQ(depth.cy, 24);
  EXPECT_EQ(depth.camera.nearPlane, 0.2);
  EXPECT_EQ(depth.camera.farPlane, 9);
  EXPECT_EQ(depth.noiseStddev, 0.01);
  EXPECT_EQ(depth.noiseSeed, 7u);
  EXPECT_EQ(depth.sensorIndex, 0);
  // On the box (1 0 0.5), 1 m above its centre.
  EXPECT_TRUE(depth.camera.world.position.isApprox(Eigen::Vector3d(1, 0, 1.5)));

  const View& color = b.views[4];
  EXPECT_EQ(color.passes, std::vector<Pass>{Pass::Color});
  EXPECT_EQ(color.fx, 0);              // no calibration: the fields of view
  EXPECT_EQ(color.camera.width, 640);  // the sensor record's defaults
  EXPECT_EQ(color.camera.verticalFov, 60);
}

TEST(Views, ACalibrationWithThePrincipalPointAtZeroIsUsedAllZerosIsNone) {
  // Validate accepts cx = cy = 0 (a crop's principal point): render must
  // use that calibration, not fall back to the fields of view; four zeros,
  // as Engine 2 writes an uncalibrated sensor, are no calibration.
  Built b = build(
      "sensor /World/Crop rgb box 0 0 1 1 0 0 0 calibrationFx=50 calibrationFy=50 calibrationCx=0 calibrationCy=0\n"
      "sensor /World/Plain rgb box 0 0 1 1 0 0 0 calibrationFx=0 calibrationFy=0 calibrationCx=0 calibrationCy=0\n");
  ASSERT_TRUE(b.ok) << (b.diags.empty() ? "" : b.diags[0].message);
  ASSERT_EQ(b.views.size(), 2u);
  EXPECT_EQ(b.views[0].fx, 50);
  EXPECT_EQ(b.views[0].cx, 0);
  EXPECT_EQ(viewProblem(b.views[0]), "");
  EXPECT_EQ(b.views[1].fx, 0);
}

TEST(Views, ACameraOnABodyMovesWithIt) {
  Built b = build("camera /World/Box/Cam 0 0 1 1 0 0 0 60 0.1 50 320 240 rgb true id=cam parentGroupId=box\n");
  ASSERT_TRUE(b.ok);
  ASSERT_EQ(b.views.size(), 1u);
  EXPECT_TRUE(b.views[0].camera.world.position.isApprox(Eigen::Vector3d(1, 0, 1.5)));
  robot::BodyPoses moved = b.rest;
  moved.objects[0].position = {4, 0, 0.5};
  moved.objects[0].orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  poseViews(b.views, b.scene, b.render, b.sensors, b.rest, moved);
  EXPECT_TRUE(b.views[0].camera.world.position.isApprox(Eigen::Vector3d(4, 0, 1.5)));
  // It turned with the box: it looks along +y now.
  EXPECT_TRUE((b.views[0].camera.world.orientation * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
}

TEST(Views, ASensorOnARobotLinkMovesWithTheLink) {
  auto dir = std::filesystem::temp_directory_path() / "rscene_views_test_arm";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "arm.urdf") << R"(<robot name="arm">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base"><visual><geometry><box size="0.2 0.2 0.2"/></geometry></visual></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 1"/>
    <axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <link name="arm"><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>
</robot>
)";
  Built b = build(
      "articulated_resource arm_res Arm arm.urdf\n"
      "articulated /World/Arm arm_res 0 0 0 1 0 0 0 true true id=arm\n"
      "sensor /World/Arm/Eye rgb arm 0 0 0.5 1 0 0 0 id=eye parentLink=arm width=32 height=24\n",
      dir.string());
  ASSERT_TRUE(b.ok) << (b.diags.empty() ? "" : b.diags[0].message);
  ASSERT_EQ(b.views.size(), 1u);
  EXPECT_TRUE(b.views[0].camera.world.position.isApprox(Eigen::Vector3d(0, 0, 1.5)));
  robot::BodyPoses turned = b.rest;
  // j1 at a quarter turn about x: the arm's +z points along -y.
  robot::Coordinates c;
  robot::makeCoordinates(*b.render.robotModels[0], {}, c);
  Eigen::VectorXd q = Eigen::VectorXd::Constant(c.coordinateDim, M_PI / 2);
  turned.robotLinks[0] = robot::linkPoses(*b.render.robotModels[0], c, b.scene.articulated[0].world, q);
  poseViews(b.views, b.scene, b.render, b.sensors, b.rest, turned);
  EXPECT_TRUE(b.views[0].camera.world.position.isApprox(Eigen::Vector3d(0, -0.5, 1)))
      << b.views[0].camera.world.position;
  std::filesystem::remove_all(dir);
}

TEST(Views, FindViewByPathIdOrRobotSensorName) {
  std::vector<View> views(2);
  views[0].name = "/World/Cam";
  views[0].id = "cam";
  views[1].name = "/World/Robot/front_cam/depth";
  EXPECT_EQ(findView(views, "/World/Cam"), 0);
  EXPECT_EQ(findView(views, "World/Cam"), 0);
  EXPECT_EQ(findView(views, "cam"), 0);
  EXPECT_EQ(findView(views, "/World/Robot/front_cam/depth"), 1);
  EXPECT_EQ(findView(views, "World/Robot/front_cam/depth"), 1);
  EXPECT_EQ(findView(views, "depth"), -1);
  EXPECT_EQ(findView(views, ""), -1);
}

TEST(Views, FindViewsListsEveryViewOfOneName) {
  std::vector<View> views(3);
  views[0].name = "/World/A/front/color";  // a sensor record named like a URDF sensor
  views[0].id = "rec";
  views[1].name = "/World/A/front/color";
  views[2].name = "/World/B";
  views[2].id = "World/A/front/color";  // an id equal to another's path
  EXPECT_EQ(findViews(views, "World/A/front/color"), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(findViews(views, "rec"), (std::vector<int>{0}));
  EXPECT_TRUE(findViews(views, "nosuch").empty());
  EXPECT_EQ(findView(views, "/World/A/front/color"), 0);
}

TEST(OutputNames, FileNamesAreSafe) {
  EXPECT_EQ(fileNameOf("/World/Robot/front_cam/depth"), "World_Robot_front_cam_depth");
  EXPECT_EQ(fileNameOf("/a b/c:d\xc3\xa9"), "a_b_c_d__");
  EXPECT_EQ(fileNameOf("/.."), "__");
  EXPECT_EQ(fileNameOf("/"), "_");
  EXPECT_EQ(fileNameOf("x.y-z"), "x.y-z");
}

TEST(OutputNames, PatternsExpandTheirFields) {
  OutputFields f{"World_Cam", "", "depth", 42, "0.25"};
  std::string out, err;
  ASSERT_TRUE(expandPattern("out/{name}.{kind}.{frame}_{time}_{id}.png", f, out, &err));
  EXPECT_EQ(out, "out/World_Cam.depth.000042_0.25_World_Cam.png");  // {id}: the name when there is none
  f.id = "cam";
  f.frame = 1234567;
  ASSERT_TRUE(expandPattern("{{{id}}}-{frame}", f, out, &err));
  EXPECT_EQ(out, "{cam}-1234567");
  EXPECT_FALSE(expandPattern("{nme}.png", f, out, &err));
  EXPECT_NE(err.find("unknown field {nme}"), std::string::npos);
  EXPECT_FALSE(expandPattern("{name.png", f, out, &err));
  EXPECT_FALSE(expandPattern("name}.png", f, out, &err));
  EXPECT_TRUE(patternHas("a/{frame}.png", "frame"));
  EXPECT_FALSE(patternHas("a/frame.png", "frame"));
}

TEST(OutputNames, AScenesOutputPathStaysBelowTheCurrentFolder) {
  EXPECT_EQ(outputPathProblem("captures/front.png"), "");
  EXPECT_EQ(outputPathProblem("a..b/c.png"), "");
  EXPECT_NE(outputPathProblem("/tmp/x.png"), "");
  EXPECT_NE(outputPathProblem("../x.png"), "");
  EXPECT_NE(outputPathProblem("a/../../x.png"), "");
  EXPECT_NE(outputPathProblem("a\\..\\x.png"), "");
  EXPECT_NE(outputPathProblem("a/.."), "");
  EXPECT_NE(outputPathProblem("C:x.png"), "");
}

TEST(OutputNames, OutputPathGainsKindAndFrameWhenNeeded) {
  EXPECT_EQ(outputPathPattern("cap/front.png", false, false), "cap/front.png");
  EXPECT_EQ(outputPathPattern("cap/front.png", true, false), "cap/front.{kind}.png");
  EXPECT_EQ(outputPathPattern("cap/front.png", true, true), "cap/front.{kind}.{frame}.png");
  EXPECT_EQ(outputPathPattern("cap/{frame}-front.png", true, true), "cap/{frame}-front.{kind}.png");
  // No extension: the images are PNG files all the same.
  EXPECT_EQ(outputPathPattern("cap.d/front", false, true), "cap.d/front.{frame}.png");
  EXPECT_EQ(outputPathPattern(".hidden", true, false), ".hidden.{kind}.png");
  EXPECT_EQ(outputPathPattern("noext", true, false), "noext.{kind}.png");
  EXPECT_EQ(outputPathPattern("noext", false, false), "noext");  // one image: the path as written
  // {time} names each frame of a trajectory once, as {frame} does.
  EXPECT_EQ(outputPathPattern("cap/front-{time}.png", false, true), "cap/front-{time}.png");
  EXPECT_EQ(outputPathPattern("cap/front-{time}.png", true, true), "cap/front-{time}.{kind}.png");
}

TEST(OutputNames, ImagesArePngOrHaveNoExtension) {
  EXPECT_EQ(imageExtensionProblem("a/b.png"), "");
  EXPECT_EQ(imageExtensionProblem("a/b.PNG"), "");
  EXPECT_EQ(imageExtensionProblem("a/b.Png"), "");
  EXPECT_EQ(imageExtensionProblem("a/b"), "");
  EXPECT_EQ(imageExtensionProblem("a.d/b"), "");  // a dot in a folder is no extension
  EXPECT_EQ(imageExtensionProblem("a/.hidden"), "");
  EXPECT_NE(imageExtensionProblem("a/b.jpg"), "");
  EXPECT_NE(imageExtensionProblem("a/b.depth.npy"), "");
  EXPECT_NE(imageExtensionProblem("b.png.json"), "");
  EXPECT_NE(imageExtensionProblem("a/b.rgb"), "");
  EXPECT_NE(imageExtensionProblem("a/b.jpg").find("PNG images only"), std::string::npos);
  // A name that promises no other format is the user's to choose (a FIFO, a temporary).
  EXPECT_EQ(imageExtensionProblem("pipe.render-o"), "");
  EXPECT_EQ(imageExtensionProblem("frame.tmp"), "");
}

}  // namespace

TEST(ImageSize, OneDefaultDecidedOnce) {
  // A view with no size of its own and no flags: 1280x720, the default of
  // rscene-render(1), for a camera record, the automatic view and the
  // renderer's own options alike.
  EXPECT_EQ(kDefaultImageWidth, 1280);
  EXPECT_EQ(kDefaultImageHeight, 720);
  ImageSize none = cameraImageSize(Camera{});
  EXPECT_EQ(none.width, kDefaultImageWidth);
  EXPECT_EQ(none.height, kDefaultImageHeight);
  EXPECT_EQ(RenderOptions{}.width, none.width);
  EXPECT_EQ(RenderOptions{}.height, none.height);
  // Each side on its own: the flag, else the camera's, else the default.
  Camera own;
  own.width = 64;
  own.height = 48;
  EXPECT_EQ(cameraImageSize(own).width, 64);
  EXPECT_EQ(cameraImageSize(own).height, 48);
  EXPECT_EQ(cameraImageSize(own, 100).width, 100);
  EXPECT_EQ(cameraImageSize(own, 100).height, 48);
  EXPECT_EQ(cameraImageSize(own, 0, 30).width, 64);
  EXPECT_EQ(cameraImageSize(own, 0, 30).height, 30);
  Camera wide;
  wide.width = 640;  // no height of its own
  EXPECT_EQ(cameraImageSize(wide).width, 640);
  EXPECT_EQ(cameraImageSize(wide).height, kDefaultImageHeight);
  EXPECT_EQ(cameraImageSize(Camera{}, 40).width, 40);
  EXPECT_EQ(cameraImageSize(Camera{}, 40).height, kDefaultImageHeight);
}
