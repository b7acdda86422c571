// The file names rscene-sim --sensors gives sensor streams, and the
// outputPath values it refuses.
#include <gtest/gtest.h>

#include "sim/sensor_paths.hpp"
#include "sim/sensor_test_scene.hpp"

using namespace rscene;
using namespace rscene::sim;

TEST(SensorPaths, APathBecomesOneSafeFileName) {
  EXPECT_EQ(sensorFileName("/World/Robot/Imu"), "World+Robot+Imu");
  EXPECT_EQ(sensorFileName("/World/anymal/os1_64/lidar"), "World+anymal+os1_64+lidar");
  EXPECT_EQ(sensorFileName("/World/a b/c%d+e"), "World+a%20b+c%25d%2Be");
  EXPECT_EQ(sensorFileName("/World/../x"), "World+%2E.+x");
  EXPECT_EQ(sensorFileName("/.hidden/v1.2"), "%2Ehidden+v1.2");
  EXPECT_EQ(sensorFileName("/World//x"), "World++x");  // not the same as /World/x
  EXPECT_NE(sensorFileName("/World/a+b"), sensorFileName("/World/a/b"));
  for (const char* p : {"/World/Robot/Imu", "/a/../../b", "/x/./y", "/%2F"})
    EXPECT_EQ(sensorFileName(p).find('/'), std::string::npos) << p;
}

TEST(SensorPaths, OutputPathsMustStayUnderTheFolder) {
  std::string why;
  EXPECT_TRUE(safeRelativePath("imu.csv", why));
  EXPECT_TRUE(safeRelativePath("robot/front/imu.jsonl", why));
  EXPECT_TRUE(safeRelativePath("a..b/scan", why));  // '..' inside a name is a name
  EXPECT_FALSE(safeRelativePath("/tmp/imu.csv", why));
  EXPECT_NE(why.find("absolute"), std::string::npos);
  EXPECT_FALSE(safeRelativePath("../imu.csv", why));
  EXPECT_FALSE(safeRelativePath("a/../../imu.csv", why));
  EXPECT_FALSE(safeRelativePath("a/..", why));
  EXPECT_NE(why.find("'..'"), std::string::npos);
  EXPECT_TRUE(safeRelativePath("scans/front/", why));  // a folder (a LiDAR's); validate accepts it too
}

TEST(SensorPaths, PlanNamesOutputsAndRefusesBadOnes) {
  auto r = test::makeSensorRun(
      "sensor /World/Imu imu - 0 0 1 1 0 0 0\n"
      "sensor /World/Imu2 imu - 0 0 1 1 0 0 0 outputPath=streams/imu.jsonl\n"
      "sensor /World/Lidar lidar - 0 0 1 1 0 0 0\n"
      "sensor /World/Off lidar - 0 0 1 1 0 0 0 enabled=false\n"
      "sensor /World/Abs imu - 0 0 1 1 0 0 0 outputPath=/etc/imu.csv\n"
      "sensor /World/Up imu - 0 0 1 1 0 0 0 outputPath=../imu.csv\n"
      "sensor /World/Same imu - 0 0 1 1 0 0 0 outputPath=World+Imu.csv\n");
  ASSERT_EQ(r->sensors.size(), 3u);
  EXPECT_EQ(r->sensors[0].output, "World+Imu.csv");
  EXPECT_EQ(r->sensors[0].imuFormat, ImuFormat::Csv);
  EXPECT_EQ(r->sensors[1].output, "streams/imu.jsonl");
  EXPECT_EQ(r->sensors[1].imuFormat, ImuFormat::Jsonl);
  EXPECT_EQ(r->sensors[2].output, "World+Lidar");
  EXPECT_EQ(r->sensors[2].directions.size(), 16u * 1024u);  // the schema's defaults
  std::vector<std::string> codes;
  for (const Diagnostic& d : r->diags) codes.push_back(d.code + ":" + std::to_string(d.line));
  EXPECT_EQ(codes, (std::vector<std::string>{"RS7069:7", "RS7069:8", "RS7070:9"}));
}
