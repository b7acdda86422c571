// Views: what one camera record or camera-like sensor sees, as images
// (RGB, depth, segmentation), and the Renderer that draws many views of
// one scene with one upload (rscene-render --all-cameras, --trajectory).
//
// Frames: a view looks along its local +x with +z up (RaiSim's sensor
// frame: +x forward, +y left, +z up).  Depth is the distance along +x in
// metres, NaN where nothing is hit within [near, far].
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/diagnostic.hpp"
#include "render/image.hpp"
#include "render/render_scene.hpp"
#include "render/renderer.hpp"

namespace rscene::render {

enum class Pass { Color, Depth, Segmentation };
const char* passName(Pass p);  // "rgb", "depth", "segmentation" (the {kind} of output patterns)

// Pinhole intrinsics (View::fx..cy) follow intrinsicProjection()'s
// convention (camera.hpp): pixel (col, row) covers [col, col+1) x
// [row, row+1), its centre at +0.5, row 0 at the top; cx = width/2 is the
// image's centre.  They apply to perspective views (an orthographic view
// has no pinhole: its orthoScale and aspect rule).
struct View {
  std::string name;  // the camera's or sensor's path ("<robot>/<set>/<sensor>" for a URDF sensor)
  std::string id;    // record id, may be empty
  bool sensor = false;  // a sensor: draws world objects only (Drawable::worldObject)
  // Pose (world), fields of view, near/far, projection, orthoScale, image
  // size; Camera::renderMode as written.
  Camera camera;
  // Pinhole intrinsics in pixels, all > 0 or all 0 (then the fields of
  // view give them).  A point at (x, y, z) in the view frame lands on
  // column cx - fx*y/x and row cy - fy*z/x (row 0 at the top).
  double fx = 0, fy = 0, cx = 0, cy = 0;
  std::vector<Pass> passes;  // at least one
  // Samples per pixel of the color pass; 0: RenderOptions::samples.  Depth
  // and segmentation always take one, at the pixel's centre.  (llvmpipe
  // shades every sample: 4 cost about twice 1 for the ANYmal's color pass.)
  int samples = 0;
  // Additive Gaussian noise on depth (metres), from noiseSeed: the same
  // seed gives the same image.
  double noiseMean = 0, noiseStddev = 0;
  std::uint64_t noiseSeed = 0;
  std::string outputPath;  // as written; "-" and empty: none
  int recordIndex = -1;    // the camera or sensor record; -1 for a URDF sensor
  int sensorIndex = -1;  // into the robot::collectSensors list (sensor views), else -1
};

// The images of one view.  `color` and `segmentation` are RGBA8 rows top
// to bottom; `depth` width*height floats, rows top to bottom.
struct ViewImages {
  int width = 0, height = 0;
  Image color;
  std::vector<float> depth;
  Image segmentation;
};

// Why `view` cannot be drawn (a size outside 1..kMaxImageSide, no pass,
// intrinsics partly given or not finite and positive, near/far not 0 <
// near < far); empty when it can.
std::string viewProblem(const View& view);

// Clip-space matrix of the view: projection (its intrinsics when given and
// perspective, else the camera's fields of view or orthoScale) times the
// view matrix.
Eigen::Matrix4d viewProjection(const View& view);

// Adds Gaussian noise (mean, stddev in metres) to each finite value of
// `depth`; NaN stays NaN.  The value added at index i is a function of
// (seed, i) alone (splitmix64 and Box-Muller, no std:: distribution whose
// output is implementation-defined), so an image is the same on every
// run and, up to the last bit of libm's log and cos (which rounding to
// float hides in practice), every platform, whatever the other pixels hit.  A caller wanting
// different noise per frame of a trajectory passes a different seed (for
// instance seed + frame).
void addDepthNoise(std::vector<float>& depth, double mean, double stddev, std::uint64_t seed);

// Draws views of one RenderScene with the current EGL context.  Meshes and
// textures are uploaded once, by create(); updatePoses() carries new
// drawable transforms (after poseScene()) to the GPU without uploading
// anything else.
class Renderer {
 public:
  virtual ~Renderer() = default;
  // Null (with an error diagnostic) when an asset is missing and
  // !options.allowMissingAssets, or GL fails.  `scene` must outlive the
  // renderer.  options.width/height are ignored: each view has its size.
  static std::unique_ptr<Renderer> create(const RenderScene& scene, const RenderOptions& options,
                                          Diagnostics& diagnostics);
  // The scene's drawables moved (poseScene()): same drawables, new
  // Drawable::world and bounds.
  virtual void updatePoses() = 0;
  // The views the next frames draw (their poses now): granular particles,
  // which a trajectory moves anywhere, are re-tessellated for them as
  // createRenderer() tessellates round shapes at rest (a 20,000-grain bed
  // at 48 segments is 46 M triangles).  Other shapes keep theirs.
  virtual void setParticleViews(const std::vector<Camera>& cameras) = 0;
  // Renders the passes of `view` at view.camera.width x height.
  virtual bool render(const View& view, ViewImages& out, Diagnostics& diagnostics) = 0;
  virtual RenderTimings timings() const = 0;  // upload (create) and drawing so far
};

// Renderer::create() with spheres, cylinders and capsules tessellated for
// the views that will be drawn (each within half a pixel of round in the
// view that sees it largest, fewer triangles where all see it small);
// create() gives every one the finest tessellation (48 segments).
std::unique_ptr<Renderer> createRenderer(const RenderScene& scene, const RenderOptions& options,
                                         Diagnostics& diagnostics, std::vector<Camera> lodCameras);

}  // namespace rscene::render
