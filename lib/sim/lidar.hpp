// One LiDAR scan: channels (pitch rows) x samples (yaw columns, a full
// turn) of rays from the sensor's pose against the world's collision
// geometry (lidar_geometry.hpp).
//
// Sensor frame (RaiSim's): +x forward, +y left, +z up.  Channel i has pitch
// minPitch + i (maxPitch - minPitch) / (channels - 1) (one channel: the
// middle of the span), positive up; sample j has yaw j 360 / samples
// degrees from +x, counter-clockwise seen from above (+z), or clockwise
// when lidarClockwise.  Rays are cast in that order (channel-major); a ray
// whose first surface is closer than lidarMinRange or farther than
// lidarMaxRange (or that meets nothing) returns no point.  Noise: the
// range of each return gets noiseMean + noiseStddev N(0, 1) from
// sensor_noise.hpp (stream: the scan number, index: the ray), a noisy
// range of zero or less gives no point.  A scan is one instant: a real
// spinning LiDAR's turn takes 1/lidarSpinRate seconds while the robot
// moves (motion distortion); that is not modelled, lidarSpinRate is unused.
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "scene/scene.hpp"
#include "sim/lidar_geometry.hpp"

namespace rscene::sim {

// Unit ray directions in the sensor frame, channel-major.
std::vector<Eigen::Vector3d> lidarDirections(const SensorParams& p);

struct LidarScanOptions {
  const btCollisionObject* exclude = nullptr;  // the body the sensor rides on
  std::uint64_t scanIndex = 0;                 // noise stream
  int threads = 2;
};

// The returns of one scan from `pose` (the sensor's world pose), in the
// sensor frame, in ray order.
std::vector<Eigen::Vector3f> scanLidar(const RayGeometry& geometry, const Pose& pose, const SensorParams& p,
                                       const std::vector<Eigen::Vector3d>& directions,
                                       const LidarScanOptions& options = {});

}  // namespace rscene::sim
