// Point clouds as PCD v0.7 (the Point Cloud Library's format; ROS's
// pcl_ros, Open3D, CloudCompare and pcl_viewer open it).  Why PCD and not
// PLY: it is the native cloud format of the ROS/PCL tool chain LiDAR users
// already have, it carries the acquisition pose (VIEWPOINT) and needs no
// face section.  Fields x y z, float32, one row (unorganised: no-return
// rays are left out).  Binary by default: exact floats, 12 bytes a point
// (a 64 x 1024 scan: 768 KB, against about 2.5 MB as text); ascii on
// request, for eyes and diffs.
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/writer.hpp"
#include "scene/scene.hpp"

namespace rscene::sim {

enum class PcdEncoding { Binary, Ascii };

// Writes one cloud.  `viewpoint` (the sensor's world pose when the scan
// was taken) goes into VIEWPOINT (tx ty tz qw qx qy qz), which PCL reads as
// the cloud's sensor origin and orientation: a point p of the file is at
// viewpoint * p in the world.  `time` (simulated seconds) goes into a
// comment line, which PCD readers skip.
void writePcd(Sink& out, const std::vector<Eigen::Vector3f>& points, const Pose& viewpoint, double time,
              PcdEncoding encoding);

}  // namespace rscene::sim
