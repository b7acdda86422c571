#include "sensor_files.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "common/cli.hpp"

namespace rscene::simcmd {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kChunk = 1 << 16;
constexpr std::size_t kMaxTempBaseBytes = 200;  // ".NAME.tmpXXXXXX" must fit NAME_MAX (255)

std::string lowerFirst(std::string why) {
  if (why.size() > 1 && std::isupper(static_cast<unsigned char>(why[0])) &&
      !std::isupper(static_cast<unsigned char>(why[1])))
    why[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(why[0])));
  return why;
}

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
    cli::error(p.string() + ": cannot create the folder: " + lowerFirst(why));
    return false;
  }
  return true;
}

// Whether `path` names `folder` or something below it (both as they
// resolve; a path that does not exist yet resolves through its existing
// parents).  `same` tells which.
bool within(const std::string& path, const fs::path& folder, bool& same) {
  if (path.empty() || path == "-") return false;
  std::error_code ec;
  fs::path p = fs::weakly_canonical(path, ec);
  if (ec) return false;
  fs::path f = fs::weakly_canonical(folder, ec);
  if (ec) return false;
  auto [fi, pi] = std::mismatch(f.begin(), f.end(), p.begin(), p.end());
  if (fi != f.end()) return false;
  same = pi == p.end() || (std::next(pi) == p.end() && pi->empty());  // "dir/" names dir
  return true;
}

// The names a LiDAR's folder holds after a run of rscene-sim (and the
// temporary files of one that was killed): a re-run may replace them.
bool scanFolderEntry(const fs::directory_entry& e) {
  std::string name = e.path().filename().string();
  std::error_code ec;
  if (!e.is_regular_file(ec) || e.is_symlink(ec)) return false;
  if (name == "scans.csv" || name.rfind(".scans.csv.tmp", 0) == 0) return true;
  std::string_view n = name;
  if (n.rfind(".scan_", 0) == 0 && n.find(".pcd.tmp") != std::string_view::npos) return true;
  if (n.rfind("scan_", 0) != 0 || n.size() < 5 + 6 + 4 || n.substr(n.size() - 4) != ".pcd") return false;
  std::string_view digits = n.substr(5, n.size() - 9);
  return std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// Why the LiDAR scan folder `folder` (as it is now) may not be written and
// replaced, or "" when it may: nothing there, or a folder of scans.
std::string scanFolderRefusal(const fs::path& folder) {
  struct stat st {};
  if (::lstat(folder.c_str(), &st) != 0) {
    if (errno == ENOENT) return {};
    return lowerFirst(std::strerror(errno));
  }
  if (S_ISLNK(st.st_mode))
    return "is a symbolic link; a LiDAR's scan folder is replaced as a whole after each run, so it must be a real "
           "folder (or nothing): remove the link or choose another --sensors folder";
  if (!S_ISDIR(st.st_mode)) return "is in the way of the LiDAR's scan folder and is not a folder: remove it or choose another --sensors folder";
  std::error_code ec;
  fs::directory_iterator it(folder, ec), end;
  if (ec) return "cannot read the folder: " + lowerFirst(ec.message());
  for (; it != end; it.increment(ec)) {
    if (ec) return "cannot read the folder: " + lowerFirst(ec.message());
    if (!scanFolderEntry(*it))
      return "holds '" + it->path().filename().string() +
             "', which is not a scan rscene-sim wrote; a re-run replaces the whole scan folder: move it away or "
             "choose another --sensors folder";
  }
  return {};
}

// A new folder `.BASE.tmpXXXXXX` beside `final`, with the mode the
// folder it replaces has (0777 less the umask for a new one); "" after a
// message when it cannot be made.
std::string makeTemporaryFolder(const fs::path& final) {
  fs::path parent = final.parent_path();
  std::string base = final.filename().string();
  std::string pattern = (parent.empty() ? fs::path(".") : parent).string() + "/." +
                        base.substr(0, kMaxTempBaseBytes) + ".tmpXXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  if (!::mkdtemp(name.data())) {
    cli::error((parent.empty() ? std::string(".") : parent.string()) +
               ": cannot create the LiDAR's temporary scan folder: " + lowerFirst(std::strerror(errno)));
    return {};
  }
  std::string temp(name.data());
  struct stat old {};
  mode_t mode;
  if (::stat(final.c_str(), &old) == 0 && S_ISDIR(old.st_mode)) {
    mode = old.st_mode & 07777;
  } else {
    mode_t mask = ::umask(0);
    ::umask(mask);
    mode = 0777 & ~mask;
  }
  (void)::chmod(temp.c_str(), mode);
  return temp;
}

}  // namespace

SensorFiles::SensorFiles(std::string dir, const std::vector<sim::RecordedSensor>& sensors, sim::PcdEncoding encoding)
    : dir_(std::move(dir)), sensors_(sensors), encoding_(encoding) {
  for (const sim::RecordedSensor& s : sensors_) {
    fs::path out = fs::path(dir_) / s.output;
    if (!out.has_filename()) out = out.parent_path();  // outputPath "scans/": the folder scans
    bool lidar = s.spec.kind == robot::SensorKind::Lidar;
    paths_.push_back((lidar ? out / "scans.csv" : out).string());
    folders_.push_back(lidar ? ScanFolder{out.string(), {}} : ScanFolder{});
  }
  buffers_.resize(paths_.size());
  sinks_.resize(paths_.size(), nullptr);
}

bool SensorFiles::prepare(std::vector<cli::NamedOutput> outputs) {
  // A scene with nothing to record makes no folder (a batch's
  // 'sens/{stem}' would leave one empty folder per such scene).
  if (sensors_.empty()) return cli::checkOutputs(outputs);
  if (!makeFolder(dir_, created_)) return false;
  const std::size_t given = outputs.size();  // -o, --trajectory
  // Every check first, then the temporary folders: a refusal makes none.
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    const std::string& folder = folders_[i].final;
    if (folder.empty()) {  // an IMU: its file's folder
      if (!makeFolder(fs::path(paths_[i]).parent_path(), created_)) return false;
      continue;
    }
    if (!makeFolder(fs::path(folder).parent_path(), created_)) return false;
    if (std::string why = scanFolderRefusal(folder); !why.empty()) {
      cli::error(folder + ": " + why);
      return false;
    }
    // A LiDAR's folder is its own: it is replaced as a whole when the run
    // ends, so no other output may be it or inside it.
    for (std::size_t k = 0; k < given; ++k) {
      bool same = false;
      if (!within(outputs[k].path, folder, same)) continue;
      cli::error(std::string(outputs[k].flag) + " '" + outputs[k].path + "' " +
                 (same ? "names" : "is inside") + " the scan folder '" + folder + "' of LiDAR '" +
                 sensors_[i].spec.name +
                 "', which holds its scans and is replaced as a whole: give a path outside --sensors' LiDAR folders");
      return false;
    }
  }
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    if (!folders_[i].final.empty()) {
      folders_[i].temp = makeTemporaryFolder(folders_[i].final);
      if (folders_[i].temp.empty()) return false;
      paths_[i] = (fs::path(folders_[i].temp) / "scans.csv").string();
    }
    outputs.push_back({"--sensors", paths_[i]});
  }
  return cli::checkOutputs(outputs);
}

bool SensorFiles::open(std::size_t stream, const std::function<bool()>& simulate) {
  if (stream == paths_.size()) {
    bool ok = simulate() && !(stopped_ && *stopped_);
    // From here until the scan folders are in place a stop signal waits:
    // it would end the tool between two renames.
    if (ok) holdStops();
    return ok;
  }
  // Nested: each file is written inside the one before, so all of them are
  // put in place together when the simulation succeeds, none when it fails.
  return cli::writeOutput(
      paths_[stream],
      [&](Sink& sink) {
        sinks_[stream] = &sink;
        const sim::RecordedSensor& s = sensors_[stream];
        buffers_[stream] =
            s.spec.kind == robot::SensorKind::Lidar ? "index,time,points,file\n" : sim::imuHeader(s.imuFormat);
        bool ok = open(stream + 1, simulate);
        if (ok) flush(stream, true);
        sinks_[stream] = nullptr;
        return ok;
      },
      cli::Cancel::Quiet);
}

void SensorFiles::holdStops() {
  if (held_) return;
  sigset_t interrupt = cli::stopSignals();
  pthread_sigmask(SIG_BLOCK, &interrupt, &previousMask_);
  held_ = true;
}

bool SensorFiles::run(const std::function<bool()>& simulate, const volatile std::sig_atomic_t* stopped) {
  stopped_ = stopped;
  bool ok = open(0, simulate);
  if (ok) ok = commitFolders();
  if (held_) {
    held_ = false;
    pthread_sigmask(SIG_SETMASK, &previousMask_, nullptr);  // a signal that waited is handled now: the run is done
  }
  return ok;
}

// Puts each LiDAR's temporary folder at its place: a new folder is renamed
// there; an earlier run's is swapped with it in one rename (renameat2
// RENAME_EXCHANGE; where the file system cannot, renamed aside first and
// back on failure) and then removed.
bool SensorFiles::commitFolders() {
  for (ScanFolder& f : folders_) {
    if (f.temp.empty()) continue;
    struct stat st {};
    bool exists = ::lstat(f.final.c_str(), &st) == 0;
    if (exists && !S_ISDIR(st.st_mode)) {  // appeared during the run
      cli::error(f.final + ": " + scanFolderRefusal(f.final));
      return false;
    }
    std::string old;  // the earlier run's folder once it is out of the way
    int err = 0;
    if (!exists) {
      if (::rename(f.temp.c_str(), f.final.c_str()) != 0) err = errno;
    } else if (::renameat2(AT_FDCWD, f.temp.c_str(), AT_FDCWD, f.final.c_str(), RENAME_EXCHANGE) == 0) {
      old = f.temp;
    } else if (errno == EINVAL || errno == ENOSYS || errno == ENOTSUP) {
      std::string aside = f.temp + ".old";
      if (::rename(f.final.c_str(), aside.c_str()) != 0) {
        err = errno;
      } else if (::rename(f.temp.c_str(), f.final.c_str()) != 0) {
        err = errno;
        (void)::rename(aside.c_str(), f.final.c_str());
      } else {
        old = aside;
      }
    } else {
      err = errno;
    }
    if (err) {
      cli::error(f.final + ": cannot put the LiDAR's scans in place: " + lowerFirst(std::strerror(err)));
      return false;
    }
    f.temp.clear();
    if (!old.empty()) {
      std::error_code ec;
      fs::remove_all(old, ec);
      if (ec) cli::warning(old + ": cannot remove the earlier run's scans: " + lowerFirst(ec.message()));
    }
  }
  return true;
}

void SensorFiles::flush(std::size_t stream, bool all) {
  if (!sinks_[stream] || (!all && buffers_[stream].size() < kChunk)) return;
  sinks_[stream]->write(buffers_[stream]);
  buffers_[stream].clear();
}

bool SensorFiles::lidarScan(std::size_t sensor, std::uint64_t index, double time, const Pose& pose,
                            const std::vector<Eigen::Vector3f>& points) {
  char name[40];
  std::snprintf(name, sizeof name, "scan_%06llu.pcd", static_cast<unsigned long long>(index));
  fs::path file = fs::path(folders_[sensor].temp) / name;
  // A stop signal waits while a scan is written (inside writeOutput() it
  // would end the tool at once, leaving the temporary folder): the stepping
  // loop then sees the flag, stops, and discard() removes the folder.
  sigset_t interrupt = cli::stopSignals(), previous;
  pthread_sigmask(SIG_BLOCK, &interrupt, &previous);
  bool written = cli::writeOutput(file.string(), [&](Sink& s) {
    sim::writePcd(s, points, pose, time, encoding_);
    return true;
  });
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
  for (ScanFolder& f : folders_)
    if (!f.temp.empty()) {
      fs::remove_all(f.temp, ec);
      f.temp.clear();
    }
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) fs::remove(*it, ec);  // only when empty
  created_.clear();
}

bool SensorFiles::imuReading(std::size_t sensor, const sim::ImuReading& reading) {
  sim::appendImu(buffers_[sensor], sensors_[sensor].imuFormat, reading);
  flush(sensor, false);
  return true;
}

}  // namespace rscene::simcmd
