// The FileSystem interface: the disk refuses what is not a regular file at
// once (no hang on a FIFO, no endless read of /dev/zero); the in-memory
// one behaves the same for tests.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/filesystem.hpp"

using namespace rscene;

namespace {

struct TempDir {
  std::string path;
  TempDir() {
    char tmpl[] = "/tmp/rscene-fs-XXXXXX";
    path = mkdtemp(tmpl);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
};

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

TEST(DiskFileSystem, ReadsRegularFilesWhole) {
  TempDir dir;
  std::string file = dir.path + "/a.txt";
  std::ofstream(file) << "hello\n";
  const FileSystem& fs = diskFileSystem();
  EXPECT_EQ(fs.stat(file).kind, FileKind::Regular);
  EXPECT_EQ(fs.stat(file).size, 6u);
  EXPECT_EQ(fs.stat(dir.path).kind, FileKind::Directory);
  EXPECT_EQ(fs.stat(dir.path + "/none").kind, FileKind::Missing);
  std::string out, err;
  ASSERT_TRUE(fs.read(file, out, &err)) << err;
  EXPECT_EQ(out, "hello\n");
  EXPECT_FALSE(fs.read(file, out, &err, 5));
  EXPECT_EQ(err, "file larger than 5 bytes");
  EXPECT_FALSE(fs.read(dir.path + "/none", out, &err));
  EXPECT_EQ(err, "No such file or directory");
  EXPECT_FALSE(fs.read(dir.path, out, &err));
  EXPECT_EQ(err, "is a directory");
}

TEST(DiskFileSystem, DevicesAndFifosAreRefusedWithoutWaiting) {
  TempDir dir;
  std::string fifo = dir.path + "/pipe";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const FileSystem& fs = diskFileSystem();
  EXPECT_EQ(fs.stat("/dev/zero").kind, FileKind::Other);
  EXPECT_EQ(fs.stat(fifo).kind, FileKind::Other);
  auto t0 = std::chrono::steady_clock::now();
  std::string out, err;
  EXPECT_FALSE(fs.read("/dev/zero", out, &err));
  EXPECT_EQ(err, "not a regular file");
  EXPECT_FALSE(fs.read(fifo, out, &err));  // no writer: a blocking open would wait for ever
  EXPECT_EQ(err, "not a regular file");
  EXPECT_LT(secondsSince(t0), 1.0);
}

TEST(MemoryFileSystem, ActsLikeADisk) {
  MemoryFileSystem fs;
  fs.addFile("/scene/meshes/a.obj", "v 0 0 0\n");
  fs.addOther("/dev/zero");
  EXPECT_EQ(fs.stat("/scene/meshes/a.obj").kind, FileKind::Regular);
  EXPECT_EQ(fs.stat("/scene/meshes/a.obj").size, 8u);
  EXPECT_EQ(fs.stat("/scene/meshes").kind, FileKind::Directory);
  EXPECT_EQ(fs.stat("/scene/mesh").kind, FileKind::Missing);  // a prefix of a name is no directory
  EXPECT_TRUE(fs.exists("/scene"));
  std::string out, err;
  ASSERT_TRUE(fs.read("/scene/meshes/a.obj", out, &err));
  EXPECT_EQ(out, "v 0 0 0\n");
  EXPECT_EQ(fs.reads(), 1);
  EXPECT_FALSE(fs.read("/scene/meshes/a.obj", out, &err, 4));
  EXPECT_EQ(err, "file larger than 4 bytes");
  EXPECT_FALSE(fs.read("/dev/zero", out, &err));
  EXPECT_EQ(err, "not a regular file");
  EXPECT_FALSE(fs.read("/scene", out, &err));
  EXPECT_EQ(err, "is a directory");
  EXPECT_FALSE(fs.read("/b", out, &err));
  EXPECT_EQ(err, "No such file or directory");
}
