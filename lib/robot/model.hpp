// The robot model (DESIGN.md, lib/robot): one description of an articulated
// system, whatever file it came from (URDF in RaiSim's dialect, or MJCF
// compiled by MuJoCo), that sim, render and validate all read.
//
// The model is a kinematic tree in URDF's terms: links joined by joints,
// each joint placing its child link in its parent link's frame.  A link's
// frame is where its parent joint puts it; its inertial, visual and
// collision elements carry their own origin in that frame.  Fixed joints
// stay in the model (they are frames users name); a simulator merges them
// into the body they are fixed to.
//
// Units are SI; angles radians.  The model is already scaled (`scale=` of
// the record) and its mesh paths already resolved (package://, relative to
// the robot file), so the tools downstream never see the file's spelling.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.hpp"  // Pose

namespace rscene::robot {

enum class GeometryKind { Box, Sphere, Cylinder, Capsule, Mesh };

// A shape in its element's frame.  Cylinders and capsules lie along the
// frame's z axis; a capsule's `length` is the distance between the centres
// of its two spheres (RaiSim's "height" convention; MJCF's half-length x 2).
struct Geometry {
  GeometryKind kind = GeometryKind::Box;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // box: full side lengths
  double radius = 0;                               // sphere, cylinder, capsule
  double length = 0;                               // cylinder, capsule
  std::string meshPath;                            // mesh: resolved file path
  Eigen::Vector3d meshScale = Eigen::Vector3d::Ones();
};

// A visual element.  `color` is the URDF material colour (or MJCF rgba)
// when the file gives one; otherwise a mesh keeps its own materials and a
// primitive is drawn in the renderer's default.
struct Visual {
  std::string name;
  Pose origin;  // in the link frame
  Geometry geometry;
  std::optional<Eigen::Vector4d> color;
  std::string texture;       // resolved texture file of the URDF material, empty = none
  std::string materialName;  // as written, for messages
  int line = 0;              // in `Model::sourceFile` (0: unknown)
};

struct Collision {
  std::string name;
  Pose origin;  // in the link frame
  Geometry geometry;
  int line = 0;
};

struct Inertial {
  double mass = 0;
  Pose origin;                                         // centre of mass frame, in the link frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about the centre of mass, in `origin`'s axes
};

struct Link {
  std::string name;
  Inertial inertial;
  std::vector<Visual> visuals;
  std::vector<Collision> collisions;
  int parentJoint = -1;          // index into Model::joints; -1 for the root
  std::vector<int> childJoints;  // in file order
  int line = 0;
  // The file `line` (and the lines of the link's elements) are in when it
  // is not Model::sourceFile: a URDF module.  Empty: Model::sourceFile.
  std::string file;
  // RaiSim's <link sensor="FILE">: the sensor set file as written; its
  // sensors are in Model::sensors.
  std::string sensorSet;
};

// One sensor of a sensor set a URDF link names (RaiSim's <link
// sensor="FILE">, Sensors.rst): `<sensor name type update_rate>` of the
// set's file, placed on the link that names the set.
struct SensorDef {
  std::string set;    // the link's name (RaiSim names the set by it)
  std::string name;   // the sensor's name in the set ("color", "depth", "imu", "lidar")
  std::string kind;   // canonical sensor_kind: rgb, depth, imu, lidar (spinning_lidar); others skipped (RS7062)
  int link = -1;      // index into Model::links
  Pose origin;        // in the link frame: the set's <origin> then the sensor's
  SensorParams params;  // degrees, metres, Hz (scene/scene.hpp)
  std::string file;   // the sensor-set file (resolved)
  int line = 0;       // of the <sensor> element in `file`
};

// Floating only ever joins the world to the root (an MJCF free joint, or a
// URDF whose root is not `world`): it is Model::floatingBase, not a Joint.
enum class JointType { Fixed, Revolute, Continuous, Prismatic, Spherical };

struct Joint {
  std::string name;
  JointType type = JointType::Fixed;
  int parentLink = -1, childLink = -1;
  Pose origin;  // child link frame in the parent link frame at q = 0
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // unit, in the joint (child) frame
  // Limits (revolute, prismatic): position [lower, upper] when hasLimits;
  // effort and velocity 0 = none.  Spherical: hasLimits when the URDF's
  // <limit> gives lower or upper, the numbers as written (RaiSim's
  // chain/robot_short.urdf writes only lower="1"; RaiSim does not document
  // what a ball joint's limit means).
  bool hasLimits = false;
  double lower = 0, upper = 0, effort = 0, velocity = 0;
  // <dynamics>: viscous damping (N m s/rad or N s/m), Coulomb friction,
  // RaiSim's reflected rotor inertia (kg m^2 or kg) and spring.
  double damping = 0, friction = 0, rotorInertia = 0, stiffness = 0;
  // The spring's rest position: 1 number (revolute, prismatic) or a
  // quaternion w x y z (spherical); empty = the zero position.
  std::vector<double> springMount;
  // Where a 1-dof joint starts when the record writes no coordinates:
  // MJCF's qpos0 (the joint's ref), 0 for URDF.
  double initial = 0;
  int line = 0;
  std::string file;  // as Link::file: the module the joint is in, empty = Model::sourceFile

  int coordinateDim() const;  // entries in the generalized coordinate: 0, 1 or 4
  int velocityDim() const;    // entries in the generalized velocity: 0, 1 or 3
};

struct Model {
  std::string name;
  std::string sourceFile;  // the file the lines refer to
  std::vector<Link> links;
  std::vector<Joint> joints;
  std::vector<SensorDef> sensors;  // the sensor sets' sensors, in link order
  int root = 0;  // index of the root link
  // A URDF whose root link is named `world`, or an MJCF model whose first
  // body has no free joint, is fixed to the world at the record's pose.
  bool floatingBase = true;
  // A floating base's start pose relative to the record's pose: an MJCF
  // free body's pos/quat (MuJoCo's qpos0), identity for URDF.
  Pose baseStart;

  int findLink(const std::string& name) const;   // -1 when none
  int findJoint(const std::string& name) const;  // -1 when none
  double totalMass() const;
};

}  // namespace rscene::robot
