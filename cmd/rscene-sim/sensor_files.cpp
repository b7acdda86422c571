#include "sensor_files.hpp"

#include <pthread.h>

#include <algorithm>
#include <cctype>
#include <csignal>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "common/cli.hpp"

namespace rscene::simcmd {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kChunk = 1 << 16;

// Creates `p` and its missing parents, appending each one it creates to
// `created` (outermost first), so that a failed run can remove them.
bool makeFolder(const fs::path& p, std::vector<std::string>& created) {
  std::error_code ec;
  if (fs::is_directory(p, ec)) return true;
  std::vector<std::string> missing;
  for (fs::path q = p; !q.empty() && !fs::exists(fs::symlink_status(q, ec)); q = q.parent_path()) {
    missing.push_back(q.string());
    if (q == q.parent_path()) break;
  }
  fs::create_directories(p, ec);
  for (auto it = missing.rbegin(); it != missing.rend(); ++it)
    if (fs::is_directory(*it)) created.push_back(*it);
  if (ec || !fs::is_directory(p)) {
    std::string why = ec ? ec.message() : "something else is there";
    if (!why.empty()) why[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(why[0])));
    cli::error(p.string() + ": cannot create the folder: " + why);
    return false;
  }
  return true;
}

// Whether `path` names something below `folder` (both as they resolve;
// a path that does not exist yet resolves through its existing parents).
bool inside(const std::string& path, const fs::path& folder) {
  if (path.empty() || path == "-") return false;
  std::error_code ec;
  fs::path p = fs::weakly_canonical(path, ec);
  if (ec) return false;
  fs::path f = fs::weakly_canonical(folder, ec);
  if (ec) return false;
  auto [fi, pi] = std::mismatch(f.begin(), f.end(), p.begin(), p.end());
  return fi == f.end() && pi != p.end();
}

}  // namespace

SensorFiles::SensorFiles(std::string dir, const std::vector<sim::RecordedSensor>& sensors, sim::PcdEncoding encoding)
    : dir_(std::move(dir)), sensors_(sensors), encoding_(encoding) {
  for (const sim::RecordedSensor& s : sensors_) {
    fs::path out = fs::path(dir_) / s.output;
    paths_.push_back((s.spec.kind == robot::SensorKind::Lidar ? out / "scans.csv" : out).string());
  }
  buffers_.resize(paths_.size());
  sinks_.resize(paths_.size(), nullptr);
}

bool SensorFiles::prepare(std::vector<cli::NamedOutput> outputs) {
  if (!makeFolder(dir_, created_)) return false;
  const std::size_t given = outputs.size();  // -o, --trajectory
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    bool lidar = sensors_[i].spec.kind == robot::SensorKind::Lidar;
    fs::path folder = lidar ? fs::path(dir_) / sensors_[i].output : fs::path(paths_[i]).parent_path();
    if (!makeFolder(folder, created_)) return false;
    // A LiDAR's folder is its own: scan_NNNNNN.pcd files appear there as
    // the run goes, so no other output may be inside it.
    if (lidar)
      for (std::size_t k = 0; k < given; ++k)
        if (inside(outputs[k].path, folder)) {
          cli::error(std::string(outputs[k].flag) + " '" + outputs[k].path + "' is inside the scan folder '" + folder.string() +
                     "' of LiDAR '" + sensors_[i].spec.name +
                     "', where its scans are written: give a path outside --sensors' sensor folders");
          return false;
        }
    outputs.push_back({"--sensors", paths_[i]});
  }
  return cli::checkOutputs(outputs);
}

bool SensorFiles::open(std::size_t stream, const std::function<bool()>& simulate) {
  if (stream == paths_.size()) return simulate();
  // Nested: each file is written inside the one before, so all of them are
  // put in place together when the simulation succeeds, none when it fails.
  return cli::writeOutput(paths_[stream], [&](Sink& sink) {
    sinks_[stream] = &sink;
    const sim::RecordedSensor& s = sensors_[stream];
    buffers_[stream] =
        s.spec.kind == robot::SensorKind::Lidar ? "index,time,points,file\n" : sim::imuHeader(s.imuFormat);
    bool ok = open(stream + 1, simulate);
    if (ok) flush(stream, true);
    sinks_[stream] = nullptr;
    return ok;
  });
}

bool SensorFiles::run(const std::function<bool()>& simulate) { return open(0, simulate); }

void SensorFiles::flush(std::size_t stream, bool all) {
  if (!sinks_[stream] || (!all && buffers_[stream].size() < kChunk)) return;
  sinks_[stream]->write(buffers_[stream]);
  buffers_[stream].clear();
}

bool SensorFiles::lidarScan(std::size_t sensor, std::uint64_t index, double time, const Pose& pose,
                            const std::vector<Eigen::Vector3f>& points) {
  char name[40];
  std::snprintf(name, sizeof name, "scan_%06llu.pcd", static_cast<unsigned long long>(index));
  fs::path file = fs::path(dir_) / sensors_[sensor].output / name;
  // A stop signal waits while a scan is written (it would end the tool
  // there, leaving the scans before it): the stepping loop then sees the
  // flag, stops, and discard() removes them.
  sigset_t interrupt = cli::stopSignals(), previous;
  pthread_sigmask(SIG_BLOCK, &interrupt, &previous);
  bool written = cli::writeOutput(file.string(), [&](Sink& s) {
    sim::writePcd(s, points, pose, time, encoding_);
    return true;
  });
  if (written) scans_.push_back(file.string());
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  if (!written) return false;
  std::string& b = buffers_[sensor];
  char t[32];
  auto end = std::to_chars(t, t + sizeof t, time).ptr;
  b += std::to_string(index) + ',' + std::string(t, end) + ',' + std::to_string(points.size()) + ',' + name + '\n';
  flush(sensor, false);
  return true;
}

void SensorFiles::discard() {
  std::error_code ec;
  for (const std::string& scan : scans_) fs::remove(scan, ec);
  scans_.clear();
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) fs::remove(*it, ec);  // only when empty
  created_.clear();
}

bool SensorFiles::imuReading(std::size_t sensor, const sim::ImuReading& reading) {
  sim::appendImu(buffers_[sensor], sensors_[sensor].imuFormat, reading);
  flush(sensor, false);
  return true;
}

}  // namespace rscene::simcmd
