// libFuzzer target (tests/fuzz/run.sh): rscene-render --trajectory's reader
// on arbitrary bytes, every frame posed against a small scene (one box, one
// floating two-link robot, a cloth of 4 vertices and a granular record of
// unknown count), with limits small enough that the bounds are
// reached: no crash, no hang, memory bounded by the limits.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "robot/trajectory_read.hpp"

namespace {

rscene::robot::Model arm() {
  using namespace rscene::robot;
  Model m;
  m.name = "arm";
  m.links.resize(2);
  m.links[0].name = "base";
  m.links[1].name = "arm";
  Joint j;
  j.name = "j1";
  j.type = JointType::Spherical;
  j.parentLink = 0;
  j.childLink = 1;
  m.joints.push_back(j);
  m.links[0].childJoints.push_back(0);
  m.links[1].parentJoint = 0;
  return m;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rscene::robot;
  static rscene::Scene scene = [] {
    rscene::Scene s;
    s.objects.resize(1);
    s.objects[0].path = "/box";
    s.articulated.resize(1);
    s.articulated[0].path = "/arm";
    s.deformables.resize(1);
    s.deformables[0].path = "/cloth";
    s.granulars.resize(1);
    s.granulars[0].path = "/sand";
    return s;
  }();
  static std::vector<std::shared_ptr<const Model>> models{std::make_shared<Model>(arm())};
  static TrajectoryPoser poser(scene, models, ParticleCounts{{4}, {-1}});
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  TrajectoryLimits limits;
  limits.maxLineBytes = 4096;
  limits.maxEntriesPerFrame = 64;
  limits.maxPoints = 64;
  TrajectoryReader reader(in, "fuzz.jsonl", limits);
  TrajectoryFrame frame;
  rscene::Diagnostics d;
  BodyPoses poses = restPoses(scene, models);
  ParticlePositions particles;
  while (reader.next(frame, d)) poser.apply(frame, "fuzz.jsonl", poses, d, &particles);
  return 0;
}
