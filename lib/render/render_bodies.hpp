// Geometry of the body-like records rscene-render draws without simulating
// them (wires, granular media): shared by prepareScene() and poseScene().
#pragma once
#include <Eigen/Geometry>

namespace rscene::render {

// The unit cylinder (radius 1, z in [-0.5, 0.5]) -> a cylinder of diameter
// `width` from `a` to `b`.  Coincident ends give a zero-length cylinder.
Eigen::Affine3d wireTransform(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double width);

}  // namespace rscene::render
