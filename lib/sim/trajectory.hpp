// Trajectory lines: body and robot states as JSON Lines or CSV
// (rscene-sim --trajectory).
//
// A body's line: time, path, position, quaternion (w x y z), linear and
// angular velocity, world frame.  An articulated system's line has the
// same fields for its base (the root link's frame, its origin's velocity),
// then its joints by name (robot::coordinateNames): in JSON Lines
// "jointPositions" and "jointVelocities" objects; in CSV one column
// "q.NAME" per coordinate and "u.NAME" per velocity entry, after the body
// columns, for the joints of every robot (a joint name shared by two
// robots is one column); a row leaves the columns not its own empty.
//
// A deformable's or granular record's line: time, path and its particles'
// world positions (a deformable's OBJ vertices first, in file order): in
// JSON Lines "points":[[x,y,z],...]; in CSV the last column, "points",
// holds "x y z;x y z;..." and the pose and joint columns stay empty.
#pragma once
#include <string>
#include <vector>

#include "sim/world.hpp"

namespace rscene::sim {

enum class TrajectoryFormat { Jsonl, Csv };

class Trajectory {
 public:
  // `robots`: the states of the robots the lines will carry (World::robotStates()).
  Trajectory(TrajectoryFormat format, const std::vector<RobotState>& robots);
  // The CSV header line (with newline); JSON Lines has none.
  std::string header() const;
  // One line per body, then one per robot, at simulated time `time`;
  // numbers shortest round-trip.
  void append(std::string& out, double time, const std::vector<BodyState>& bodies,
              const std::vector<RobotState>& robots, const std::vector<ParticleState>& particles = {}) const;

 private:
  TrajectoryFormat format_;
  std::vector<std::string> columns_;  // joint columns (CSV)
  // Per robot: the column of each q entry past the base, then of each u entry.
  std::vector<std::vector<int>> qColumns_, uColumns_;
};

}  // namespace rscene::sim
