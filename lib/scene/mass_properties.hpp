// Mass properties of bodies, decided once: rscene-sim builds its bodies
// from them and rscene-to-xml writes them, so the XML's body is the one
// that was simulated.
#pragma once
#include <Eigen/Core>
#include <vector>

#include "scene/scene.hpp"

namespace rscene {

// The mass a compound is simulated with: a dynamic compound's own (> 0,
// checked by RS7003); a static or kinematic one with mass <= 0 gets 1 kg,
// as an object does (Object::effectiveMass).
double compoundMass(const Compound& c);

// The true volume of a primitive compound child at its physical size
// (childBox, childRadius, childHeight): a box's w*h*d, a sphere's
// 4/3 pi r^3, a cylinder's pi r^2 h, a capsule's pi r^2 (h + 4/3 r).  0 for
// a mesh child: its volume is the simulator's hull's (the caller measures
// it), and no primitive.
double primitiveVolume(const Compound& c, const CompoundChild& ch);

// A compound's centre of mass in its own frame: centerOfMass when the
// record writes it, else its children's positions (childPose) weighted by
// `volumes` (one per child, in child order; a child of volume 0 does not
// count), the origin when no child has a volume.  Uniform density: the
// children's masses are the compound's mass in the same proportions.
Eigen::Vector3d compoundCenterOfMass(const Compound& c, const std::vector<double>& volumes);

}  // namespace rscene
