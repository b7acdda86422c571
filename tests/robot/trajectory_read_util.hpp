// Reading a whole trajectory text into frames, for the reader's tests
// (trajectory_read_test.cpp, trajectory_read_points_test.cpp).
#pragma once
#include <sstream>
#include <string>
#include <vector>

#include "robot/trajectory_read.hpp"

namespace rscene::robot::test {

struct Read {
  std::vector<TrajectoryFrame> frames;
  Diagnostics diags;
  bool failed = false;
};

inline Read readAll(const std::string& text, TrajectoryLimits limits = {}) {
  std::istringstream in(text);
  TrajectoryReader r(in, "t.jsonl", limits);
  Read out;
  TrajectoryFrame f;
  while (r.next(f, out.diags)) out.frames.push_back(f);
  out.failed = r.failed();
  return out;
}

}  // namespace rscene::robot::test
