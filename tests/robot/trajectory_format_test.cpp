// The trajectory format's writer and reader agree (robot/trajectory_format.hpp):
// what TrajectoryWriter writes, TrajectoryReader reads back to the bit, in
// both formats, with paths that need CSV quoting.
#include <gtest/gtest.h>

#include "robot/trajectory_format.hpp"
#include "trajectory_read_util.hpp"

namespace rscene::robot {
namespace {

BodyState body(const std::string& path, double x) {
  BodyState b;
  b.path = path;
  b.position = Eigen::Vector3d(x, -0.1 / 3, 1e-300);
  b.orientation = Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5);
  b.linearVelocity = Eigen::Vector3d(1, 2, 3);
  return b;
}

void roundTrip(TrajectoryFormat format) {
  SCOPED_TRACE(format == TrajectoryFormat::Csv ? "csv" : "jsonl");
  TrajectoryWriter writer(format, {});
  std::vector<Eigen::Vector3d> grains = {{0.1, 0.2, 0.3}, {1.0 / 3, -2, 1e11}};
  ParticleState particles;
  particles.path = "/World/Sand";
  particles.granular = true;
  particles.points = &grains;
  std::string text = writer.header();
  for (int step = 0; step < 2; ++step)
    writer.append(text, 0.0025 * step, {body("/World/A,\"B\"", 1.0 / 7 + step), body("/World/C", -2)}, {},
                  {particles});
  test::Read read = test::readAll(text);
  ASSERT_FALSE(read.failed) << (read.diags.empty() ? "" : read.diags[0].message);
  ASSERT_EQ(read.frames.size(), 2u);
  const TrajectoryFrame& f = read.frames[1];
  EXPECT_EQ(f.time, 0.0025);
  ASSERT_EQ(f.entries.size(), 3u);
  EXPECT_EQ(f.entries[0].path, "/World/A,\"B\"");  // quoted in CSV, escaped in JSON
  EXPECT_EQ(f.entries[0].pose.position.x(), 1.0 / 7 + 1);
  EXPECT_EQ(f.entries[0].pose.position.y(), -0.1 / 3);
  EXPECT_EQ(f.entries[0].pose.position.z(), 1e-300);
  EXPECT_NEAR(f.entries[0].pose.orientation.w(), 0.5, 1e-15);
  EXPECT_EQ(f.entries[1].path, "/World/C");
  ASSERT_TRUE(f.entries[2].particles);
  ASSERT_EQ(f.entries[2].points.size(), 2u);
  EXPECT_EQ(f.entries[2].points[1], grains[1]);
}

TEST(TrajectoryFormat, WhatTheWriterWritesTheReaderReadsBack) {
  roundTrip(TrajectoryFormat::Jsonl);
  roundTrip(TrajectoryFormat::Csv);
}

// A body path may hold any byte (percent escapes in the scene): a newline
// is quoted in CSV and read back over two lines, counted as two; a byte
// that is not UTF-8 becomes U+FFFD in JSON, never an exception.
TEST(TrajectoryFormat, PathsWithNewlinesAndBytesThatAreNotUtf8) {
  const std::string newline = "/World/nl\nline", notUtf8 = "/World/x\xFF";
  TrajectoryWriter csv(TrajectoryFormat::Csv, {});
  std::string text = csv.header();
  csv.append(text, 0, {body(newline, 1), body(notUtf8, 2)}, {});
  csv.append(text, 0.1, {body(newline, 1), body("/World/end", 2)}, {});
  test::Read read = test::readAll(text);
  ASSERT_FALSE(read.failed) << (read.diags.empty() ? "" : read.diags[0].message);
  ASSERT_EQ(read.frames.size(), 2u);
  EXPECT_EQ(read.frames[0].entries[0].path, newline);
  EXPECT_EQ(read.frames[0].entries[1].path, notUtf8);
  EXPECT_EQ(read.frames[0].entries[1].line, 4u);  // the header, then two lines for the first row
  EXPECT_EQ(read.frames[1].entries[1].line, 7u);
  test::Read bad = test::readAll(text + "0.2,/World/bad\n");  // a short row: its line counts the continued ones
  ASSERT_TRUE(bad.failed);
  ASSERT_FALSE(bad.diags.empty());
  EXPECT_EQ(bad.diags[0].line, 8u);

  TrajectoryWriter jsonl(TrajectoryFormat::Jsonl, {});
  std::string lines;
  jsonl.append(lines, 0, {body(notUtf8, 1)}, {});
  test::Read json = test::readAll(lines);
  ASSERT_FALSE(json.failed) << (json.diags.empty() ? "" : json.diags[0].message);
  EXPECT_EQ(json.frames.at(0).entries.at(0).path, jsonSafeText(notUtf8));
  EXPECT_EQ(jsonSafeText(notUtf8), "/World/x\xEF\xBF\xBD");
  EXPECT_EQ(jsonSafeText("/World/caf\xC3\xA9"), "/World/caf\xC3\xA9");  // valid UTF-8 kept
}

TEST(TrajectoryFormat, CsvHeaderIsTheColumnTable) {
  TrajectoryWriter writer(TrajectoryFormat::Csv, {});
  EXPECT_EQ(writer.header(), "time,path,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,points\n");
  EXPECT_EQ(TrajectoryWriter(TrajectoryFormat::Jsonl, {}).header(), "");
}

TEST(TrajectoryFormat, CsvQuotingSplitsBack) {
  std::string line;
  for (std::string field : {"plain", "a,b", "say \"hi\"", "", "line\nbreak"}) {
    if (!line.empty() || field != "plain") line += ',';
    appendCsvField(line, field);
  }
  std::vector<CsvField> fields;
  std::uint32_t bad = 0;
  ASSERT_TRUE(splitCsv(line, fields, bad));
  ASSERT_EQ(fields.size(), 5u);
  EXPECT_EQ(fields[1].text, "a,b");
  EXPECT_EQ(fields[2].text, "say \"hi\"");
  EXPECT_EQ(fields[3].text, "");
  EXPECT_EQ(fields[4].text, "line\nbreak");
  EXPECT_FALSE(splitCsv("\"open", fields, bad));
  EXPECT_EQ(bad, 1u);
}

TEST(TrajectoryFormat, ReaderRefusesWhatNoSimulationWrites) {
  TrajectoryWriter writer(TrajectoryFormat::Jsonl, {});
  std::string text;
  writer.append(text, 0, {body("/World/A", kMaxTrajectoryValue * 2)}, {});
  test::Read read = test::readAll(text);
  EXPECT_TRUE(read.failed);
  ASSERT_FALSE(read.diags.empty());
  EXPECT_EQ(read.diags[0].code, "RS9046");
}

}  // namespace
}  // namespace rscene::robot
