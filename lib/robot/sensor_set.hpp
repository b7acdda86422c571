// RaiSim's sensor sets (Sensors.rst, "How to attach a sensor to a link"):
// a URDF link written `<link name="L" sensor="FILE.xml"/>` carries the
// sensors of FILE, a <sensor_set> with an <origin> (the set's frame in the
// link frame) and a <link> holding the set's body (visuals, collisions, an
// inertial) and its <sensor name type update_rate> elements:
//
//   <origin xyz rpy>                         in the set's frame
//   <camera horizontal_fov="RAD">            rgb, depth
//     <image width height/> <clip near far/> <noise type mean stddev/>
//   <update_rate>HZ</update_rate>            used when the attribute is absent
//   <yaw samples/> <pitch samples min_angle max_angle/>   spinning_lidar (radians)
//   <spin direction rate/> <range min max/>
//   <limit acc_limit ang_vel_limit/>         imu
//
// Each sensor becomes a SensorDef of Model::sensors in SensorParams' units
// (degrees, metres, Hz), placed at set origin * sensor origin in the link
// frame.  A number a sensor leaves out takes the sensor record's default
// (the schema table), so a URDF camera without <image> is 640 x 480 like a
// record without width and height.  The update_rate attribute wins over
// the <update_rate> element: ArticulatedSystem.rst says RaiSim applies the
// attribute (realsense435.xml writes both, 20 and 60).
//
// The set's body joins the link (the URDF link is usually empty, the file
// describes the device): its visuals and collisions are added at set
// origin * their origin, its inertial is combined with the link's (masses
// add, inertias about the common centre of mass).  Sensors.rst does not say
// what RaiSim does with them; adding them is what a link written out in
// full would hold.  Their elements are read by the URDF reader (codes
// RS7030/RS7031 at the sensor-set file's line); their `line` is 0 in the
// model, whose lines refer to the URDF.
#pragma once
#include <tinyxml2.h>

#include <string>
#include <vector>

#include "core/codes.hpp"
#include "core/diagnostic.hpp"
#include "core/filesystem.hpp"
#include "robot/model.hpp"

namespace rscene::robot {

namespace code {
inline constexpr const char* kNoSensorSet = rs::RS7060;    // sensor set file not found in RaiSim's search order
inline constexpr const char* kBadSensorSet = rs::RS7061;   // sensor set file that does not parse
inline constexpr const char* kSensorSkipped = rs::RS7062;  // sensor set element skipped (warning)
}  // namespace code

// Where `file` (a <link sensor=> value) may be, in RaiSim's order: as is
// when absolute; else DIR/F, DIR/sensor/F, DIR/sensors/F, DIR/../F,
// DIR/../sensors/F, DIR the URDF's directory.
std::vector<std::string> sensorSetCandidates(const std::string& urdfDirectory, const std::string& file);

// A sensor set file read and parsed.
struct SensorSetFile {
  std::string path;  // the file found
  tinyxml2::XMLDocument doc;
  std::string name;                            // <sensor_set name>
  Pose origin;                                 // the set's frame in the link frame
  const tinyxml2::XMLElement* body = nullptr;  // its <link>, nullptr when none
};

// Finds (RS7060 at the URDF link's `line` of `urdfFile`, listing the
// places searched) and parses (RS7061) the set `file`.  False after an error.
bool openSensorSet(const FileSystem& files, const std::string& urdfDirectory, const std::string& file, const std::string& urdfFile, int line,
                   std::size_t maxBytes, SensorSetFile& out, Diagnostics& diagnostics);

// The <sensor> elements of `set` (inside its <link>, or directly in the
// <sensor_set>) as sensors of the link named `linkName` (`link` index
// -1: the caller sets it once the tree is built).  Problems are RS7061,
// RS7062 and the sensor record's codes for its bounds (RS7064-RS7067,
// scene/sensor_check.hpp) at the element's line of the set's file.
// False after an error.
bool readSensors(const SensorSetFile& set, const std::string& linkName, std::vector<SensorDef>& out,
                 Diagnostics& diagnostics);

// Adds the body `extra` to `into`: masses add, the centre of mass is
// their weighted mean, inertias move to it (parallel axes), expressed in
// the axes of `into`'s inertial frame (or `extra`'s when `into` has no mass).
void combineInertial(Inertial& into, const Inertial& extra);

}  // namespace rscene::robot
