// How the lit pass draws a view (passes.cpp colorPass): the pieces that
// decide the strategy, free of GL state so that they can be unit-tested.
//
// Why two strategies: llvmpipe (Mesa's CPU rasteriser) tests depth before
// shading and skips a 4x4 block whose fragments are all hidden only when
// the target has one sample; with MSAA it shades every fragment it
// rasterises, hidden or not (its early depth test then only masks the
// writes).  So on a scene whose surfaces overlap many deep (the real
// warehouse: placeholder boxes ~30 deep) a 4x MSAA pass pays the full
// shader for every layer.  There the renderer draws instead one
// single-sample pass per MSAA sample position, each jittered by that
// sample's offset, front to back (no depth pre-pass: on the warehouse it
// cost more raster than it saved shading), and averages them: the same
// coverage as the MSAA resolve, each sample shaded about once.  A
// multisampled id pass first (cheap: a flat id per instance and triangle)
// tells which instances some sample sees (the others are not drawn) and
// which pixels have samples that see different triangles: after the first
// pass only those are drawn again (the stencil), the rest keep the first
// pass's color, as MSAA shades such a pixel once.  On a
// shallow scene (the 5000-object yard) MSAA's one shade per pixel is
// cheaper than N jittered passes, so the choice is made per view from the
// estimated depth complexity.
#pragma once
#include <Eigen/Geometry>

#include <vector>

namespace rscene::render::detail {

// Sum of the screen areas (NDC, clipped to the screen) of the boxes'
// projections, divided by the screen's area: about how many layers of
// surface an average pixel has.  A box crossing the camera's plane counts
// as covering the screen.
class DepthComplexity {
 public:
  explicit DepthComplexity(const Eigen::Matrix4d& viewProj) : viewProj_(viewProj) {}
  void add(const Eigen::AlignedBox3d& box, double layers = 1);
  double value() const { return sum_ / 4.0; }  // NDC area of the screen: 2 x 2

 private:
  Eigen::Matrix4d viewProj_;
  double sum_ = 0;
};

// Choose the jittered single-sample passes over MSAA (software
// rasterisers only): when the estimated layers per pixel exceed what N
// shades per visible sample cost.  `samples`: the MSAA count it replaces.
bool preferJitteredPasses(double depthComplexity, int samples);

// Key of an instance for front-to-back order: its distance to the eye
// (perspective) or the depth of its nearest corner along the view
// (orthographic); smaller is nearer.
double nearness(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& eye, const Eigen::Vector3d& forward,
                bool orthographic);

// viewProj shifted so that the pixel centers sample the scene at `offset`
// (pixels, in [0,1)^2 from the pixel's lower left corner, GL's sample
// position convention) of a w x h image.
Eigen::Matrix4d jittered(const Eigen::Matrix4d& viewProj, const Eigen::Vector2f& offset, int w, int h);

// The sample positions of the standard MSAA patterns (GL/D3D) for 2, 4, 8
// and 16 samples; for another count, a regular grid.  Used when the driver
// cannot be asked (glGetMultisamplefv).
std::vector<Eigen::Vector2f> standardSamplePattern(int samples);

// Fragment shaders of the strategy's programs (vertex: kSurfaceVertex for
// the pre-pass, kPostVertex for the average).
extern const char* const kPrepassFragment;  // depth only
extern const char* const kAverageFragment;  // one jittered pass, weighted by the blend constant
// What each sample of a multisampled target sees (instance, triangle), and
// the pixels whose samples do not all see the same: only those are drawn
// by the jittered passes after the first.
extern const char* const kIdVertex;
extern const char* const kIdFragment;
extern const char* const kEdgeFragment;
extern const char* const kClearFragment;  // transparent black
extern const char* const kSpreadFragment;  // the ids' samples side by side, for reading back

}  // namespace rscene::render::detail
