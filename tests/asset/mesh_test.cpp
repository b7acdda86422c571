// Mesh files through assimp, read from an in-memory disk (and the real one
// for the fixtures render uses), and the cache both tools share.
#include <gtest/gtest.h>

#include "asset/cache.hpp"
#include "asset/mesh.hpp"
#include "test_images.hpp"

using namespace rscene;
using namespace rscene::asset;

namespace {

// A unit quad (two triangles) with a material; `texture` names its map_Kd.
MemoryFileSystem quadFiles(const std::string& texture = "") {
  MemoryFileSystem fs;
  fs.addFile("/m/quad.obj",
             "mtllib quad.mtl\n"
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
             "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
             "usemtl green\n"
             "f 1/1 2/2 3/3 4/4\n");
  fs.addFile("/m/quad.mtl", "newmtl green\nKd 0.1 0.8 0.2\n" + (texture.empty() ? "" : "map_Kd " + texture + "\n"));
  return fs;
}

std::string data(const std::string& name) { return std::string(RSCENE_TEST_DATA) + "/render_assets/" + name; }

}  // namespace

TEST(Mesh, ObjWithMtlFromMemory) {
  MemoryFileSystem fs = quadFiles();
  Mesh m;
  std::string err;
  ASSERT_TRUE(loadMesh(fs, "/m/quad.obj", MeshContent::Surface, m, &err)) << err;
  ASSERT_EQ(m.parts.size(), 1u);
  const MeshPart& p = m.parts[0];
  EXPECT_EQ(p.indices.size(), 6u);
  EXPECT_EQ(p.normals.size(), p.positions.size());
  EXPECT_EQ(p.uvs.size() / 2, p.vertexCount());
  EXPECT_NEAR(p.material.baseColor[1], 0.8f, 1e-6);
  EXPECT_EQ(p.material.texture, nullptr);
  EXPECT_TRUE(m.warnings.empty());
}

TEST(Mesh, GeometryIsOnePartOfPositionsAndTriangles) {
  MemoryFileSystem fs = quadFiles();
  Mesh m;
  std::string err;
  ASSERT_TRUE(loadMesh(fs, "/m/quad.obj", MeshContent::Geometry, m, &err)) << err;
  ASSERT_EQ(m.parts.size(), 1u);
  EXPECT_EQ(m.triangleCount(), 2u);
  EXPECT_TRUE(m.parts[0].normals.empty());
  for (std::uint32_t i : m.parts[0].indices) EXPECT_LT(i, m.parts[0].vertexCount());
}

TEST(Mesh, PngAndJpegTexturesAreDecoded) {
  for (const std::string& name : {std::string("tex.png"), std::string("tex.jpg")}) {
    MemoryFileSystem fs = quadFiles(name);
    Image red = test::solidImage(8, 8, 250, 10, 10);
    fs.addFile("/m/" + name, name == "tex.png" ? encodePng(red) : test::encodeJpeg(red));
    Mesh m;
    std::string err;
    ASSERT_TRUE(loadMesh(fs, "/m/quad.obj", MeshContent::Surface, m, &err)) << err;
    ASSERT_NE(m.parts[0].material.texture, nullptr) << name << ": " << (m.warnings.empty() ? "" : m.warnings[0]);
    EXPECT_EQ(m.parts[0].material.texture->width, 8);
    EXPECT_NEAR(m.parts[0].material.texture->pixel(4, 4)[0], 250, 8) << name;
  }
}

TEST(Mesh, MissingOrBadTextureIsAWarningNotAFailure) {
  MemoryFileSystem fs = quadFiles("gone.png");
  Mesh m;
  std::string err;
  ASSERT_TRUE(loadMesh(fs, "/m/quad.obj", MeshContent::Surface, m, &err)) << err;
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_EQ(m.warnings[0], "texture /m/gone.png is not drawn: No such file or directory");
  fs.addFile("/m/gone.png", "not an image");
  ASSERT_TRUE(loadMesh(fs, "/m/quad.obj", MeshContent::Surface, m, &err)) << err;
  EXPECT_EQ(m.warnings.at(0), "texture /m/gone.png is not drawn: not a png, jpeg or hdr image");
}

TEST(Mesh, FailuresSayWhy) {
  MemoryFileSystem fs = quadFiles();
  fs.addOther("/dev/zero");
  fs.addFile("/m/points.obj", "v 0 0 0\nv 1 0 0\np 1\np 2\n");
  Mesh m;
  std::string err;
  EXPECT_FALSE(loadMesh(fs, "/m/none.obj", MeshContent::Geometry, m, &err));
  EXPECT_EQ(err, "No such file or directory");
  EXPECT_FALSE(loadMesh(fs, "/dev/zero", MeshContent::Geometry, m, &err));
  EXPECT_EQ(err, "not a regular file");
  EXPECT_FALSE(loadMesh(fs, "/m/points.obj", MeshContent::Geometry, m, &err));
  EXPECT_EQ(err, "no triangles in mesh file");
  AssetLimits small;
  small.maxFileBytes = 10;
  EXPECT_FALSE(loadMesh(fs, "/m/quad.obj", MeshContent::Geometry, m, &err, small));
  EXPECT_EQ(err, "file larger than 10 bytes");
}

TEST(Mesh, RealDiskDevicesAreRefusedAtOnce) {
  Mesh m;
  std::string err;
  EXPECT_FALSE(loadMesh(diskFileSystem(), "/dev/zero", MeshContent::Geometry, m, &err));
  EXPECT_EQ(err, "not a regular file");
}

TEST(Mesh, FixturesOnDisk) {
  Mesh m;
  std::string err;
  ASSERT_TRUE(loadMesh(diskFileSystem(), data("crate.obj"), MeshContent::Surface, m, &err)) << err;
  ASSERT_EQ(m.parts.size(), 1u);
  EXPECT_EQ(m.parts[0].indices.size(), 36u);
  EXPECT_NEAR(m.parts[0].material.baseColor[1], 0.8f, 1e-5);
  ASSERT_TRUE(loadMesh(diskFileSystem(), data("tetra.stl"), MeshContent::Geometry, m, &err)) << err;
  EXPECT_EQ(m.triangleCount(), 4u);
  ASSERT_TRUE(loadMesh(diskFileSystem(), data("triangle.gltf"), MeshContent::Surface, m, &err)) << err;
  EXPECT_EQ(m.parts[0].indices.size(), 3u);
  EXPECT_NEAR(m.parts[0].material.baseColor[2], 0.9f, 1e-5);
}

TEST(Cache, ReadsAFileOnceForEveryAsker) {
  MemoryFileSystem fs = quadFiles("tex.png");
  fs.addFile("/m/tex.png", encodePng(test::solidImage(2, 2, 1, 2, 3)));
  AssetCache cache(fs);
  std::string err;
  auto a = cache.mesh("/m/quad.obj", MeshContent::Surface, &err);
  ASSERT_TRUE(a) << err;
  int reads = fs.reads();  // obj, mtl, png
  EXPECT_EQ(reads, 3);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(cache.mesh("/m/quad.obj", MeshContent::Surface, &err), a);
  EXPECT_EQ(cache.image("/m/tex.png", &err), a->parts[0].material.texture);  // shared with the mesh
  EXPECT_EQ(fs.reads(), reads);
  // What is extracted is part of the key.
  auto g = cache.mesh("/m/quad.obj", MeshContent::Geometry, &err);
  ASSERT_TRUE(g);
  EXPECT_NE(g, a);
  EXPECT_TRUE(g->parts[0].normals.empty());
}

TEST(Cache, FailuresAreCachedWithTheirReason) {
  MemoryFileSystem fs;
  AssetCache cache(fs);
  std::string err;
  EXPECT_FALSE(cache.mesh("/x.obj", MeshContent::Geometry, &err));
  EXPECT_EQ(err, "No such file or directory");
  fs.addFile("/x.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  err.clear();
  EXPECT_FALSE(cache.mesh("/x.obj", MeshContent::Geometry, &err));  // one answer per run
  EXPECT_EQ(err, "No such file or directory");
  EXPECT_FALSE(cache.image("/nope.png", &err));
  EXPECT_FALSE(cache.floatImage("/nope.hdr", &err));
}

namespace {

// One triangle reaching up to z = 2 (in the file's units), written Z_UP.
std::string colladaTriangle(const std::string& unit) {
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset>)" + unit + R"(<up_axis>Z_UP</up_axis></asset>
  <library_geometries>
    <geometry id="tri" name="tri"><mesh>
      <source id="tri-pos"><float_array id="tri-pos-array" count="9">0 0 0 1 0 0 0 0 2</float_array>
        <technique_common><accessor source="#tri-pos-array" count="3" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common></source>
      <vertices id="tri-vtx"><input semantic="POSITION" source="#tri-pos"/></vertices>
      <triangles count="1"><input semantic="VERTEX" source="#tri-vtx" offset="0"/><p>0 1 2</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene"><node id="n"><instance_geometry url="#tri"/></node></visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";
}

float maxCoordinate(const Mesh& m, int axis) {
  float hi = -1e30f;
  for (const MeshPart& p : m.parts)
    for (std::size_t v = 0; v < p.vertexCount(); ++v) hi = std::max(hi, p.positions[v * 3 + std::size_t(axis)]);
  return hi;
}

}  // namespace

// Robot meshes (ANYmal's .dae files) are written Z_UP in a z-up world:
// assimp's rotation to Y up would lay every link on its side.
TEST(Mesh, ColladaZUpKeepsItsCoordinatesAndUnit) {
  MemoryFileSystem fs;
  fs.addFile("/m/tri.dae", colladaTriangle(R"(<unit name="meter" meter="1"/>)"));
  fs.addFile("/m/tri_cm.dae", colladaTriangle(R"(<unit name="centimeter" meter="0.01"/>)"));
  for (MeshContent content : {MeshContent::Geometry, MeshContent::Surface}) {
    Mesh m;
    std::string err;
    ASSERT_TRUE(loadMesh(fs, "/m/tri.dae", content, m, &err)) << err;
    EXPECT_NEAR(maxCoordinate(m, 2), 2.0f, 1e-6);  // still along +z
    EXPECT_NEAR(maxCoordinate(m, 1), 0.0f, 1e-6);
    ASSERT_TRUE(loadMesh(fs, "/m/tri_cm.dae", content, m, &err)) << err;
    EXPECT_NEAR(maxCoordinate(m, 2), 0.02f, 1e-6);  // <unit> applies
  }
}
