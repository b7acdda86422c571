// asset/obj_surface: OBJ vertices and faces in file order, bounded.
#include "asset/obj_surface.hpp"

#include <gtest/gtest.h>

namespace rscene::asset {
namespace {

TEST(ObjSurface, KeepsFileOrderAndFansPolygons) {
  ObjSurface s;
  std::string error;
  ASSERT_TRUE(parseObjSurface("# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1 4/1\n", s, &error)) << error;
  ASSERT_EQ(s.vertices.size(), 4u);
  EXPECT_EQ(s.vertices[2][0], 1);
  EXPECT_EQ(s.vertices[2][1], 1);
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(s.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
}

TEST(ObjSurface, NegativeIndicesCountBackFromTheLastVertex) {
  ObjSurface s;
  std::string error;
  ASSERT_TRUE(parseObjSurface("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n", s, &error)) << error;
  EXPECT_EQ(s.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
}

TEST(ObjSurface, RefusesWhatIsNotASurface) {
  ObjSurface s;
  std::string error;
  EXPECT_FALSE(parseObjSurface("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", s, &error));
  EXPECT_EQ(error, "line 4: face index 4 is not one of the 3 vertices before it");
  EXPECT_FALSE(parseObjSurface("v 0 0 nan\n", s, &error));
  EXPECT_EQ(error, "line 1: a vertex needs three finite numbers");
  EXPECT_FALSE(parseObjSurface("v 0 0 0\n", s, &error));
  EXPECT_NE(error.find("no triangles"), std::string::npos);
  ObjLimits small;
  small.maxVertices = 2;
  EXPECT_FALSE(parseObjSurface("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", s, &error, small));
  EXPECT_EQ(error, "line 3: more than 2 vertices");
}

TEST(ObjSurface, ReadsThroughTheFileSystemAndRefusesBinary) {
  MemoryFileSystem fs;
  fs.addFile("cloth.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  fs.addFile("cloth.glb", std::string("glTF\0\0\0", 7));
  ObjSurface s;
  std::string error;
  EXPECT_TRUE(loadObjSurface(fs, "cloth.obj", s, &error)) << error;
  EXPECT_FALSE(loadObjSurface(fs, "cloth.glb", s, &error));
  EXPECT_FALSE(loadObjSurface(fs, "missing.obj", s, &error));
}

}  // namespace
}  // namespace rscene::asset
