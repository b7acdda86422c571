#include "scene/scene_builder.hpp"

#include <deque>

#include "scene/visual_records_read.hpp"

namespace rscene::scene_build {

const Pose* Builder::localPose(int idx) const {
  auto it = poses_.find(idx);
  return it == poses_.end() ? nullptr : it->second;
}

void Builder::resolveParents() {
  parentIdx_.assign(doc_.records.size(), -1);
  for (const auto& [idx, ref] : parentOf_) {
    int parent = lookup(ref);
    if (parent != idx) parentIdx_[static_cast<std::size_t>(idx)] = parent;
    else reportCycle(idx);  // its own parent: the shortest cycle
  }
}

void Builder::resolveFrames() {
  std::vector<Pose> frames;
  if (s_.inheritedTransforms) {
    auto stops = [&](int n) { return localPose(parentIdx_[static_cast<std::size_t>(n)]) == nullptr; };
    auto root = [](int) { return Pose{}; };
    auto step = [&](int n, const Pose& parentFrame) {
      return parentFrame * *localPose(parentIdx_[static_cast<std::size_t>(n)]);
    };
    auto cycle = [](const std::vector<int>&) { return Pose{}; };
    resolveChains(frames, stops, root, step, cycle);
  } else {
    frames.assign(doc_.records.size(), Pose{});
  }
  frames_ = std::move(frames);
}

void Builder::resolveHidden() {
  std::vector<char> hiddenGroup(doc_.records.size(), 0);
  for (int g : hiddenGroups_) hiddenGroup[static_cast<std::size_t>(g)] = 1;
  auto stops = [](int) { return false; };
  auto root = [](int) { return char{0}; };
  auto step = [&](int n, char parentHidden) {
    return static_cast<char>(parentHidden || hiddenGroup[static_cast<std::size_t>(parentIdx_[static_cast<std::size_t>(n)])]);
  };
  auto cycle = [&](const std::vector<int>& members) {
    reportCycle(members.front());
    return static_cast<char>(std::any_of(members.begin(), members.end(),
                                         [&](int m) { return hiddenGroup[static_cast<std::size_t>(m)] != 0; }));
  };
  resolveChains(hidden_, stops, root, step, cycle);
}

void Builder::reportCycle(int idx) {
  RecordReader r(doc_, static_cast<std::size_t>(idx), diags_);
  const std::string& tag = doc_.records[static_cast<std::size_t>(idx)].kind->tag;
  const char* field = tag == "group" ? "parentId" : "parentGroupId";
  if (!r.has(field)) field = "parentGroupId";
  r.error(field, rs::RS3017, "node '" + nodePath(doc_, r.record()) + "' is its own ancestor",
          "break the cycle of parents");
}

Mount Builder::mountOf(int record) const {
  Mount m;
  auto find = [&](const auto& list, Mount::Kind kind) {
    for (std::size_t i = 0; i < list.size(); ++i)
      if (list[i].recordIndex == record) {
        m.kind = kind;
        m.index = static_cast<int>(i);
        return true;
      }
    return false;
  };
  if (record >= 0) find(s_.objects, Mount::Kind::Object) || find(s_.compounds, Mount::Kind::Compound) ||
                       find(s_.articulated, Mount::Kind::Articulated);
  return m;
}

void Builder::resolveMounts() {
  for (Camera& c : s_.cameras) c.mount = mountOf(parentIdx_[static_cast<std::size_t>(c.recordIndex)]);
  for (Sensor& v : s_.sensors) {
    v.mount = mountOf(lookup(v.parentObject));
    if (v.mount.kind == Mount::Kind::Articulated) v.mount.link = v.parentLink;
  }
}

Pose Builder::mountFrame(const Mount& m, int record) const {
  switch (m.kind) {
    case Mount::Kind::Object: return s_.objects[static_cast<std::size_t>(m.index)].world;
    case Mount::Kind::Compound: return s_.compounds[static_cast<std::size_t>(m.index)].world;
    case Mount::Kind::Articulated: return s_.articulated[static_cast<std::size_t>(m.index)].world;
    case Mount::Kind::World: break;
  }
  return parentFrame(record);
}

void Builder::resolveBodyPoses() {
  for (const Object& o : s_.objects) poses_[o.recordIndex] = &o.local;
  for (const Compound& c : s_.compounds) poses_[c.recordIndex] = &c.local;
  for (const Camera& c : s_.cameras) poses_[c.recordIndex] = &c.local;
  for (const Articulated& a : s_.articulated) poses_[a.recordIndex] = &a.local;
  // A plain static body the build left out may be a parent: its pose (and
  // its own parent) are read here, up the chain.
  std::deque<Pose> skipped;
  const std::size_t before = diags_.size();
  for (bool grown = true; grown;) {
    grown = false;
    resolveParents();
    for (int p : std::vector<int>(parentIdx_)) {
      if (p < 0 || poses_.count(p) || doc_.records[static_cast<std::size_t>(p)].kind != objectKind_) continue;
      RecordReader r(doc_, static_cast<std::size_t>(p), diags_);
      skipped.push_back(readPose(r, "position", "orientation"));
      poses_[p] = &skipped.back();
      parentOf_[p] = r.str("parentGroupId");
      grown = true;
    }
  }
  resolveFrames();
  diags_.resize(before);  // a cycle, a bad number: lib/core's to report in validate
  for (Object& o : s_.objects) o.world = parentFrame(o.recordIndex) * o.local;
  for (Compound& c : s_.compounds) c.world = parentFrame(c.recordIndex) * c.local;  // RS7015 (start_pose.hpp)
}

void Builder::resolveWorld() {
  for (const Object& o : s_.objects) poses_[o.recordIndex] = &o.local;
  for (const Compound& c : s_.compounds) poses_[c.recordIndex] = &c.local;
  for (const Camera& c : s_.cameras) poses_[c.recordIndex] = &c.local;
  for (const Articulated& a : s_.articulated) poses_[a.recordIndex] = &a.local;
  resolveParents();
  resolveFrames();
  resolveHidden();
  for (Object& o : s_.objects) o.world = parentFrame(o.recordIndex) * o.local;
  for (Compound& c : s_.compounds) c.world = parentFrame(c.recordIndex) * c.local;
  resolveMounts();
  for (Camera& c : s_.cameras) c.world = parentFrame(c.recordIndex) * c.local;
  for (Articulated& a : s_.articulated) {
    a.world = parentFrame(a.recordIndex) * a.local;
    a.hiddenByGroup = hiddenByGroup(a.recordIndex);
  }
  for (Sensor& v : s_.sensors) v.world = mountFrame(v.mount, v.recordIndex) * v.local;
  for (Object& o : s_.objects) o.hiddenByGroup = hiddenByGroup(o.recordIndex);
  for (Compound& c : s_.compounds) c.hiddenByGroup = hiddenByGroup(c.recordIndex);
  for (Terrain& t : s_.terrains) t.hiddenByGroup = hiddenByGroup(t.recordIndex);
  for (InstancedVisual& v : s_.instancedVisuals) v.hiddenByGroup = hiddenByGroup(v.recordIndex);
  for (PointCloud& p : s_.pointClouds) p.hiddenByGroup = hiddenByGroup(p.recordIndex);
  resolveVisualRecords();
  for (Light& l : s_.lights) {
    l.hiddenByGroup = hiddenByGroup(l.recordIndex);
    Pose f = parentFrame(l.recordIndex);
    l.position = f.position + f.orientation * l.position;
    l.direction = f.orientation * l.direction;
  }
}

void Builder::resolveVisualRecords() {
  auto placed = [&](auto& v) {
    v.world = parentFrame(v.recordIndex) * v.local;
    v.hiddenByGroup = hiddenByGroup(v.recordIndex);
  };
  for (Decal& d : s_.decals) placed(d);
  for (IrradianceVolume& v : s_.irradianceVolumes) placed(v);
  for (Deformable& d : s_.deformables) placed(d);
  for (Granular& g : s_.granulars) placed(g);
  for (LocalFog& f : s_.localFogs) {
    Pose p = parentFrame(f.recordIndex);
    f.center = p.position + p.orientation * f.localCenter;
    f.hiddenByGroup = hiddenByGroup(f.recordIndex);
  }
  for (ReflectionProbe& pr : s_.reflectionProbes) {
    Pose p = parentFrame(pr.recordIndex);
    pr.position = p.position + p.orientation * pr.localPosition;
    pr.hiddenByGroup = hiddenByGroup(pr.recordIndex);
  }
}

void Builder::resolveWires() {
  std::unordered_map<int, bool> simulatedBody;
  for (const Object& o : s_.objects) simulatedBody[o.recordIndex] = o.bodyMode != BodyMode::VisualOnly;
  for (const Compound& c : s_.compounds) simulatedBody[c.recordIndex] = c.bodyMode != BodyMode::VisualOnly;
  for (const Terrain& t : s_.terrains) simulatedBody[t.recordIndex] = true;
  std::unordered_map<int, bool> robot;
  for (const Articulated& a : s_.articulated) robot[a.recordIndex] = true;
  auto classify = [&](const std::string& ref, WireEnd& end, std::string& tag, int& record) {
    if (ref.empty()) return;
    int target = lookup(ref);
    record = target;
    if (target < 0) {
      end = WireEnd::Unknown;
      return;
    }
    tag = doc_.records[static_cast<std::size_t>(target)].kind->tag;
    if (robot.count(target)) {
      end = WireEnd::Articulated;
      return;
    }
    auto it = simulatedBody.find(target);
    if (it == simulatedBody.end() && tag == "object") {  // skipped by a bodiesOnly build
      RecordReader r(doc_, static_cast<std::size_t>(target), diags_);
      bool simulated = objectMode(r, r.name("primitive"), r.flag("collidable")) != BodyMode::VisualOnly;
      it = simulatedBody.emplace(target, simulated).first;
    }
    end = it != simulatedBody.end() && it->second ? WireEnd::Body : WireEnd::NotSimulated;
  };
  for (Wire& w : s_.wires) {
    classify(w.bodyA, w.endA, w.tagA, w.recordA);
    classify(w.bodyB, w.endB, w.tagB, w.recordB);
  }
}

}  // namespace rscene::scene_build
