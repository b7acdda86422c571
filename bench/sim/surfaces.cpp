// rscene-surfaces-bench: what one particle's contact query with the rigid
// world costs (BulletSurfaces::contacts), on tests/sim/surfaces_bed_test's
// beds (surfaces_bed.hpp): 20,000 grains on the ground plane, a static
// box, a convex hull and an 8,192-triangle static mesh.  Prints ns per
// query, the best of BENCH_REPEAT passes (default 10: other processes on
// the machine only add); figures, never a verdict.  Exit 1 when a bed
// cannot be built or a pass does not find one contact per grain.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <unistd.h>

#include "surfaces_bed.hpp"

using namespace rscene::sim;

int main() {
  const char* env = std::getenv("BENCH_REPEAT");
  const int repeat = env ? std::max(1, std::atoi(env)) : 10;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("rscene-bench-surfaces-" + std::to_string(::getpid()));
  const std::string grid = test::writeGridMesh(dir);
  int status = 0;
  for (const test::SurfaceCase& c :
       test::surfaceCases(std::string(RSCENE_TEST_DATA) + "/render_assets/crate.obj", grid)) {
    test::Bed bed = test::makeBed(c.body);
    if (!bed.error.empty()) {
      std::fprintf(stderr, "surfaces bench: %s: %s\n", c.what.c_str(), bed.error.c_str());
      status = 1;
      continue;
    }
    std::vector<SurfaceContact> out;
    out.reserve(bed.grains.size());
    double best = 1e300;
    for (int k = 0; k < repeat; ++k) {
      out.clear();
      auto start = std::chrono::steady_clock::now();
      test::queryAll(bed, out);
      best = std::min(best, std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count());
    }
    if (out.size() != bed.grains.size()) {
      std::fprintf(stderr, "surfaces bench: %s: %zu contacts for %zu grains\n", c.what.c_str(), out.size(),
                   bed.grains.size());
      status = 1;
    }
    std::printf("contacts() on %-36s %7.1f ns per query (20,000 grains, best of %d passes)\n", c.what.c_str(),
                best / static_cast<double>(bed.grains.size()), repeat);
  }
  std::filesystem::remove_all(dir);
  return status;
}
