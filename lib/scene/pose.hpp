// A pose of the scene model: position and unit orientation.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rscene {

struct Pose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // normalised

  Pose operator*(const Pose& child) const {
    return {position + orientation * child.position, (orientation * child.orientation).normalized()};
  }
  Pose inverse() const {
    Eigen::Quaterniond q = orientation.conjugate();
    return {q * -position, q};
  }
};

}  // namespace rscene
