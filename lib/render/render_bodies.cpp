#include "render/render_bodies.hpp"

#include <cmath>

namespace rscene::render {

Eigen::Affine3d wireTransform(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double width) {
  Eigen::Vector3d d = b - a;
  double length = d.norm();
  double r = std::isfinite(width) && width > 0 ? width / 2 : 0;
  Eigen::Quaterniond q = length > 0 && std::isfinite(length)
                             ? Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), d / length)
                             : Eigen::Quaterniond::Identity();
  if (!std::isfinite(length)) length = 0;
  return Eigen::Translation3d((a + b) / 2) * q * Eigen::Scaling(r, r, length);
}

}  // namespace rscene::render
