// The trajectory file format, in one place: what rscene-sim --trajectory
// writes (TrajectoryWriter) and rscene-render --trajectory reads back
// (robot/trajectory_read.hpp) share its column table, JSON keys, CSV
// quoting rule and limits from here.
//
// Lines: a body's line holds time, path, position, quaternion (w x y z),
// linear and angular velocity, world frame.  An articulated system's line
// has the same fields for its base (the root link's frame, its origin's
// velocity), then its joints by name (robot::coordinateNames): in JSON
// Lines "jointPositions" and "jointVelocities" objects; in CSV one column
// "q.NAME" per coordinate and "u.NAME" per velocity entry, after the body
// columns, for the joints of every robot (a joint name shared by two
// robots is one column); a row leaves the columns not its own empty.
//
// A deformable's or granular record's line: time, path and its particles'
// world positions (a deformable's OBJ vertices first, in file order): in
// JSON Lines "points":[[x,y,z],...]; in CSV the last column, "points",
// holds "x y z;x y z;..." and the pose and joint columns stay empty.
// Numbers are shortest round-trip; lines with one time form a frame.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "robot/instance.hpp"
#include "scene/limits.hpp"
#include "scene/pose.hpp"

namespace rscene::robot {

enum class TrajectoryFormat { Jsonl, Csv };

// The CSV columns of every line, in order; joint columns and "points"
// follow them.
inline constexpr std::array<std::string_view, 15> kTrajectoryBodyColumns = {
    "time", "path", "px", "py", "pz", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz"};
inline constexpr std::string_view kTrajectoryPointsColumn = "points";  // CSV: last; JSON: the key
inline constexpr std::string_view kJointPositionPrefix = "q.";         // CSV joint columns
inline constexpr std::string_view kJointVelocityPrefix = "u.";

// A coordinate, velocity or point beyond this is not a simulation's: the
// scene's own bound on lengths (scene/limits.hpp), which rscene-sim keeps
// bodies within; a reader refuses it (it would only overflow a renderer's
// matrices).
inline constexpr double kMaxTrajectoryValue = kMaxLength;

// What a reader holds at most (memory bounded whatever the file's length).
struct TrajectoryLimits {
  // rscene-sim writes a particle at most kBytesPerPoint bytes wide (three
  // shortest round-trip numbers of up to 24 characters, brackets, commas).
  static constexpr std::size_t kBytesPerPoint = 80;
  // A longer line is an error.  What rscene-sim writes for a robot of 1000
  // joints is about 60 KB, for a granular bed of 20,000 particles about
  // 1.2 MB (1.6 MB at the widest numbers); 64 MiB holds 800,000 particles
  // at the widest.  forPoints() fits it to a scene instead.
  std::size_t maxLineBytes = std::size_t{64} << 20;
  // Lines of one frame: rscene-sim writes one per body and robot.
  std::size_t maxEntriesPerFrame = std::size_t{1} << 18;
  // Points on one line (a line with more is an error before they are all
  // held: 24 bytes each).
  std::size_t maxPoints = 1'000'000;

  // Limits for a scene whose largest deformable or granular record has
  // `points` particles: lines of 1 MiB plus kBytesPerPoint per point, at
  // most `points` points (a 20,000-grain bed: 2.6 MB lines).
  static TrajectoryLimits forPoints(std::size_t points);
};

// The CSV quoting rule (RFC 4180): a field holding a comma, a quote or a
// newline goes in double quotes, a quote inside doubled.
void appendCsvField(std::string& out, std::string_view field);

// A path as a JSON line holds it: JSON text is UTF-8, so a byte that is
// not part of a valid UTF-8 sequence (a path written %FF) becomes U+FFFD.
// The reader matches a scene's paths in this form too.
std::string jsonSafeText(std::string_view text);

// One CSV field as read back: its decoded text and its 1-based column.
struct CsvField {
  std::string text;
  std::uint32_t column = 0;
};
// Splits a line quoted by appendCsvField's rule.  False on an unclosed
// quote or text after a closing quote; `bad` is then the column.
bool splitCsv(const std::string& line, std::vector<CsvField>& out, std::uint32_t& bad);

// State of one simulated body (dynamic or kinematic), in the world frame:
// what a body's line carries.
struct BodyState {
  int recordIndex = -1;  // object or compound record
  std::string path;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d linearVelocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();
  bool dynamic = true;
  bool sleeping = false;
  bool departed = false;  // left the world (sim::Departure): frozen at its last pose
};

// State of one articulated system, RaiSim's layout (robot/kinematics.hpp).
struct RobotState {
  int recordIndex = -1;
  std::string path;
  const RobotInstance* instance = nullptr;  // model, coordinate layout and names
  Eigen::VectorXd q, u;                     // generalized coordinate and velocity
  Pose base;                                // the root link's frame, world
  Eigen::Vector3d baseLinearVelocity = Eigen::Vector3d::Zero();   // of that frame's origin, world
  Eigen::Vector3d baseAngularVelocity = Eigen::Vector3d::Zero();  // world
  // Per body (RaiSim's body index: 0 the root, then one per movable joint
  // in RaiSim's joint order; fixed links merged): the body frame's world
  // pose, and its centre of mass's world velocity and angular velocity.
  std::vector<Pose> bodyPoses;
  std::vector<Eigen::Vector3d> bodyLinearVelocities, bodyAngularVelocities;
};

// The particles of one record now.
struct ParticleState {
  int recordIndex = -1;
  std::string path;
  bool granular = false;                                 // else deformable
  const std::vector<Eigen::Vector3d>* points = nullptr;  // world; valid until the next step
};

class TrajectoryWriter {
 public:
  // `robots`: the states of the robots the lines will carry (their
  // instances give the joint columns).
  TrajectoryWriter(TrajectoryFormat format, const std::vector<RobotState>& robots);
  // The CSV header line (with newline); JSON Lines has none.
  std::string header() const;
  // One line per body, then one per robot, then one per particle record,
  // at simulated time `time`.
  void append(std::string& out, double time, const std::vector<BodyState>& bodies,
              const std::vector<RobotState>& robots, const std::vector<ParticleState>& particles = {}) const;

 private:
  TrajectoryFormat format_;
  std::vector<std::string> columns_;  // joint columns (CSV)
  // Per robot: the column of each q entry past the base, then of each u entry.
  std::vector<std::vector<int>> qColumns_, uColumns_;
};

}  // namespace rscene::robot
