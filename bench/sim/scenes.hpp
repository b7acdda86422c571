// Benchmark scenes of rscene-sim, as plain data (no rscene, no Bullet):
// rscene-sim-bench-gen writes them as .rscene text and rscene-sim-baseline
// builds the same bodies by hand, so the two programs simulate the same
// world.  Header-only, C++ standard library only.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "../rng.hpp"

namespace rscene::bench {

// One box body.  Orientation (w, x, y, z) is exactly unit length (its
// components are 0, +-1 or +-0.5), so the scene reader's normalisation
// leaves it bit for bit as the baseline sees it.
struct Box {
  std::string path;
  double position[3];
  double orientation[4];
  double size[3];  // full side lengths (the object record's scale)
  double mass;
  bool dynamic;
};

// Multiples of 1/1024 in [lo, hi): short decimals, exact in binary, so
// reading the scene back changes nothing.
inline double shortUniform(Rng& rng, double lo, double hi) {
  return lo + std::floor((hi - lo) * 1024 * rng.unit()) / 1024;
}

// The 12 of a cube's 24 rotations whose quaternion components are 0, +-1
// or +-0.5: the identity, three half turns about the axes and eight third
// turns about the diagonals.
inline void cubeRotation(std::uint64_t k, double q[4]) {
  static const double kRot[12][4] = {
      {1, 0, 0, 0},          {0, 1, 0, 0},          {0, 0, 1, 0},           {0, 0, 0, 1},
      {0.5, 0.5, 0.5, 0.5},  {0.5, -0.5, -0.5, -0.5}, {0.5, 0.5, -0.5, 0.5}, {0.5, -0.5, 0.5, -0.5},
      {0.5, 0.5, 0.5, -0.5}, {0.5, -0.5, -0.5, 0.5}, {0.5, -0.5, 0.5, 0.5},  {0.5, 0.5, -0.5, -0.5}};
  for (int i = 0; i < 4; ++i) q[i] = kRot[k % 12][i];
}

// Scene (a): `count` boxes of mixed sizes (0.2 to 0.4 m sides) dropped in
// layers of 10 x 10 on a 0.5 m grid, every other layer shifted by a quarter
// of the grid so that boxes land on the corners of the ones below, tumble
// and pile up on the ground plane (z = 0).  No two boxes overlap at start.
inline std::vector<Box> pile(int count, std::uint64_t seed = 1) {
  std::vector<Box> out;
  Rng rng(seed);
  for (int i = 0; i < count; ++i) {
    int layer = i / 100, cell = i % 100;
    double shift = (layer % 2) * 0.125;
    Box b;
    b.path = "/World/Pile/Box_" + std::to_string(i);
    b.size[0] = shortUniform(rng, 0.2, 0.4);
    b.size[1] = shortUniform(rng, 0.2, 0.4);
    b.size[2] = shortUniform(rng, 0.2, 0.4);
    b.position[0] = (cell % 10 - 4.5) * 0.5 + shift + shortUniform(rng, -0.04, 0.04);
    b.position[1] = (cell / 10 - 4.5) * 0.5 + shift + shortUniform(rng, -0.04, 0.04);
    b.position[2] = 0.5 + layer * 0.6;
    cubeRotation(rng.below(12), b.orientation);
    b.mass = shortUniform(rng, 0.5, 3);
    b.dynamic = true;
    out.push_back(b);
  }
  return out;
}

// Scene (b)'s crates: `count` 0.4 m crates in a grid of 1 m pitch centred
// on (cx, cy), dropped from z0 up in layers of 25.
inline std::vector<Box> crates(int count, double cx, double cy, double z0, std::uint64_t seed = 2) {
  std::vector<Box> out;
  Rng rng(seed);
  for (int i = 0; i < count; ++i) {
    int layer = i / 25, cell = i % 25;
    Box b;
    b.path = "/World/Crates/Crate_" + std::to_string(i);
    b.size[0] = b.size[1] = b.size[2] = 0.4;
    b.position[0] = cx + (cell % 5 - 2) * 1.0 + shortUniform(rng, -0.2, 0.2);
    b.position[1] = cy + (cell / 5 - 2) * 1.0 + shortUniform(rng, -0.2, 0.2);
    b.position[2] = z0 + layer * 0.8;
    cubeRotation(rng.below(12), b.orientation);
    b.mass = 5;
    b.dynamic = true;
    out.push_back(b);
  }
  return out;
}

// The object record of a box (25 positional fields, see compat-notes.md).
inline std::string objectLine(const Box& b) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "object %s box %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g 0.5 1 %.17g default "
                "engine_default false true false - %s true 1 18446744073709551615\n",
                b.path.c_str(), b.position[0], b.position[1], b.position[2], b.orientation[0], b.orientation[1],
                b.orientation[2], b.orientation[3], b.size[0], b.size[1], b.size[2], b.mass,
                b.dynamic ? "dynamic" : "static");
  return buf;
}

}  // namespace rscene::bench
