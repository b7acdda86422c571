// rscene-sim --sensors DIR: the files the sensor streams go to.
//
//   IMU    DIR/<name>.csv (or .jsonl), one line per reading, streamed while
//          the world steps and put in place when the run ends (atomically,
//          as every output: cli::writeOutput).
//   LiDAR  DIR/<name>/scan_NNNNNN.pcd, one file per scan (written as it is
//          taken), and DIR/<name>/scans.csv (index,time,points,file),
//          streamed like an IMU file.
// <name>: sim::sensorFileName() or the record's outputPath.  A failed or
// interrupted run leaves nothing of its own: no IMU file, no index, and
// discard() removes the scans it wrote and the folders it created.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "core/writer.hpp"
#include "sim/pcd.hpp"
#include "sim/sensor_recorder.hpp"

namespace rscene::simcmd {

class SensorFiles : public sim::SensorOutput {
 public:
  SensorFiles(std::string dir, const std::vector<sim::RecordedSensor>& sensors, sim::PcdEncoding encoding);

  // Creates DIR and the folders under it, and refuses (with a message) an
  // output that cannot be written or that is one of `others` (-o,
  // --trajectory).  Call before stepping.
  bool prepare(std::vector<cli::NamedOutput> others);

  // Runs `simulate` with the streamed files open; they are put in place
  // when it returns true.
  bool run(const std::function<bool()>& simulate);

  // Removes the scans this run wrote and then the folders prepare()
  // created (those left empty), deepest first: a failed or interrupted run
  // leaves no sensor files.  Files that were there before stay.
  void discard();

  bool lidarScan(std::size_t sensor, std::uint64_t index, double time, const Pose& pose,
                 const std::vector<Eigen::Vector3f>& points) override;
  bool imuReading(std::size_t sensor, const sim::ImuReading& reading) override;

 private:
  bool open(std::size_t stream, const std::function<bool()>& simulate);
  void flush(std::size_t stream, bool all);

  std::string dir_;
  const std::vector<sim::RecordedSensor>& sensors_;
  sim::PcdEncoding encoding_;
  // One streamed file per sensor (the IMU's file, the LiDAR's index).
  std::vector<std::string> paths_, buffers_;
  std::vector<Sink*> sinks_;
  std::vector<std::string> scans_;    // written by this run
  std::vector<std::string> created_;  // folders prepare() made, outermost first
};

}  // namespace rscene::simcmd
