// The scene model's builder (buildScene, scene.hpp), one class whose jobs
// live in files of their own, as MuJoCo keeps its user model apart from its
// compiler: reading the whole-scene and resource records
// (scene_read_settings.cpp), the bodies and the records that hang on them
// (scene_read_bodies.cpp), robots and sensors (scene_read_robots.cpp), and
// the passes that resolve parents, frames, mounts and wire ends once every
// record is read (scene_resolve.cpp); scene.cpp drives them.  Internal to
// lib/scene: not installed for users of the library.
#pragma once
#include "scene/scene.hpp"

#include <algorithm>
#include <limits>
#include <cmath>
#include <tuple>
#include <unordered_map>
#include "core/codes.hpp"
#include "scene/limits.hpp"
#include "scene/reader.hpp"
#include "scene/visual_records_read.hpp"
#include "core/filesystem.hpp"
#include "core/text.hpp"

namespace rscene::scene_build {

// The last node of `nodes` whose id or path is `ref` (a child record
// belongs to the most recent parent of that name), or nullptr.
template <class Node>
Node* lastNamed(std::vector<Node>& nodes, const std::string& ref) {
  Node* found = nullptr;
  for (Node& n : nodes)
    if (n.id == ref || n.path == ref) found = &n;
  return found;
}

// Record kinds the view turns into structs; other node and child kinds are
// listed in Scene::skipped.
inline constexpr std::string_view kModelled[] = {"group",  "terrain_region", "terrain_splat_layer", "light",
                                          "camera", "object",         "compound",            "compound_child",
                                          "wire",   "instanced_visual", "point_cloud", "articulated",
                                          "articulated_ik", "sensor", "projected_decal", "local_fog",
                                          "irradiance_volume", "reflection_probe", "terrain_foliage_layer",
                                          "deformable", "granular"};

inline bool modelled(std::string_view tag) {
  return std::find(std::begin(kModelled), std::end(kModelled), tag) != std::end(kModelled);
}

// Record kinds SceneOptions::bodiesOnly builds: what checkScene() judges.
inline bool forBodies(std::string_view tag) {
  return tag == "time_step" || tag == "group" || tag == "object" || tag == "compound" || tag == "compound_child" ||
         tag == "terrain_region" || tag == "wire" || tag == "point_cloud" || tag == "articulated_resource" ||
         tag == "articulated" || tag == "articulated_ik" || tag == "deformable" || tag == "granular" || tag == "terrain_foliage_layer" ||
         tag == "instanced_visual";
}

inline Eigen::Quaterniond toQuat(const Eigen::Vector4d& wxyz) { return {wxyz[0], wxyz[1], wxyz[2], wxyz[3]}; }

class Builder {
 public:
  Builder(const Document& doc, const SceneOptions& opt, Scene& scene, Diagnostics& diags)
      : doc_(doc), opt_(opt), s_(scene), diags_(diags) {}

  void run();

 private:
  std::string asset(const std::string& path) const;

  // The id and path index of every node, built on the first lookup: a
  // bodiesOnly build of a scene without wires never needs it.
  void indexNodes() const;

  // Record index of a node named by id or by path, or -1.
  int lookup(const std::string& ref) const;
  void readSolver(const RecordReader& r, int idx);
  void readEnvironment(const RecordReader& r, int idx);
  void readWeather(const RecordReader& r, int idx);
  void readRenderSettings(const RecordReader& r, int idx);

  // Singleton records a scene may leave out hold every field's schema
  // default: read through a reader of an absent record, so that no struct
  // keeps a second copy of them.
  void absentSingletons();
  void readMaterial(const RecordReader& r, int idx) { s_.materials.push_back(material(r, idx)); }

  Material material(const RecordReader& r, int idx);
  void readContact(const RecordReader& r, int idx);
  void readTerrainTexture(const RecordReader& r, int idx);

  // What a terrain_texture record holds beside its slot and names.
  TerrainTexture terrainTexture(const RecordReader& r);
  void readGroup(const RecordReader& r, int idx);
  void readLight(const RecordReader& r, int idx);

  // A camera's image size.  A value past 32 bits is RS2003 (the reader's,
  // never a wrap: 4294967297 would be 1); one outside 0..16384 is
  // checkNumericLimits()'s RS7028; either way the size is left to the tool.
  static int pixelCount(const RecordReader& r, const char* name);
  void readCamera(const RecordReader& r, int idx);
  void readObject(const RecordReader& r, int idx);

  // Body mode of an object (compat-notes.md, "object record"): #21 when it
  // names a known mode, else #17 visualOnly / #19 locked (the 19-field
  // layout: #18 fixed), else dynamic; ground and half_space are static,
  // collidable=false is visual-only.
  static BodyMode objectMode(const RecordReader& r, const std::string& primitive, bool collidable);

  // bodiesOnly: whether an object certainly passes checkScene(), so that
  // building it can be skipped: visual-only by its written #21 or #22, or
  // a primitive other than a mesh whose mass, scale, radius and height are
  // all positive numbers, whatever its mode, and no inertiaDiagonal.
  // Anything less plain is built and checked in full.
  bool plainBody(const Record& rec);

  // Whether `s` is a short plain decimal ("0.5", "12") below 10^12 (so
  // within scene/limits.hpp's kMaxLength): finite, and its square neither
  // overflows nor underflows to zero unless it is zero.
  static bool plainDecimal(std::string_view s);

  // Whether `s` is a finite number in (0, max] (a normal double: 4.9e-324
  // is RS7020's).  Plain decimals below 10^12 ("0.5", "12") are read from
  // their digits, which keeps a bodiesOnly build cheap on scenes with
  // hundreds of thousands of objects; anything else is parsed.
  static bool positiveNumber(std::string_view s, double max);
  void readCompound(const RecordReader& r, int idx);
  void readCompoundChild(const RecordReader& r, int idx);

  // Parses a per-sample list: empty, or exactly `per * samples` numbers.
  bool sampleList(const RecordReader& r, std::string_view name, std::size_t samples, int per,
                  std::vector<double>& out);
  void readTerrain(const RecordReader& r, int idx);

  // A terrain as a body wires can name, without its samples (bodiesOnly).
  void readTerrainNode(const RecordReader& r, int idx);
  AssetPath assetFn() const;

  // A node of visual_records.hpp: its parent noted for resolveWorld().
  template <typename T>
  void node(std::vector<T>& into, T value) {
    parentOf_[value.recordIndex] = value.parentId;
    into.push_back(std::move(value));
  }

  void readFoliage(const RecordReader& r, int idx);
  void readSplat(const RecordReader& r, int idx);
  void readWire(const RecordReader& r, int idx);

  // A resource directory: like an asset path, but the candidate must be a
  // directory.
  std::string assetDirectory(const std::string& path) const;
  static std::vector<std::string> splitList(const std::string& text);

  // A child record (compound_child, terrain layer, articulated_ik) belongs
  // to the most recent parent of its name before it; with none, lib/core's
  // finding, in its words and at its place.
  static void orphan(const RecordReader& r, const std::string& parentTag);
  void readArticulatedResource(const RecordReader& r, int idx);
  void readSensor(const RecordReader& r, int idx);
  void readArticulated(const RecordReader& r, int idx);

  // Which of the fields a resource provides an articulated record wrote.
  struct Written {
    bool source = false, directory = false, modules = false, order = false, noParent = false, convexify = false;
  };
  void resolveArticulated();
  void readArticulatedIk(const RecordReader& r, int idx);
  void readInstanced(const RecordReader& r, int idx);
  void readPointCloud(const RecordReader& r, int idx);
  void defaults();

  // Local pose of a node that has one (object, compound, camera), or nullptr.
  const Pose* localPose(int idx) const;

  // Parent record of each node, or -1 (none, unresolved, or itself).
  // Resolved once so that the walks below cost one array read per step.
  void resolveParents();

  // Memoised resolution over the parent links, for any depth: each node's
  // value is computed once, by an explicit stack instead of recursion (a
  // million-deep chain must not overflow the call stack), so that resolving
  // every node costs time linear in the number of nodes.  `stops(n)` says
  // that node n's value does not depend on its parent's (its value is then
  // `root(n)`); otherwise it is `step(n, value of parent)`.  The nodes of a
  // parent cycle (lib/core reports it, RS3xxx) all get `cycle(members)`.
  template <typename T, typename Stops, typename Root, typename Step, typename Cycle>
  void resolveChains(std::vector<T>& value, Stops stops, Root root, Step step, Cycle cycle) {
    enum : unsigned char { kTodo, kOnStack, kDone };
    std::vector<unsigned char> state(doc_.records.size(), kTodo);
    value.assign(doc_.records.size(), T{});
    std::vector<int> stack;
    for (std::size_t start = 0; start < state.size(); ++start) {
      if (state[start] == kDone) continue;
      // Climb until a node whose value is known or needs no parent.
      int n = static_cast<int>(start);
      while (true) {
        state[static_cast<std::size_t>(n)] = kOnStack;
        stack.push_back(n);
        int parent = parentIdx_[static_cast<std::size_t>(n)];
        if (parent < 0 || stops(n)) {
          value[static_cast<std::size_t>(n)] = root(n);
          state[static_cast<std::size_t>(n)] = kDone;
          stack.pop_back();
          break;
        }
        if (state[static_cast<std::size_t>(parent)] == kDone) break;
        if (state[static_cast<std::size_t>(parent)] == kOnStack) {
          auto first = std::find(stack.begin(), stack.end(), parent);
          std::vector<int> members(first, stack.end());
          T v = cycle(members);
          for (int m : members) {
            value[static_cast<std::size_t>(m)] = v;
            state[static_cast<std::size_t>(m)] = kDone;
          }
          stack.erase(first, stack.end());
          break;
        }
        n = parent;
      }
      // Come back down: each node's parent is now done.
      for (auto it = stack.rbegin(); it != stack.rend(); ++it) {
        auto i = static_cast<std::size_t>(*it);
        value[i] = step(*it, value[static_cast<std::size_t>(parentIdx_[i])]);
        state[i] = kDone;
      }
      stack.clear();
    }
  }

  // The world pose of the frame each node's pose is written in: its
  // parent's world pose when the parent has a pose of its own; groups and
  // pose-less nodes are folders in the world frame.  In a cycle there is
  // no parent frame to inherit, so its members keep the world frame.
  void resolveFrames();

  // Whether a group with visible=false is among each node's ancestors (in
  // a cycle, every member is an ancestor of every other).
  void resolveHidden();

  // A parent cycle has no world pose to give its members: sim and render
  // refuse it with lib/core's code, at the record and field lib/core's
  // check names (both walk the records in order and report the node where
  // the walk comes back to itself).  validate's bodiesOnly build resolves
  // no world, so the finding is not doubled there.
  void reportCycle(int idx);
  Pose parentFrame(int idx) const { return frames_[static_cast<std::size_t>(idx)]; }

  // The body a record index is, as a Mount (World when it is none).
  Mount mountOf(int record) const;

  // A camera rides on the body its parentGroupId names; a sensor on its
  // parentObject (at parentLink on a robot).  An unknown name is lib/core's
  // RS3012 (validate) and leaves the sensor in the world.
  void resolveMounts();

  // The world pose of the frame a sensor's local pose is written in: its
  // mount body's (a robot's base: lib/robot's sensor rig places it on the
  // link), else its parent folder's.
  Pose mountFrame(const Mount& m, int record) const;
  bool hiddenByGroup(int idx) const { return hidden_[static_cast<std::size_t>(idx)] != 0; }

  void resolveWorld();
  // bodiesOnly: objects' world poses only (checkScene()'s ground rule,
  // scene/start_pose.hpp); a parent cycle is the full build's to report.
  void resolveBodyPoses();

  // visual_records.hpp nodes: carried by their parent's frame like a light.
  void resolveVisualRecords();

  // What each wire end names: the world, a body the simulator models, a
  // node it does not (an articulated system, a visual-only object ...), or
  // nothing (lib/core's validator reports that as RS3012).
  void resolveWires();
  const Document& doc_;
  const SceneOptions& opt_;
  Scene& s_;
  Diagnostics& diags_;
  mutable std::unordered_map<std::string, std::size_t> byId_, byPath_;
  mutable bool indexed_ = false;
  const KindDef* objectKind_ = Schema::get().kind("object");
  // Per object layout, the tokens of primitive, scale x3, radius, height,
  // mass, then bodyMode and collidable (-1 when the layout has none).
  std::unordered_map<const Layout*, std::vector<int>> plainSlots_;
  std::unordered_map<int, std::string> parentOf_;
  std::vector<Written> written_;  // per Scene::articulated entry
  std::unordered_map<int, const Pose*> poses_;
  std::vector<int> hiddenGroups_;  // record indices of groups with visible=false
  std::vector<int> parentIdx_;     // per record: its parent's record index, or -1
  std::vector<Pose> frames_;       // per record: the world pose of its parent frame
  std::vector<char> hidden_;       // per record: a hidden group is among its ancestors
};

}  // namespace rscene::scene_build
