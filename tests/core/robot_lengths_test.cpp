// RS4007: generalizedCoordinate and generalizedVelocity lengths no robot can
// have.  Each quaternion (floating base, spherical joint) is one coordinate
// more than its velocities, so q = u + k with 3k <= u.
#include <gtest/gtest.h>

#include "core/check.hpp"

using namespace rscene;

namespace {

bool rs4007(const std::string& q, const std::string& u) {
  Document doc;
  Diagnostics ds = validateText("raisim_engine_scene 1\narticulated_resource r r r.urdf\n"
                                "articulated /World/r r 0 0 0 1 0 0 0 true true generalizedCoordinate=" +
                                    q + " generalizedVelocity=" + u + "\n",
                                CheckOptions{}, doc);
  for (const Diagnostic& d : ds)
    if (d.code == "RS4007") return true;
  return false;
}

TEST(RobotLengths, LengthsSomeRobotHasPass) {
  EXPECT_FALSE(rs4007("0,0", "0,0"));                          // fixed base, two revolute joints
  EXPECT_FALSE(rs4007("0,0,1,1,0,0,0", "0,0,0,0,0,0"));        // floating base alone
  EXPECT_FALSE(rs4007("1,0,0,0,1,0,0,0", "0,0,0,0,0,0"));      // fixed base, two spherical joints
  EXPECT_FALSE(rs4007("0,0,1,1,0,0,0,1,0,0,0,0.5", "0,0,0,0,0,0,0,0,0,0"));  // floating + spherical + revolute
}

TEST(RobotLengths, LengthsNoRobotHasAreReported) {
  EXPECT_TRUE(rs4007("0,0", "0,0,0"));            // fewer coordinates than velocities
  EXPECT_TRUE(rs4007("1,0,0,0,0", "0,0"));        // three quaternions would need 9 velocities
  EXPECT_TRUE(rs4007("0,0,0", "0"));
}

}  // namespace

namespace {

// --check-files: a robot's resourceDirectory is a directory, not a missing file.
TEST(RobotFiles, ResourceDirectoryIsNoFileToFind) {
  Document doc;
  CheckOptions o;
  o.checkFiles = true;
  o.fileExists = [](const std::string& p) { return p.find("robot.urdf") != std::string::npos; };
  Diagnostics ds = validateText("raisim_engine_scene 1\narticulated_resource r r robot.urdf resourceDirectory=robots\n"
                                "articulated /World/r r 0 0 0 1 0 0 0 true true resourceDirectory=robots "
                                "sourcePath=gone.urdf\n",
                                o, doc);
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].code, "RS5001");
  EXPECT_EQ(ds[0].field, "sourcePath");
}

}  // namespace

namespace {

// articulated_ik's target is a vector in one positional token (csv3): its
// numbers are checked like a vec3 key's.
TEST(RobotFiles, IkTargetNumbersAreChecked) {
  auto codes = [](const std::string& target) {
    Document doc;
    std::string out;
    for (const Diagnostic& d : validateText("raisim_engine_scene 1\narticulated_resource r r r.urdf\n"
                                            "articulated /World/r r 0 0 0 1 0 0 0 true true\n"
                                            "articulated_ik /World/r foot " + target + "\n",
                                            CheckOptions{}, doc))
      out += d.code + " ";
    return out;
  };
  EXPECT_EQ(codes("0.1,0.2,0.3"), "");
  EXPECT_EQ(codes("nan,0,0"), "RS2002 ");
  EXPECT_EQ(codes("0,x,0"), "RS2001 ");
  EXPECT_EQ(codes("1,2"), "RS2008 ");
}

}  // namespace
