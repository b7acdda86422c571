// A robot read through an injected FileSystem (LoadOptions::files): the
// URDF, its module and its sensor set come from memory, and nothing on the
// disk is consulted, so a path that exists on the disk is still missing.
#include <gtest/gtest.h>

#include "core/filesystem.hpp"
#include "robot/load.hpp"

namespace rscene::robot {
namespace {

const char* kArm = R"(<robot name="arm">
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="tip" sensor="tip_sensors.xml"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="tip"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>)";

const char* kGripper = R"(<robot name="gripper">
  <link name="finger"><inertial><mass value="0.1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="g" type="fixed"><parent link="tip"/><child link="finger"/></joint>
</robot>)";

const char* kSensors = R"(<sensor_set name="s"><link>
  <sensor name="imu" type="imu" update_rate="400"><origin xyz="0 0 0.1"/></sensor>
</link></sensor_set>)";

TEST(RobotFileSystem, UrdfModuleAndSensorSetComeFromTheInjectedFiles) {
  MemoryFileSystem files;
  files.addFile("/mem/arm.urdf", kArm);
  files.addFile("/mem/gripper.urdf", kGripper);
  files.addFile("/mem/tip_sensors.xml", kSensors);
  LoadOptions options;
  options.files = &files;
  options.modules = {"gripper.urdf"};
  Model m;
  Diagnostics d;
  ASSERT_TRUE(loadModel("/mem/arm.urdf", options, m, d)) << (d.empty() ? "" : d.front().message);
  EXPECT_EQ(m.links.size(), 3u);
  ASSERT_EQ(m.sensors.size(), 1u);
  EXPECT_EQ(m.sensors[0].name, "imu");
}

TEST(RobotFileSystem, AFileOnlyOnTheDiskIsMissingThroughMemory) {
  MemoryFileSystem files;
  LoadOptions options;
  options.files = &files;
  Model m;
  Diagnostics d;
  // The test binary itself exists on the disk, not in `files`.
  EXPECT_FALSE(loadModel("/proc/self/exe", options, m, d));
  ASSERT_FALSE(d.empty());
  EXPECT_EQ(d.front().code, std::string("RS5001"));
}

}  // namespace
}  // namespace rscene::robot
