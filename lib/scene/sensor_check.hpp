// What a sensor must satisfy before a tool renders or simulates it: the
// bounds of its numbers, shared by the scene's sensor records (checked by
// checkScene(), so validate, sim and render refuse the same record with
// the same code at the same field) and by the sensor sets of robot files
// (lib/robot/sensor_set.cpp reads them with the same bounds and codes).
//
//   RS2007  warning: sensor kind the schema does not know (lib/core's code:
//           validate reports it from its own check, sim and render from
//           this one; the sensor is neither rendered nor simulated)
//   RS3012  parentObject names no node (lib/core's code and words:
//           validate reports it from its own check, sim and render from
//           this one)
//   RS4012  nearPlane <= 0 or farPlane <= nearPlane (lib/core's code and
//           words: validate's core check says it of every sensor record)
//   RS7063  parentObject names a node that is no body (a camera, a group,
//           a light ...): the sensor would sit at the world origin
//   RS7064  camera-like image size outside 1..16384, a field of view
//           outside (0, 180) degrees; farPlane beyond 1e12 m
//   RS7065  calibration given in part, or fx, fy not positive
//   RS7066  LiDAR channels or samples below 1 or more than kMaxLidarRays
//           rays per scan, ranges not 0 <= min < max <= 1e12, vertical
//           field of view outside 0..180 degrees
//   RS7067  updateRate outside 0..1e6 Hz, noise stddev negative, noise
//           or IMU limit beyond 1e12 or negative
//   RS7068  warning: parentLink on a sensor whose parentObject is not an
//           articulated system (the link is not used)
//   RS7069  outputPath (sensor or camera) absolute or with a '..' part
//   RS7070  two enabled sensor records with one outputPath (rscene-sim's
//           code for two streams at one path)
//   RS7072  warning: lidarVerticalFov 0 with more than one channel (every
//           ring scans the same plane)
//   RS7073  warning: segmentation=true on a kind that draws no image (the
//           flag is not used)
//   RS7074  camera orthoScale not finite and > 0 under an orthographic
//           projection (a degenerate image)
//
// A value that did not parse is an RS2xxx error of its own; no bound is
// judged on the default that replaced it.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/codes.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "scene/scene.hpp"

namespace rscene {

namespace sensor_code {
inline constexpr const char* kUnknownKind = rs::RS2007;  // lib/core's open-enumeration warning
inline constexpr const char* kClip = rs::RS4012;         // lib/core's near/far check
inline constexpr const char* kNotABody = rs::RS7063;
inline constexpr const char* kImage = rs::RS7064;
inline constexpr const char* kCalibration = rs::RS7065;
inline constexpr const char* kLidar = rs::RS7066;
inline constexpr const char* kRate = rs::RS7067;
inline constexpr const char* kLinkWithoutRobot = rs::RS7068;
inline constexpr const char* kOutputPath = rs::RS7069;
inline constexpr const char* kSameOutput = rs::RS7070;
inline constexpr const char* kFlatLidar = rs::RS7072;
inline constexpr const char* kSegmentationUnused = rs::RS7073;
inline constexpr const char* kOrthoScale = rs::RS7074;
}  // namespace sensor_code

// Most rays one LiDAR scan casts (2^22).  The largest spinning LiDARs sold
// scan 128 x 2048 = 262,144 rays; sixteen times that still keeps one
// scan's point cloud near 64 MiB (16 bytes a point) and its ray casts
// around a second, where a slip of the keyboard (lidarSamples=1000000000)
// would ask for 16 GB a scan.
inline constexpr std::int64_t kMaxLidarRays = std::int64_t{1} << 22;
// Highest updateRate: a microsecond between readings is far past any
// sensor sold, and a step of the simulation cannot be shorter than 1e-9 s.
inline constexpr double kMaxUpdateRate = 1e6;

// The numbers of a sensor as written, before the scene model clamps them
// (an image side of 99999 arrives in SensorParams as 0).
struct SensorValues {
  std::string kind;  // canonical sensor_kind
  std::int64_t width = 0, height = 0, lidarChannels = 0, lidarSamples = 0;
  double lidarVerticalFov = 0;             // degrees: the pitch span
  std::array<bool, 4> calibrationGiven{};  // fx, fy, cx, cy written
  SensorParams params;                     // the other numbers
};

// One bound a sensor's numbers break: `field` is the sensor record's field
// (a sensor-set reader maps it to its element), `message` lower-case, no
// final period.
struct SensorProblem {
  const char* code;
  const char* field;
  std::string message;
};

// The bounds above that the kind uses (images for camera-like kinds, LiDAR
// numbers for lidar, IMU limits for imu; rates and noise for all).
std::vector<SensorProblem> sensorProblems(const SensorValues& values);

bool isCameraLikeSensor(const std::string& canonicalKind);  // rgb, depth, segmentation, rgb_depth
// True when the schema's sensor_kind enumeration names `canonicalKind`.
bool isKnownSensorKind(const std::string& canonicalKind);

// Why tools refuse to write to `outputPath` (absolute, or a '..' part that
// climbs out of the output directory), or empty when they may.  "" and "-"
// are no output.
std::string outputPathProblem(const std::string& outputPath);
// Why an image file name does not suit: rscene-render writes PNG only, so
// its extension must be .png (any case) or absent ("" when it suits).  A
// .jpg holding PNG bytes would mislead every viewer; a .npy or .json one
// would also clash with the depth and segmentation files written beside
// the image.  A leading dot ("out/.hidden") is no extension.  A camera's
// outputPath must also name a file, not a folder (no final '/').
std::string imageExtensionProblem(const std::string& file);

// ---- What rscene-sim --sensors writes, one rule for sim and validate ----
//
// A recorded sensor (lidar, imu) writes under the --sensors folder: an IMU
// one file, a LiDAR one folder (scans.csv and scan_NNNNNN.pcd inside).
// Its place is its outputPath, normalised (empty and '.' parts dropped), or
// sensorFileName(its path), plus .csv or .jsonl for an IMU.

// A sensor path made one safe file name: the leading '/' dropped, every
// other '/' written '+', bytes other than ASCII letters, digits, '.', '_'
// and '-' written %XX (upper-case hex), a '.' that starts a component
// written %2E.  One-to-one:  /World/Robot/Imu -> World+Robot+Imu.
std::string sensorFileName(const std::string& sensorPath);

// `outputPath` with empty and '.' parts dropped ("./a//b/" -> "a/b").
std::string normalizedSensorOutput(const std::string& outputPath);

// Why a recorded sensor cannot write to `outputPath` beyond
// outputPathProblem() (lower-case, no final period), or empty: it names
// the --sensors folder itself ('.', './'), or, for an IMU (`folder`
// false), it ends in '/' although an IMU writes a file.
std::string sensorOutputProblem(const std::string& outputPath, bool folder);

// Where a recorded sensor writes, relative to the --sensors folder:
// the normalised outputPath when one is set, else sensorFileName(name)
// plus `imuExtension` (".csv", ".jsonl") for an IMU (`folder` false).
std::string sensorOutput(const std::string& name, const std::string& outputPath, bool folder,
                         const std::string& imuExtension);

// The places recorded sensors write, to find two that collide: the same
// place, or one inside the other (an IMU at x/scans.csv in the LiDAR
// folder x, a LiDAR x/y below the IMU file x).
class SensorOutputs {
 public:
  // The owner (as given to add()) and place of an earlier output that
  // `place` collides with, or nullptr.
  const std::pair<const std::string, std::string>* clash(const std::string& place) const;
  void add(const std::string& place, const std::string& owner) { places_.emplace(place, owner); }

 private:
  std::map<std::string, std::string> places_;  // place -> owner
};

// "sensors 'A' and 'B' would both write 'P'" or "... 'B' would write 'P',
// inside 'Q' of 'A'" (and the other way round): the one wording of RS7070
// for a clash() found.  `self` and `other` are already quoted names.
std::string sensorClashMessage(const std::string& self, const std::string& place, const std::string& other,
                               const std::string& otherPlace);

// Appends the findings above about every sensor record of `scene` and the
// outputPath of every camera record, each at the record's field.  Reads
// the document, not the scene's resolved mounts: validate's scene is built
// bodiesOnly.
void checkSensors(const Document& doc, const Scene& scene, Diagnostics& diagnostics);

}  // namespace rscene
