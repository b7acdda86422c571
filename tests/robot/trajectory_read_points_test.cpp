// Particle lines of rscene-sim trajectories (deformable and granular
// records): "points" in JSON Lines, the points column in CSV, every
// malformed point refused at its column, counts checked against the scene
// by the poser, and memory bounded by TrajectoryLimits::maxPoints.
#include <gtest/gtest.h>

#include <sstream>

#include "robot/trajectory_read.hpp"
#include "trajectory_read_util.hpp"

namespace rscene::robot {
namespace {

using test::Read;
using test::readAll;

void expectError(const Read& r, std::uint32_t line, std::uint32_t column, const std::string& words) {
  ASSERT_TRUE(r.failed);
  ASSERT_EQ(r.diags.size(), 1u);
  EXPECT_EQ(r.diags[0].code, code::kTrajectorySyntax);
  EXPECT_EQ(r.diags[0].line, line) << r.diags[0].message;
  EXPECT_EQ(r.diags[0].column, column) << r.diags[0].message;
  EXPECT_NE(r.diags[0].message.find(words), std::string::npos) << r.diags[0].message;
}

std::string pointsLine(double t, const std::string& path, const std::string& points) {
  return "{\"time\":" + std::to_string(t) + ",\"path\":\"" + path + "\",\"points\":" + points + "}\n";
}

const std::string kBody =
    "{\"time\":0,\"path\":\"/box\",\"position\":[1,2,3],\"quaternion\":[1,0,0,0],"
    "\"linearVelocity\":[0,0,0],\"angularVelocity\":[0,0,0]}\n";

TEST(TrajectoryReadPoints, JsonPointsAreWorldPositionsInOrder) {
  Read r = readAll(kBody + pointsLine(0, "/cloth", "[[0,0,1],[0.5,-1e-3,2],[1e2,3,4]]") +
                   pointsLine(0, "/sand", "[]"));
  ASSERT_FALSE(r.failed) << r.diags[0].message;
  ASSERT_EQ(r.frames.size(), 1u);
  ASSERT_EQ(r.frames[0].entries.size(), 3u);
  EXPECT_FALSE(r.frames[0].entries[0].particles);
  const TrajectoryEntry& cloth = r.frames[0].entries[1];
  EXPECT_TRUE(cloth.particles);
  ASSERT_EQ(cloth.points.size(), 3u);
  EXPECT_EQ(cloth.points[1], Eigen::Vector3d(0.5, -1e-3, 2));
  EXPECT_EQ(cloth.points[2], Eigen::Vector3d(100, 3, 4));
  EXPECT_EQ(cloth.pointsColumn, 34u);  // "points" after {"time":0.000000,"path":"/cloth",
  EXPECT_TRUE(r.frames[0].entries[2].particles);
  EXPECT_TRUE(r.frames[0].entries[2].points.empty());
}

TEST(TrajectoryReadPoints, CsvPointsColumnAsRsceneSimWritesIt) {
  // sim/trajectory.cpp: a particle row leaves the 13 pose cells and the
  // joint cells empty; a body row leaves the points cell empty.
  Read r = readAll(
      "time,path,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,q.j,u.j,points\n"
      "0,/box,1,2,3,1,0,0,0,0,0,0,0,0,0,,,\n"
      "0,/cloth,,,,,,,,,,,,,,,,0 0 1;0.5 -1 2\n"
      "0,/sand,,,,,,,,,,,,,,,,\n"
      "0.5,/cloth,,,,,,,,,,,,,,,,1 1 1;2 2 2\n");
  ASSERT_FALSE(r.failed) << r.diags[0].message;
  ASSERT_EQ(r.frames.size(), 2u);
  ASSERT_EQ(r.frames[0].entries.size(), 3u);
  EXPECT_FALSE(r.frames[0].entries[0].particles);
  EXPECT_EQ(r.frames[0].entries[0].pose.position, Eigen::Vector3d(1, 2, 3));
  const TrajectoryEntry& cloth = r.frames[0].entries[1];
  ASSERT_TRUE(cloth.particles);
  ASSERT_EQ(cloth.points.size(), 2u);
  EXPECT_EQ(cloth.points[1], Eigen::Vector3d(0.5, -1, 2));
  EXPECT_TRUE(r.frames[0].entries[2].particles);
  EXPECT_TRUE(r.frames[0].entries[2].points.empty());
  EXPECT_EQ(r.frames[1].entries[0].points[1], Eigen::Vector3d(2, 2, 2));
}

TEST(TrajectoryReadPoints, MalformedJsonPointsAreErrorsAtThePoint) {
  std::string notTriple = pointsLine(0, "/c", "[[0,0,1], [1,2]]");
  expectError(readAll(notTriple), 1, static_cast<std::uint32_t>(notTriple.find("[1,2]") + 1),
              "point 1 is not an [x,y,z] triple");
  std::string text = pointsLine(0, "/c", "[[0,0,1],[\"a,]\",0,0]]");
  expectError(readAll(text), 1, static_cast<std::uint32_t>(text.find("[\"a") + 1), "point 1 is not");
  std::string bare = pointsLine(0, "/c", "[[0,0,1],[0,0,2],7]");
  expectError(readAll(bare), 1, static_cast<std::uint32_t>(bare.find("7]") + 1), "point 2 is not");
  std::string huge = pointsLine(0, "/c", "[[0,1e300,1]]");
  expectError(readAll(huge), 1, static_cast<std::uint32_t>(huge.find("[0,1e300") + 1), "point 0 out of range");
  std::string scalar = pointsLine(0, "/c", "5");
  expectError(readAll(scalar), 1, static_cast<std::uint32_t>(scalar.find("\"points\"") + 1), "points is not an array");
  std::string both = "{\"time\":0,\"path\":\"/c\",\"position\":[0,0,0],\"points\":[[0,0,0]]}\n";
  expectError(readAll(both), 1, static_cast<std::uint32_t>(both.find("\"position\"") + 1), "it has no position");
  // A "points" key inside another object is no particle list.
  Read nested = readAll("{\"time\":0,\"path\":\"/r\",\"position\":[0,0,0],\"quaternion\":[1,0,0,0],"
                        "\"jointPositions\":{\"points\":1}}\n");
  ASSERT_FALSE(nested.failed) << nested.diags[0].message;
  EXPECT_FALSE(nested.frames[0].entries[0].particles);
}

TEST(TrajectoryReadPoints, MalformedCsvPointsAreErrorsAtThePoint) {
  const std::string header = "time,path,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,points\n";
  const std::string row = "0,/c,,,,,,,,,,,,,,";
  std::string two = row + "0 0 1;1 2\n";
  expectError(readAll(header + two), 2, static_cast<std::uint32_t>(two.find("1 2") + 1),
              "point 1 '1 2' is not three numbers");
  std::string four = row + "0 0 1 5\n";
  expectError(readAll(header + four), 2, static_cast<std::uint32_t>(row.size() + 1), "point 0 '0 0 1 5'");
  std::string nan = row + "0 0 1;0 nan 1\n";
  expectError(readAll(header + nan), 2, static_cast<std::uint32_t>(nan.find("0 nan") + 1), "point 1");
  std::string far = row + "0 0 1e13\n";
  expectError(readAll(header + far), 2, static_cast<std::uint32_t>(row.size() + 1), "out of range");
  std::string trailing = row + "0 0 1;\n";
  expectError(readAll(header + trailing), 2, static_cast<std::uint32_t>(trailing.size()), "point 1 ''");
  // A row with points and a pose, or a body's row with points.
  expectError(readAll(header + "0,/c,,,,1,,,,,,,,,,0 0 0\n"), 2, 9, "has no pose or joint values");
  expectError(readAll(header + "0,/b,0,0,0,1,0,0,0,0,0,0,0,0,0,0 0 0\n"), 2, 32, "has no points");
}

TEST(TrajectoryReadPoints, OldTrajectoriesWithoutPointsStillRead) {
  Read csv = readAll("time,path,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n0,/b,0,0,0,1,0,0,0,0,0,0,0,0,0\n");
  ASSERT_FALSE(csv.failed) << csv.diags[0].message;
  EXPECT_FALSE(csv.frames[0].entries[0].particles);
  Read json = readAll(kBody);
  ASSERT_FALSE(json.failed);
  EXPECT_EQ(json.frames[0].entries[0].pose.position, Eigen::Vector3d(1, 2, 3));
}

// n points as wide as rscene-sim writes settled grains (17 digits).
std::string manyPoints(std::size_t n) {
  std::string s = "[";
  for (std::size_t i = 0; i < n; ++i)
    s += (i ? ",[" : "[") + std::to_string(i) + ".1234567890123,-0.12345678901234567,1.2345678901234567]";
  return s + "]";
}

TEST(TrajectoryReadPoints, ABedOf20000GrainsReadsAndMoreThanTheSceneHasIsRefused) {
  std::string line = pointsLine(0, "/sand", manyPoints(20000));
  ASSERT_GT(line.size(), std::size_t{1} << 20);  // past the old 1 MiB line limit
  Read ok = readAll(line);
  ASSERT_FALSE(ok.failed) << ok.diags[0].message;
  ASSERT_EQ(ok.frames[0].entries[0].points.size(), 20000u);
  EXPECT_EQ(ok.frames[0].entries[0].points[19999],
            Eigen::Vector3d(19999.1234567890123, -0.12345678901234567, 1.2345678901234567));
  Read fitted = readAll(line, TrajectoryLimits::forPoints(20000));
  ASSERT_FALSE(fitted.failed) << fitted.diags[0].message;
  // One point too many for the scene: refused at that point, not held.
  Read over = readAll(line, TrajectoryLimits::forPoints(19999));
  ASSERT_TRUE(over.failed);
  EXPECT_NE(over.diags[0].message.find("more than 19999 points"), std::string::npos) << over.diags[0].message;
  EXPECT_EQ(over.diags[0].column, static_cast<std::uint32_t>(line.find("[19999.") + 1));
  // forPoints scales the line limit: a scene of 10 particles takes no 2 MB line.
  Read small = readAll(line, TrajectoryLimits::forPoints(10));
  ASSERT_TRUE(small.failed);
  EXPECT_NE(small.diags[0].message.find("longer than"), std::string::npos) << small.diags[0].message;
  const std::string csv = "time,path,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,points\n0,/c,,,,,,,,,,,,,,0 0 0;1 1 1;2 2 2\n";
  Read csvOver = readAll(csv, TrajectoryLimits::forPoints(2));
  ASSERT_TRUE(csvOver.failed);
  EXPECT_NE(csvOver.diags[0].message.find("more than 2 points"), std::string::npos);
  EXPECT_EQ(csvOver.diags[0].column, static_cast<std::uint32_t>(csv.rfind("2 2 2") - csv.find('\n')));
}

struct ParticleScene {
  Scene scene;
  std::vector<std::shared_ptr<const Model>> models;
  ParticleScene() {
    scene.objects.resize(1);
    scene.objects[0].path = "/box";
    scene.deformables.resize(2);
    scene.deformables[0].path = "/cloth";
    scene.deformables[1].path = "/hidden";
    scene.granulars.resize(1);
    scene.granulars[0].path = "/sand";
  }
};

TEST(TrajectoryPoserPoints, ParticleLinesMoveTheirRecordsAndKeepTheRest) {
  ParticleScene s;
  ParticleCounts counts{{2, -1}, {1}};
  TrajectoryPoser poser(s.scene, s.models, counts);
  Read r = readAll(kBody + pointsLine(0, "/cloth", "[[0,0,1],[1,0,1]]") + pointsLine(0, "/hidden", "[[5,5,5]]") +
                   pointsLine(1, "/sand", "[[0,0,0.5]]"));
  ASSERT_EQ(r.frames.size(), 2u);
  BodyPoses poses = restPoses(s.scene, s.models);
  ParticlePositions particles;
  Diagnostics d;
  ASSERT_TRUE(poser.apply(r.frames[0], "t.jsonl", poses, d, &particles)) << d[0].message;
  EXPECT_EQ(poses.objects[0].position, Eigen::Vector3d(1, 2, 3));
  ASSERT_EQ(particles.deformables.size(), 2u);
  EXPECT_TRUE(particles.deformables[0].given);
  EXPECT_EQ(particles.deformables[0].points[1], Eigen::Vector3d(1, 0, 1));
  EXPECT_EQ(particles.deformables[1].points.size(), 1u);  // count unknown: taken as given
  EXPECT_TRUE(particles.granulars.empty());
  ASSERT_TRUE(poser.apply(r.frames[1], "t.jsonl", poses, d, &particles));
  ASSERT_EQ(particles.granulars.size(), 1u);
  EXPECT_EQ(particles.granulars[0].version, 1u);
  EXPECT_EQ(particles.granulars[0].points[0], Eigen::Vector3d(0, 0, 0.5));
  EXPECT_EQ(particles.deformables[0].version, 1u);  // left out of frame 1: where frame 0 put it
  EXPECT_EQ(particles.deformables[0].points[0], Eigen::Vector3d(0, 0, 1));
}

TEST(TrajectoryPoserPoints, ADeformablesFillParticlesFollowItsVertices) {
  // A volume (fem) filled with particles: its OBJ's vertices first, then
  // the fill; the line holds more points than the surface has vertices.
  ParticleScene s;
  TrajectoryPoser poser(s.scene, s.models, ParticleCounts{{2, -1}, {1}});
  Read r = readAll(pointsLine(0, "/cloth", "[[0,0,1],[1,0,1],[0.5,0,0.5]]"));
  BodyPoses poses = restPoses(s.scene, s.models);
  ParticlePositions particles;
  Diagnostics d;
  ASSERT_TRUE(poser.apply(r.frames[0], "t.jsonl", poses, d, &particles));
  EXPECT_EQ(particles.deformables[0].points.size(), 3u);
}

TEST(TrajectoryPoserPoints, WrongCountsAndKindsAreErrorsNamingTheRecord) {
  ParticleScene s;
  TrajectoryPoser poser(s.scene, s.models, ParticleCounts{{2, -1}, {1}});
  auto applyLine = [&](const std::string& line) {
    Read r = readAll(line);
    EXPECT_FALSE(r.failed) << r.diags[0].message;
    BodyPoses poses = restPoses(s.scene, s.models);
    ParticlePositions particles;
    Diagnostics d;
    EXPECT_FALSE(poser.apply(r.frames[0], "t.jsonl", poses, d, &particles));
    EXPECT_EQ(particles.deformables.size() + particles.granulars.size(), 0u);  // nothing moved
    return d;
  };
  std::string one = pointsLine(0, "/cloth", "[[0,0,1]]");
  Diagnostics d = applyLine(one);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].code, code::kTrajectoryTarget);
  EXPECT_EQ(d[0].column, static_cast<std::uint32_t>(one.find("\"points\"") + 1));
  EXPECT_EQ(d[0].message, "'/cloth' has 2 vertices (its OBJ's v lines), the line gives 1 points");
  d = applyLine(pointsLine(0, "/sand", "[[0,0,1],[0,0,2]]"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].message, "'/sand' has 1 particles, the line gives 2 points");
  d = applyLine(pointsLine(0, "/sand", "[]"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].message, "'/sand' has 1 particles, the line gives 0 points");
  d = applyLine(pointsLine(0, "/box", "[[0,0,0]]"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NE(d[0].message.find("'/box' is a body or robot"), std::string::npos) << d[0].message;
  d = applyLine("{\"time\":0,\"path\":\"/sand\",\"position\":[0,0,0],\"quaternion\":[1,0,0,0]}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].column, 18u);
  EXPECT_NE(d[0].message.find("granular record: its line gives points, not a pose"), std::string::npos);
  d = applyLine(pointsLine(0, "/ghost", "[]"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].message, "'/ghost' is no deformable or granular record of the scene");
}

}  // namespace
}  // namespace rscene::robot
