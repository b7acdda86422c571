#include "scene/mass_properties.hpp"

#include <cmath>

namespace rscene {

double compoundMass(const Compound& c) { return c.bodyMode != BodyMode::Dynamic && c.mass <= 0 ? 1.0 : c.mass; }

double primitiveVolume(const Compound& c, const CompoundChild& ch) {
  constexpr double kPi = 3.14159265358979323846;
  double r = childRadius(c, ch), h = childHeight(c, ch);
  if (ch.primitive == "box") return childBox(c, ch).prod();
  if (ch.primitive == "sphere") return 4.0 / 3.0 * kPi * r * r * r;
  if (ch.primitive == "cylinder") return kPi * r * r * h;
  if (ch.primitive == "capsule") return kPi * r * r * (h + 4.0 / 3.0 * r);
  return 0;
}

Eigen::Vector3d compoundCenterOfMass(const Compound& c, const std::vector<double>& volumes) {
  if (c.hasCenterOfMass) return c.centerOfMass;
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  double total = 0;
  for (std::size_t i = 0; i < c.children.size() && i < volumes.size(); ++i) {
    if (!(volumes[i] > 0)) continue;
    weighted += volumes[i] * childPose(c, c.children[i]).position;
    total += volumes[i];
  }
  return total > 0 ? Eigen::Vector3d(weighted / total) : Eigen::Vector3d::Zero();
}

}  // namespace rscene
