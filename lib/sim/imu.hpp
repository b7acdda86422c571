// An inertial measurement unit's reading, and how rscene-sim writes it.
//
// Specific force: the acceleration of the sensor's point minus gravity, in
// the sensor frame (at rest on the ground: +9.81 along the sensor's up;
// in free fall: zero).  The acceleration is the change of the point's
// velocity over the last step, (v_n - v_n-1) / dt, with v the velocity of
// the point fixed in its body (v_com + w x r, so a spinning body's
// centripetal w x (w x r) is in it); Bullet's step integrates velocity
// first, so this is exactly the acceleration the step applied.  Angular
// velocity: the body's, in the sensor frame.  Then noise (each of the six
// components + noiseMean + noiseStddev N(0, 1), sensor_noise.hpp with the
// sample number as stream and the component as index) and saturation
// (each component clamped to +-accelerationLimit, +-angularVelocityLimit
// when those are > 0).
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "scene/scene.hpp"

namespace rscene::sim {

struct ImuReading {
  double time = 0;
  Eigen::Vector3d specificForce = Eigen::Vector3d::Zero();    // m/s^2, sensor frame
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();  // rad/s, sensor frame
};

// The reading at `time` of an IMU at world pose `pose` whose point moved at
// `previousVelocity` a step `dt` ago and moves at `velocity` now, on a body
// turning at `omega` (world frame).  `sample` numbers the noise.
ImuReading imuReading(double time, const Pose& pose, const Eigen::Vector3d& previousVelocity,
                      const Eigen::Vector3d& velocity, const Eigen::Vector3d& omega, const Eigen::Vector3d& gravity,
                      double dt, const SensorParams& params, std::uint64_t sample);

enum class ImuFormat { Csv, Jsonl };

// CSV: a header line "time,ax,ay,az,wx,wy,wz" then one line per reading.
// JSON Lines: {"time":T,"acceleration":[ax,ay,az],"angularVelocity":[wx,wy,wz]}
// per reading (acceleration: the specific force).  Numbers shortest
// round-trip.
std::string imuHeader(ImuFormat format);
void appendImu(std::string& out, ImuFormat format, const ImuReading& r);

}  // namespace rscene::sim
