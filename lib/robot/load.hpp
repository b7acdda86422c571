// Reading robot files into the model: URDF in RaiSim's dialect (urdf.cpp,
// tinyxml2) and MJCF compiled by MuJoCo's own compiler (mjcf.cpp).
//
// Diagnostics about the robot file carry Diagnostic::file (the URDF, the
// module or the MJCF file) and the line there where one is known; the
// library never prints.
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "core/codes.hpp"
#include "core/diagnostic.hpp"
#include "core/filesystem.hpp"
#include "robot/model.hpp"

namespace rscene::robot {

// Diagnostic codes of robot loading (registry: core/check_codes.cpp).
namespace code {
inline constexpr const char* kMissingFile = rs::RS5001;   // robot file or mesh that does not exist / is not a regular file
inline constexpr const char* kBadFile = rs::RS7030;       // robot file that does not parse (XML, MJCF compile error)
inline constexpr const char* kSkipped = rs::RS7031;       // element that cannot be used, skipped (warning)
inline constexpr const char* kBadModel = rs::RS7032;      // not a tree: no root, two roots, unknown link, cycle
inline constexpr const char* kNoModule = rs::RS7033;      // module file not found in RaiSim's search order
inline constexpr const char* kNoResource = rs::RS7034;    // articulated record with no robot file to load
inline constexpr const char* kBadNumber = rs::RS7035;     // mass, inertia, length or joint coefficient out of range
}  // namespace code

struct LoadOptions {
  // Directory for package:// paths and modules (the record's
  // resourceDirectory=, resolved); empty: the robot file's directory.
  std::string resourceDirectory;
  std::vector<std::string> modules;  // URDF fragments inserted before </robot>
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  std::size_t maxFileBytes = std::size_t{256} << 20;  // robot file size cap
  // --allow-missing-assets: a URDF collision mesh that is not found is a
  // warning and that <collision> is left out (as a visual mesh always is),
  // not an error.  MJCF files are compiled by MuJoCo, which needs them all.
  bool allowMissingMeshes = false;
  // Where URDF files, modules and sensor sets are read from (nullptr: the
  // disk), so tests can load a robot from memory.  MJCF files are read by
  // MuJoCo itself, from the disk.
  const FileSystem* files = nullptr;
  const FileSystem& fileSystem() const { return files ? *files : diskFileSystem(); }
};

// Reads `path` by its root element (<robot>: URDF, <mujoco>: MJCF), then
// scales it by options.scale.  Returns false after an error diagnostic;
// warnings do not fail.  loadUrdf and loadMjcf read the file as written
// (they do not scale).
bool loadModel(const std::string& path, const LoadOptions& options, Model& out, Diagnostics& diagnostics);
bool loadUrdf(const std::string& path, const LoadOptions& options, Model& out, Diagnostics& diagnostics);
bool loadMjcf(const std::string& path, const LoadOptions& options, Model& out, Diagnostics& diagnostics);

// Scales the model as if its every link frame were stretched by `scale`
// (x, y, z of the link frame): origins of joints, inertials, visuals and
// collisions scale per axis; shapes by how much each of their own axes
// grows (a box rotated 90 degrees about z takes sx for its y side);
// sphere radii by the cube root of sx*sy*sz, cylinder and capsule radii by
// the geometric mean of their two cross axes.  Density is kept: masses
// scale by sx*sy*sz and inertias as the same body stretched (exact for a
// uniform scale, where inertia grows by s^5).  Prismatic limits scale with
// the length of their axis; angles, damping and spring constants are
// unchanged.
void scaleModel(Model& model, const Eigen::Vector3d& scale);

// One load per distinct (file, resource directory, modules, scale) in a run:
// sixteen robots of one URDF read it once.  Diagnostics of a load are
// reported by the first request only (of each scene: see nextScene()).
class ModelCache {
 public:
  // The model, or nullptr when it did not load (diagnostics say why).
  std::shared_ptr<const Model> get(const std::string& path, const LoadOptions& options, Diagnostics& diagnostics);

  // A cache kept across the scenes of a batch (rscene-sim's): from now on
  // each model's load diagnostics are reported again, to its first request,
  // so every scene naming a broken or odd file says so, as it would alone.
  void nextScene() { ++scene_; }

 private:
  using Key = std::tuple<std::string, std::string, std::vector<std::string>, double, double, double, bool>;
  struct Entry {
    std::shared_ptr<const Model> model;
    Diagnostics diagnostics;  // of the load
    std::uint64_t reportedIn = 0;
  };
  std::map<Key, Entry> models_;
  std::uint64_t scene_ = 0;
};

}  // namespace rscene::robot
