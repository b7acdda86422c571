// rscene-render's one pipeline (lib/render/view_select): a single camera
// is chosen as a view, with its renderMode; the image size default is
// decided once.  No GL: the views are data.
#include "render/view_select.hpp"

#include <gtest/gtest.h>

#include "core/loader.hpp"
#include "render/limits.hpp"
#include "render/output_plan.hpp"
#include "render/views.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

struct Built {
  LoadResult loaded;
  Scene scene;
  RenderScene render;
  std::vector<robot::SensorSpec> sensors;
  std::vector<View> all;
  Diagnostics diags;
  ViewSources sources() const { return {loaded.document, scene, render, sensors, "s.rscene"}; }
};

// Built in place: ViewSources refers to its members.
void build(Built& b, const std::string& body) {
  b.loaded = parse(
      "raisim_engine_scene 2\n"
      "object /World/Box box 1 0 0.5 1 0 0 0 1 1 1 0.5 1 1.0 default - false true false - dynamic true 1 "
      "18446744073709551615 id=box\n" +
      body);
  ASSERT_TRUE(b.loaded.ok());
  SceneOptions so;
  ASSERT_TRUE(buildRenderScene(b.loaded.document, so, b.scene, b.render, b.diags));
  b.sensors = robot::collectSensors(b.loaded.document, b.scene, b.render.robotModels, b.diags);
  robot::BodyPoses rest = robot::restPoses(b.scene, b.render.robotModels);
  b.all = collectViews(b.loaded.document, b.scene, b.render, b.sensors, rest, b.diags);
}

std::vector<View> select(const Built& b, const std::string& camera, ViewFindings& found, bool allCameras = false) {
  ViewRequest r;
  r.camera = camera;
  r.allCameras = allCameras;
  return selectViews(b.all, r, b.sources(), found);
}

}  // namespace

TEST(ImageSize, TheAutomaticViewAndASizelessCameraGetTheDefault) {
  Built b;
  build(b, "");
  ViewFindings found;
  std::vector<View> views = select(b, "", found);  // no camera: the automatic view
  ASSERT_TRUE(found.ok()) << found.error;
  ASSERT_EQ(views.size(), 1u);
  EXPECT_EQ(views[0].name, "auto");
  EXPECT_EQ(views[0].camera.width, kDefaultImageWidth);
  EXPECT_EQ(views[0].camera.height, kDefaultImageHeight);

  ViewRequest flags;
  flags.width = 40;
  flags.height = 30;
  views = selectViews(b.all, flags, b.sources(), found);
  ASSERT_EQ(views.size(), 1u);
  EXPECT_EQ(views[0].camera.width, 40);
  EXPECT_EQ(views[0].camera.height, 30);

  // A camera record of no size: sizeViews() gives it the same default.
  Built c;
  build(c, "camera /World/Cam -4 0 1 1 0 0 0 60 0.05 100 0 0 rgb true id=cam\n");
  views = select(c, "cam", found);
  ASSERT_EQ(views.size(), 1u);
  ViewRequest none;
  sizeViews(views, none, c.sources(), found);
  ASSERT_TRUE(found.ok()) << found.error;
  EXPECT_EQ(views[0].camera.width, kDefaultImageWidth);
  EXPECT_EQ(views[0].camera.height, kDefaultImageHeight);
}

TEST(ViewSelect, ASingleCameraIsAViewWithItsRenderMode) {
  Built b;
  build(b,
        "camera /World/Depth -4 0 1 1 0 0 0 60 0.05 100 64 48 depth true id=d\n"
        "camera /World/Both -4 0 1 1 0 0 0 60 0.05 100 64 48 rgb_depth true id=both\n");
  ViewFindings found;
  // The default camera (the first enabled record) and --camera NAME alike.
  for (const char* selector : {"", "d", "/World/Depth", "World/Depth"}) {
    std::vector<View> views = select(b, selector, found);
    ASSERT_TRUE(found.ok()) << found.error;
    ASSERT_EQ(views.size(), 1u) << selector;
    EXPECT_EQ(views[0].name, "/World/Depth");
    EXPECT_EQ(views[0].passes, std::vector<Pass>{Pass::Depth}) << selector;
    // One file holds its one image: the depth image, not a color one.
    EXPECT_EQ(keepOneImage(views[0], false), "");
    EXPECT_EQ(views[0].passes, std::vector<Pass>{Pass::Depth});
    // --reference compares a color image, which it does not make.
    EXPECT_EQ(keepOneImage(views[0], true),
              "--reference compares a color image; camera '/World/Depth' has renderMode depth, which makes none: "
              "write its images with -o and compare those files");
  }
  // The same view as --all-cameras has for it.
  std::vector<View> every = select(b, "", found, true);
  ASSERT_EQ(every.size(), 2u);
  EXPECT_EQ(every[0].passes, std::vector<Pass>{Pass::Depth});
  // rgb_depth in one file: its color image (as -o FILE has always written).
  std::vector<View> both = select(b, "both", found);
  ASSERT_EQ(both.size(), 1u);
  EXPECT_EQ(both[0].passes, (std::vector<Pass>{Pass::Color, Pass::Depth}));
  EXPECT_EQ(keepOneImage(both[0], false), "");
  EXPECT_EQ(both[0].passes, std::vector<Pass>{Pass::Color});
}

TEST(ViewSelect, UnknownAndAmbiguousNamesAreErrors) {
  Built b;
  build(b, "camera /World/Cam -4 0 1 1 0 0 0 60 0.05 100 64 48 rgb true id=cam\n");
  ViewFindings found;
  EXPECT_TRUE(select(b, "/World/Cma", found).empty());
  EXPECT_EQ(found.error, "no camera or camera-like sensor with path or id '/World/Cma'; did you mean '/World/Cam'?");
  Built two;
  build(two,
        "camera /World/Cam -4 0 1 1 0 0 0 60 0.05 100 64 48 rgb true id=cam\n"
        "camera /World/Other -4 0 1 1 0 0 0 60 0.05 100 64 48 rgb true id=/World/Cam\n");
  ViewFindings again;
  EXPECT_TRUE(select(two, "/World/Cam", again).empty());
  EXPECT_EQ(again.error.rfind("--camera '/World/Cam' names 2 views: '/World/Cam' (id cam), the camera record at s.rscene:3", 0),
            0u)
      << again.error;
}

// Where the images go (render/output_plan): decided from the views alone,
// before anything is drawn, with one message per way two images collide.
TEST(OutputPlan, PatternsFilesAndCollisions) {
  Built b;
  build(b,
        "camera /World/Depth -4 0 1 1 0 0 0 60 0.05 100 64 48 depth true id=d outputPath=shots/d.png\n"
        "camera /World/Both -4 0 1 1 0 0 0 60 0.05 100 64 48 rgb_depth true id=both outputPath=shots/both.png\n");
  ViewFindings found;
  std::vector<View> views = select(b, "", found, true);
  ASSERT_EQ(views.size(), 2u);
  OutputPlan plan;
  // The records' outputPath: a one-pass view keeps it, a two-pass one gains {kind}.
  ASSERT_TRUE(planOutputs(views, {}, b.sources(), plan, found)) << found.error;
  EXPECT_EQ(plan.files, (std::vector<std::string>{"shots/d.png", "shots/d.npy", "shots/both.rgb.png",
                                                  "shots/both.depth.png", "shots/both.depth.npy"}));
  ASSERT_EQ(plan.outputs.size(), 3u);
  EXPECT_EQ(outputPathAt(plan.outputs[2], views[1], 3, 0.5), "shots/both.depth.png");
  // A trajectory: every frame its own file.
  ASSERT_TRUE(planOutputs(views, {"out/{name}.{kind}.{frame}.png", true, false}, b.sources(), plan, found));
  EXPECT_EQ(outputPathAt(plan.outputs[0], views[0], 7, 0.5), "out/World_Depth.depth.000007.png");
  // Without {frame} or {time} every frame writes one file.
  EXPECT_FALSE(planOutputs(views, {"out/{name}.{kind}.png", true, false}, b.sources(), plan, found));
  EXPECT_EQ(found.error, "-o 'out/{name}.{kind}.png' has no {frame} or {time}: every frame of --trajectory would "
                         "write the same file");
  // Two views to one file, and one view's two passes to one file.
  found = {};
  EXPECT_FALSE(planOutputs(views, {"out/{kind}.png", false, false}, b.sources(), plan, found));
  EXPECT_EQ(found.error, "two images would go to 'out/depth.png': '/World/Depth' (depth) and '/World/Both' (depth); "
                         "use {name} and {kind} in -o, or give the records different outputPath [RS9048]");
  found = {};
  EXPECT_FALSE(planOutputs(views, {"out/{name}.png", false, false}, b.sources(), plan, found));
  EXPECT_NE(found.error.find("view '/World/Both' makes several images (rgb, depth); put {kind} in -o"),
            std::string::npos)
      << found.error;
  // Standard output takes one color image.
  found = {};
  EXPECT_FALSE(planOutputs(views, {"-", false, false}, b.sources(), plan, found));
  EXPECT_EQ(found.error.rfind("-o - writes one color image; these views make 3 images", 0), 0u) << found.error;
}

TEST(OutputPlan, AnOutputPathASceneMayNotWriteIsAnErrorAtTheField) {
  Built b;
  build(b, "camera /World/Cam -4 0 1 1 0 0 0 60 0.05 100 64 48 rgb true id=cam outputPath=x.png\n");
  ViewFindings found;
  std::vector<View> views = select(b, "cam", found);
  ASSERT_EQ(views.size(), 1u);
  // The scene model refuses it first (RS4xxx); a view's path is checked
  // again where it becomes a file name.
  views[0].outputPath = "../x.png";
  OutputPlan plan;
  EXPECT_FALSE(planOutputs(views, {}, b.sources(), plan, found));
  ASSERT_EQ(found.diagnostics.size(), 1u);
  EXPECT_EQ(found.diagnostics[0].code, std::string("RS9048"));
  EXPECT_EQ(found.diagnostics[0].line, 3u);
  EXPECT_TRUE(plan.files.empty());
}

// Issue 27: the look-at form is a view of its own, drawn as the automatic
// one is (its color image, the flags' size or the default), in place of
// the scene's camera; sizeViews() keeps its size.
TEST(ViewSelect, TheLookAtFormIsAViewOfItsOwn) {
  Built b;
  build(b, "camera /World/Cam -4 0 1 1 0 0 0 60 0.05 100 64 48 rgb_depth true id=cam\n");
  ViewRequest r;
  r.lookAt = true;
  r.lookFrom = Eigen::Vector3d(-3, -4, 2.5);
  r.lookTo = Eigen::Vector3d(1, 0, 0.5);
  r.lookFov = 35;
  r.width = 80;
  r.height = 60;
  ViewFindings found;
  std::vector<View> views = selectViews(b.all, r, b.sources(), found);
  ASSERT_TRUE(found.ok()) << found.error;
  ASSERT_EQ(views.size(), 1u);
  EXPECT_EQ(views[0].name, "look-at");
  EXPECT_EQ(views[0].passes, std::vector<Pass>{Pass::Color});
  EXPECT_FALSE(views[0].sensor);
  EXPECT_TRUE(views[0].camera.world.position.isApprox(r.lookFrom));
  EXPECT_DOUBLE_EQ(views[0].camera.verticalFov, 35);
  sizeViews(views, r, b.sources(), found);
  ASSERT_TRUE(found.ok()) << found.error;
  EXPECT_EQ(views[0].camera.width, 80);
  EXPECT_EQ(views[0].camera.height, 60);
  EXPECT_EQ(keepOneImage(views[0], true), "");  // --reference compares it
}
