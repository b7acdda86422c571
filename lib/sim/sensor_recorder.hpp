// rscene-sim --sensors: the physical sensors of a scene (lidar, imu;
// sensor records and robots' sensor sets, robot::collectSensors) sampled
// while the world steps.  The recorder computes readings; the driver
// writes them (SensorOutput), so lib/sim does no I/O.
//
// Schedule.  updateRate r > 0: a reading at the first step whose time is
// at or past each multiple of 1/r (so never more often than the steps; a
// rate above 1/time_step gives one reading per step); r = 0: every step.
// A LiDAR scans at time 0 (before the first step) too; an IMU's first
// reading is at 1/r (or after the first step when r = 0): an acceleration
// needs a step.
//
// A LiDAR does not see the body it rides on (an object or compound, or the
// robot body its link belongs to, RaiSim's rule for its cameras): its
// housing would hide everything.  The rest of its robot it sees (legs in
// the scan, as on a real robot).
#pragma once
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/codes.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "robot/sensors.hpp"
#include "sim/imu.hpp"
#include "sim/lidar.hpp"
#include "sim/world.hpp"

namespace rscene::sim {

namespace sim_code {
inline constexpr const char* kSensorSameOutput = rs::RS7070;   // two sensors, one output
inline constexpr const char* kSensorNotRecorded = rs::RS7071;  // a physical kind rscene-sim does not record (warning)
}  // namespace sim_code

// One physical sensor to record.
struct RecordedSensor {
  robot::SensorSpec spec;
  // Relative to the sensors folder: an IMU's file, a LiDAR's folder.
  std::string output;
  ImuFormat imuFormat = ImuFormat::Csv;
  std::vector<Eigen::Vector3d> directions;  // a LiDAR's rays, sensor frame
};

struct SensorPlanOptions {
  ImuFormat imuFormat = ImuFormat::Csv;  // for IMUs whose outputPath does not end in .csv or .jsonl
};

// The enabled lidar and imu sensors of `all` (sensorFileName() or the
// record's outputPath naming their outputs; IMU files get ".csv" or
// ".jsonl"): RS7070 (two outputs at one place) is an error, RS7071
// (force_torque and unknown kinds) a warning.  Camera-like sensors are
// rscene-render's and left out without a word.  The numbers and output
// paths are checkScene()'s (records) and the sensor-set reader's (robots)
// to refuse, with RS7066, RS7067 and RS7069 (scene/sensor_check.hpp); a
// caller that skipped those gets the same codes here, and the sensor is
// not recorded.
std::vector<RecordedSensor> planSensors(const Document& doc, const std::vector<robot::SensorSpec>& all,
                                        const SensorPlanOptions& options, Diagnostics& diagnostics);

// Where the driver puts the readings.  A false return stops the run.
class SensorOutput {
 public:
  virtual ~SensorOutput() = default;
  virtual bool lidarScan(std::size_t sensor, std::uint64_t index, double time, const Pose& pose,
                         const std::vector<Eigen::Vector3f>& points) = 0;
  virtual bool imuReading(std::size_t sensor, const ImuReading& reading) = 0;
};

class SensorRecorder {
 public:
  // `scene` and `world` must outlive the recorder.  Reads the collision
  // geometry once when there is a LiDAR.
  SensorRecorder(const Scene& scene, const World& world, std::vector<RecordedSensor> sensors, int threads = 2);
  ~SensorRecorder();

  // Call once before the first step and after every step (IMUs follow the
  // motion at every step): hands the readings due now to `out`.
  bool sample(SensorOutput& out);

  // Why sample() returned false without `out` refusing: a reading or a
  // sensor pose that was not finite (handed to nobody, so no file holds
  // it).  faultDiagnostic() says it: RS7024 at the sensor's record.
  struct Fault {
    std::size_t sensor = 0;
    double time = 0;
  };
  const std::optional<Fault>& fault() const { return fault_; }
  void faultDiagnostic(const Document& doc, Diagnostics& diagnostics) const;

  const std::vector<RecordedSensor>& sensors() const { return sensors_; }
  std::uint64_t scans() const { return scans_; }
  double scanSeconds() const { return scanSeconds_; }  // wall time spent casting rays

 private:
  struct State;
  bool due(State& s, double time, bool first) const;
  bool finite(std::size_t sensor, double time, const Pose& pose, const Eigen::Vector3d* a = nullptr,
              const Eigen::Vector3d* b = nullptr);

  const Scene& scene_;
  const World& world_;
  std::vector<RecordedSensor> sensors_;
  std::vector<State> states_;
  std::optional<Fault> fault_;
  std::unique_ptr<RayGeometry> geometry_;
  int threads_;
  std::uint64_t scans_ = 0;
  double scanSeconds_ = 0;
};

// The current world poses of the bodies sensors ride on (simulated bodies
// where they are now, the rest where the scene puts them).
robot::BodyPoses currentPoses(const Scene& scene, const World& world);

}  // namespace rscene::sim
