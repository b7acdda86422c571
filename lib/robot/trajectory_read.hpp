// Reading back what `rscene-sim --trajectory` writes (robot/trajectory_format.hpp:
// JSON Lines or CSV, told apart by the first line), one frame at a time,
// so that rscene-render --trajectory can pose a scene along a simulation.
//
// Lines with the same time form a frame.  The reader holds one frame and
// one line at a time (memory bounded by TrajectoryLimits, whatever the
// file's length), never throws for bad input and reports the first
// malformed line as `file:line:col: error: ... [RS9046]`.  Times must not
// decrease (a second trajectory appended to the first is refused).
#pragma once
#include <cstdint>
#include <istream>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/codes.hpp"
#include "core/diagnostic.hpp"
#include "robot/kinematics.hpp"
#include "robot/model.hpp"
#include "robot/sensors.hpp"
#include "robot/trajectory_format.hpp"
#include "scene/scene.hpp"

namespace rscene::robot {

namespace code {
inline constexpr const char* kTrajectorySyntax = rs::RS9046;  // malformed trajectory line
inline constexpr const char* kTrajectoryTarget = rs::RS9047;  // body or joint the scene does not have
}  // namespace code

// One line: a body's pose, or a robot's base pose and joint positions, or
// a deformable's or granular record's particle positions.
struct TrajectoryEntry {
  struct Joint {
    std::string name;  // coordinate name (robot::coordinateNames): a joint, or NAME_qw.. of a spherical one
    double value = 0;
    std::uint32_t column = 0;
  };
  std::string path;
  Pose pose;  // world; the quaternion normalised
  std::vector<Joint> joints;
  std::uint32_t line = 0, pathColumn = 0;
  // A particle line (JSON "points", CSV points column with the pose cells
  // empty): world positions, a deformable's OBJ vertices in file order or
  // a granular record's particles; `pose` and `joints` are then unused.
  bool particles = false;
  std::vector<Eigen::Vector3d> points;
  std::uint32_t pointsColumn = 0;
};

struct TrajectoryFrame {
  double time = 0;
  std::uint64_t index = 0;  // 0 for the file's first frame
  std::vector<TrajectoryEntry> entries;
};

enum class TrajectoryFileFormat { Unknown, Jsonl, Csv };

class TrajectoryReader {
 public:
  // `file` names the input in messages.  `in` must outlive the reader.
  TrajectoryReader(std::istream& in, std::string file, TrajectoryLimits limits = {});
  ~TrajectoryReader();
  // The next frame; false at the end of the input, or on the first error
  // (added to `diagnostics`; failed() then says so).  A file with no line
  // at all is an error too: nothing to render is never silent.
  bool next(TrajectoryFrame& frame, Diagnostics& diagnostics);
  bool failed() const { return failed_; }
  TrajectoryFileFormat format() const { return format_; }

 private:
  bool readLine(std::string& out, Diagnostics& d);
  bool parseLine(const std::string& text, double& time, TrajectoryEntry& entry, Diagnostics& d);
  bool parseJson(const std::string& text, double& time, TrajectoryEntry& entry, Diagnostics& d);
  bool parseCsvHeader(const std::string& text, Diagnostics& d);
  bool parseCsv(const std::string& text, double& time, TrajectoryEntry& entry, Diagnostics& d);
  bool parseCsvPoints(const std::string& cell, std::uint32_t column, std::vector<Eigen::Vector3d>& out,
                      Diagnostics& d);
  bool fail(Diagnostics& d, std::uint32_t column, std::string message);

  bool csvPoints_ = false;  // the CSV header ends with a points column
  std::istream& in_;
  std::string file_;
  TrajectoryLimits limits_;
  TrajectoryFileFormat format_ = TrajectoryFileFormat::Unknown;
  std::vector<std::string> csvJoints_;  // per CSV column past the body ones: joint name, "" when not q.*
  std::uint32_t lineNumber_ = 0;
  std::uint32_t continuedLines_ = 0;  // lines past the first of the last CSV record (a quoted newline)
  std::uint64_t frames_ = 0;
  bool failed_ = false, ended_ = false;
  bool havePending_ = false;  // a line of the next frame, read ahead
  double pendingTime_ = 0;
  TrajectoryEntry pending_;
  double lastTime_ = 0;
};

// How many particles each deformable (its OBJ's vertices) and granular
// record has, indexed like Scene::deformables and Scene::granulars; -1 (or
// a record past the list): unknown, any count is taken.  A deformable's
// line gives its OBJ's vertices first, then any particles filling its
// volume (fem): its count is a minimum; a granular record's is exact.
struct ParticleCounts {
  std::vector<std::int64_t> deformables, granulars;
};

// The particle positions frames gave so far (world), indexed like
// Scene::deformables and Scene::granulars; `given` false: no frame named
// the record yet (it stays at rest).  `version` counts the frames that
// moved it, so a renderer re-uploads only what changed.
struct ParticlePositions {
  struct Record {
    bool given = false;
    std::uint64_t version = 0;
    std::vector<Eigen::Vector3d> points;
  };
  std::vector<Record> deformables, granulars;
};

// Turns frames into the scene's body poses: bodies by path (objects and
// compounds), robots by the path of their articulated record, their joints
// by name through forward kinematics (robot::linkPoses); and deformable and
// granular records' particle lines into ParticlePositions.
class TrajectoryPoser {
 public:
  // `models` indexed like Scene::articulated (null: not loaded; its lines
  // then move nothing).  `counts`: what a particle line must give.
  TrajectoryPoser(const Scene& scene, const std::vector<std::shared_ptr<const Model>>& models,
                  ParticleCounts counts = {});
  // Moves the bodies the frame names in `poses` (start from restPoses();
  // what a frame leaves out stays where it was) and, when `particles` is
  // given, the particle records it names.  A path that is no body, robot,
  // deformable or granular record of the scene, a joint its robot does not
  // have, a movable joint of the robot that the line leaves out (rscene-sim
  // writes every one), points for a body or a pose for a particle record,
  // or a point count other than the record's (fewer than a deformable's)
  // is an error naming it (RS9047 at the line in `file`), and false.
  bool apply(const TrajectoryFrame& frame, const std::string& file, BodyPoses& poses, Diagnostics& diagnostics,
             ParticlePositions* particles = nullptr) const;

 private:
  enum class Particles { None, Deformable, Granular };
  struct Target {
    Mount::Kind kind = Mount::Kind::World;
    int index = -1;
    Particles particles = Particles::None;  // a deformable's or granular record's path (index into its list)
  };
  struct Robot {
    std::shared_ptr<const Model> model;
    Coordinates coordinates;
    std::unordered_map<std::string, int> coordinate;  // q entry by name (joints only)
    std::vector<std::string> names;                   // those names in q order, from baseCoordinates
  };
  void addTargets(const Scene& scene, const std::vector<std::shared_ptr<const Model>>& models);
  std::unordered_map<std::string, Target> targets_;
  std::vector<Robot> robots_;
  ParticleCounts counts_;
  std::size_t deformables_ = 0, granulars_ = 0;
};

}  // namespace rscene::robot
