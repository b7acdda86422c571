// MJCF specifics of robot loading (loadMjcf itself is declared in
// load.hpp): the diagnostic codes only the MJCF reader raises, and the
// conversion of a compiled MuJoCo model into the robot model, apart from
// the loading so that tests can convert a model they compiled themselves.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/codes.hpp"
#include "core/diagnostic.hpp"
#include "robot/model.hpp"

struct mjModel_;

namespace rscene::robot {

namespace code {
// MJCF the robot model cannot hold: a free joint below the top level or
// beside other joints, a second top-level body beside a floating base.
inline constexpr const char* kMjcfUnsupported = rs::RS7036;
// MJCF value that would make MuJoCo allocate past a cap (MjcfFiles::overCaps).
inline constexpr const char* kMjcfOverCap = rs::RS7053;
// MJCF element converted approximately (an ellipsoid geom as a sphere), or
// a warning of MuJoCo's compiler.
inline constexpr const char* kMjcfApproximated = rs::RS7037;
}  // namespace code

// Reads the compiled model `m` (compiled from `path`, named in
// diagnostics) into `out`.  Returns false after an error diagnostic.
//
// The coordinates are MuJoCo's qpos: a joint's value in the robot model is
// its qpos entry, including a joint's `ref` offset (the joint origin holds
// the offset), so a qpos logged in MuJoCo is a generalizedCoordinate here.
// `meshFiles` maps mesh names to their files (mjcfMeshFiles); a mesh geom
// whose mesh has none is skipped with a warning.
bool convertMjcf(const mjModel_& m, const std::string& path, const std::map<std::string, std::string>& meshFiles,
                 Model& out, Diagnostics& diagnostics);

// What an MJCF file names, read before MuJoCo reads it (mjcf_files.cpp).
struct MjcfFiles {
  struct Named {
    std::string path;  // resolved as MuJoCo resolves it
    std::string from;  // the XML file that names it
    int line = 0;
  };
  std::vector<Named> files;                    // includes and asset files (mesh, texture, hfield, skin)
  std::map<std::string, std::string> meshes;   // <asset><mesh file=> by mesh name
  std::string compositeFile;                   // the first <composite>, if any
  int compositeLine = 0;                       // 0: none
  bool tooDeep = false;                        // includes past the scan's depth or count cap
  // Values that would make MuJoCo allocate past the caps (RS7053), each
  // where it is written: <size> counts, height field and texture samples.
  struct OverCap {
    std::string file;
    int line = 0;
    std::string message;
  };
  std::vector<OverCap> overCaps;
};

// Scans the MJCF file `path` (a regular file the caller has checked) and
// its includes (tinyxml2; an include that is not a regular file of at most
// `maxFileBytes` is listed, not read).  MuJoCo 2.2.2 allocates what <size>
// asks for while it compiles (its mjData included: njmax x njmax dense),
// and a height field or texture as its sizes say, so these are capped
// before it reads anything (kMjcfSizeCaps; a PNG file's size is read from
// its header).
MjcfFiles scanMjcf(const std::string& path, std::uintmax_t maxFileBytes);

// Where the vertices of mesh `file` lie in the frame of MuJoCo's compiled
// copy of it (`count` float vertices x y z): compiled = frame * (scale *
// file vertex).  False with the reason when they cannot be matched.  Calls
// MuJoCo: the caller holds the MuJoCo lock (mjcf.cpp).
bool mjcfMeshFrame(const std::string& file, const float* vertices, int count, Pose& frame, Eigen::Vector3d& scale,
                   std::string& why);

}  // namespace rscene::robot
