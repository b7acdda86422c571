// Conversions between Eigen and Bullet (double precision) for lib/sim's
// Bullet-facing sources.
#pragma once
#include <LinearMath/btTransform.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "scene/scene.hpp"  // Pose

namespace rscene::sim {

static_assert(sizeof(btScalar) == sizeof(double), "lib/sim needs Bullet's double-precision build");

inline btVector3 bt(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
inline btQuaternion bt(const Eigen::Quaterniond& q) { return {q.x(), q.y(), q.z(), q.w()}; }
inline btTransform bt(const Pose& p) { return btTransform(bt(p.orientation), bt(p.position)); }
inline Eigen::Vector3d eig(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
inline Eigen::Quaterniond eig(const btQuaternion& q) { return Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()); }
inline Pose pose(const btTransform& t) { return {eig(t.getOrigin()), eig(t.getRotation()).normalized()}; }

}  // namespace rscene::sim
