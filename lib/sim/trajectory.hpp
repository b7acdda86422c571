// Trajectory lines: body states as JSON Lines or CSV (rscene-sim --trajectory).
#pragma once
#include <string>
#include <vector>

#include "sim/world.hpp"

namespace rscene::sim {

enum class TrajectoryFormat { Jsonl, Csv };

// The CSV header line (with newline); JSON Lines has none.
std::string trajectoryHeader(TrajectoryFormat format);
// One line per body at simulated time `time`, numbers shortest round-trip.
void appendTrajectory(std::string& out, TrajectoryFormat format, double time, const std::vector<BodyState>& states);

}  // namespace rscene::sim
