// Grain beds on each kind of surface (surfaces_bed.hpp): 20,000 grains of
// radius 1 cm, each overlapping the surface by 1 mm, find exactly one
// contact each, on the ground plane, a static box, a convex hull and a
// static mesh of 8,192 triangles.  What a query costs is measured by
// bench/sim/surfaces.cpp on the same beds, not here.
#include <gtest/gtest.h>

#include "surfaces_bed.hpp"

using namespace rscene::sim;

TEST(SurfacesBed, EveryGrainFindsItsOneContactOnEachSurface) {
  const std::string grid = test::writeGridMesh(std::filesystem::path(testing::TempDir()) / "surfaces_bed");
  for (const test::SurfaceCase& c :
       test::surfaceCases(std::string(RSCENE_TEST_DATA) + "/render_assets/crate.obj", grid)) {
    test::Bed bed = test::makeBed(c.body);
    ASSERT_TRUE(bed.error.empty()) << c.what << ": " << bed.error;
    std::vector<SurfaceContact> out;
    test::queryAll(bed, out);
    EXPECT_EQ(out.size(), bed.grains.size()) << c.what;
  }
}
