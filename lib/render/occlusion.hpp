// Conservative occlusion culling on the CPU, for each view's instance
// selection (passes.cpp selectInstances): a coarse depth buffer that
// opaque boxes (the box primitive: walls, crates, shelves, the placeholders
// of missing meshes) are drawn into, nearest first, and that any instance's
// world bounds are tested against before it is drawn.
//
// Why: a software rasteriser pays for every triangle it rasterises, even
// where the depth test then rejects every fragment; a warehouse seen down
// an aisle has ~10000 boxes in view of which a few hundred are visible.
//
// Conservative: a buffer cell holds the farthest depth an occluder may
// have over the whole cell, and only cells that one occluder covers
// entirely are written; an instance is hidden only when each cell its
// bounds' screen rectangle touches is nearer than its nearest corner.  So
// an instance culled here would have failed the depth test at every
// sample of every pixel (MSAA and jittered passes alike: a jitter moves
// occluder and occludee together).
#pragma once
#include <Eigen/Geometry>

#include <vector>

namespace rscene::render::detail {

class OcclusionBuffer {
 public:
  // `cells`: the buffer's width in cells; its height follows the aspect.
  OcclusionBuffer(const Eigen::Matrix4d& viewProj, int imageWidth, int imageHeight, int cells = 256);

  // True when every point of `box` is behind what was added.
  bool hidden(const Eigen::AlignedBox3d& box) const;
  // Adds the unit cube [-0.5, 0.5]^3 placed by `model` as an occluder.
  void addBox(const Eigen::Matrix4d& model);

  int width() const { return w_; }
  int height() const { return h_; }

 private:
  struct Point {
    double x, y, z;  // buffer cells, NDC depth
  };
  bool project(const Eigen::Vector3d& p, Point& out) const;
  // Writes min(cell, depth) into every cell the convex polygon covers
  // entirely; depth is the plane through pts[0..2] (planar) or `flat`.
  void fill(const std::vector<Point>& polygon, bool planar, double flat);

  Eigen::Matrix4d viewProj_;
  int w_, h_;
  std::vector<double> depth_;  // row-major, 1 (the far plane) when empty
};

}  // namespace rscene::render::detail
