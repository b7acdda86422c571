// rscene-sim-bench-gen: writes the rscene-sim benchmark scenes
// (bench/sim/scenes.hpp) to stdout.
//
//   rscene-sim-bench-gen pile [--count N] [--seed S]
//       scene (a): a whole scene, a ground plane and N falling boxes
//   rscene-sim-bench-gen crates [--count N] [--at X Y Z] [--seed S]
//       scene (b)'s crates: only the object records, appended by
//       bench/sim/run.sh to the warehouse's collision boxes
//
// Exit status: 0, or 2 on a usage error.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "scenes.hpp"

namespace {

int usage(const char* why) {
  std::fprintf(stderr,
               "rscene-sim-bench-gen: error: %s\n"
               "usage: rscene-sim-bench-gen pile [--count N] [--seed S]\n"
               "       rscene-sim-bench-gen crates [--count N] [--at X Y Z] [--seed S]\n",
               why);
  return 2;
}

bool number(const char* s, double& out) {
  char* end = nullptr;
  out = std::strtod(s, &end);
  return end != s && *end == '\0';
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage("missing scene name");
  std::string what = argv[1];
  if (what != "pile" && what != "crates") return usage(("unknown scene '" + what + "'").c_str());
  double count = what == "pile" ? 1000 : 100, seed = what == "pile" ? 1 : 2;
  double at[3] = {0, 0, 5};
  for (int i = 2; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--count" && i + 1 < argc) {
      if (!number(argv[++i], count) || count < 0 || count > 1e6) return usage("--count needs a number in [0, 1e6]");
    } else if (a == "--seed" && i + 1 < argc) {
      if (!number(argv[++i], seed) || seed < 0) return usage("--seed needs a non-negative number");
    } else if (a == "--at" && what == "crates" && i + 3 < argc) {
      for (double& v : at)
        if (!number(argv[++i], v)) return usage("--at needs three numbers");
    } else {
      return usage(("unknown or incomplete option '" + a + "'").c_str());
    }
  }
  std::string out;
  if (what == "pile") {
    out = "raisim_engine_scene 2\n# rscene-sim benchmark (a): boxes falling into a pile (bench/sim/scenes.hpp)\n"
          "object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 0.5 1 1 default engine_default false true false - "
          "static true 1 18446744073709551615\n";
    for (const rscene::bench::Box& b : rscene::bench::pile(static_cast<int>(count), static_cast<std::uint64_t>(seed)))
      out += rscene::bench::objectLine(b);
  } else {
    for (const rscene::bench::Box& b :
         rscene::bench::crates(static_cast<int>(count), at[0], at[1], at[2], static_cast<std::uint64_t>(seed)))
      out += rscene::bench::objectLine(b);
  }
  if (std::fwrite(out.data(), 1, out.size(), stdout) != out.size() || std::fflush(stdout) != 0) {
    std::fprintf(stderr, "rscene-sim-bench-gen: error: cannot write to standard output\n");
    return 2;
  }
  return 0;
}
