// rscene-sim --sensors DIR: the files the sensor streams go to.
//
//   IMU    DIR/<name>.csv (or .jsonl), one line per reading, streamed while
//          the world steps and put in place when the run ends (atomically,
//          as every output: cli::writeOutput).
//   LiDAR  DIR/<name>/scan_NNNNNN.pcd, one file per scan, and
//          DIR/<name>/scans.csv (index,time,points,file).  The whole folder
//          is written as DIR/.<name>.tmpXXXXXX beside it (same parent, so
//          the rename is atomic) and put in place when the run succeeds,
//          replacing the folder of an earlier run (swapped in, the old one
//          then removed), so a folder never mixes two runs.
// <name>: sim::sensorFileName() or the record's outputPath.  A failed or
// interrupted run leaves nothing of its own: no IMU file, no temporary
// folder (discard()), and the earlier run's files exactly as they were.
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

  // Creates DIR and the folders under it, and each LiDAR's temporary scan
  // folder; refuses (with a message) an output that cannot be written or
  // that is one of `others` (-o, --trajectory) or inside a LiDAR's scan
  // folder, and a scan folder that is a symbolic link, not a folder, or
  // holds files rscene-sim did not write.  Call before stepping.
  bool prepare(std::vector<cli::NamedOutput> others);

  // Runs `simulate` with the streamed files open; when it returns true and
  // `*stopped` is 0, the files and the scan folders are put in place (stop
  // signals held off meanwhile, so a signal cannot leave half of them).
  bool run(const std::function<bool()>& simulate, const volatile std::sig_atomic_t* stopped);

  // Holds stop signals off from now until run() returns: `simulate` calls
  // it once its stepping succeeded, before the outputs it writes itself
  // (the trajectory) are put in place, where a signal would end the tool
  // at once and leave the temporary scan folders.
  void holdStops();

  // Removes the temporary scan folders and then the folders prepare()
  // created (those left empty), deepest first: a failed or interrupted run
  // leaves no sensor files.  Whatever was there before stays as it was.
  void discard();

  bool lidarScan(std::size_t sensor, std::uint64_t index, double time, const Pose& pose,
                 const std::vector<Eigen::Vector3f>& points) override;
  bool imuReading(std::size_t sensor, const sim::ImuReading& reading) override;

 private:
  struct ScanFolder {
    std::string final, temp;  // temp: "" until prepare() made it, and again once it is in place
  };
  bool open(std::size_t stream, const std::function<bool()>& simulate);
  void flush(std::size_t stream, bool all);
  bool commitFolders();

  std::string dir_;
  const std::vector<sim::RecordedSensor>& sensors_;
  sim::PcdEncoding encoding_;
  const volatile std::sig_atomic_t* stopped_ = nullptr;
  bool held_ = false;  // stop signals blocked from a successful simulation until the folders are in place
  sigset_t previousMask_{};
  // One streamed file per sensor (the IMU's file, the LiDAR's index).
  std::vector<std::string> paths_, buffers_;
  std::vector<Sink*> sinks_;
  std::vector<ScanFolder> folders_;   // per sensor; empty names for an IMU
  std::vector<std::string> created_;  // folders prepare() made, outermost first
};

}  // namespace rscene::simcmd
