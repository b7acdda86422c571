// Joins the links and joints a URDF declares into the model's tree and
// checks that it is one: RaiSim builds its articulated system from the
// single root down, so anything else cannot be simulated.
#include <unordered_map>

#include "robot/load.hpp"
#include "robot/urdf_reader.hpp"
#include "robot/xml_file.hpp"

namespace rscene::robot::urdf {
namespace {

class TreeBuilder {
 public:
  TreeBuilder(const std::string& sourceFile, Diagnostics& diagnostics)
      : sourceFile_(sourceFile), diagnostics_(diagnostics) {}

  bool build(std::vector<Link> links, std::vector<RawJoint> joints, Model& out);

 private:
  const std::string& fileOf(const std::string& file) const { return file.empty() ? sourceFile_ : file; }
  void error(const std::string& file, int line, std::string message) {
    diagnostics_.push_back(robotDiagnostic(Severity::Error, code::kBadModel, fileOf(file), line, std::move(message)));
    ok_ = false;
  }
  std::string where(const std::string& file, int line) const {
    std::string at = "line " + std::to_string(line);
    return file.empty() ? at : at + " of " + file;
  }
  bool liftFloatingBase(std::vector<Link>& links, std::vector<RawJoint>& joints, bool& floating);

  const std::string& sourceFile_;
  Diagnostics& diagnostics_;
  bool ok_ = true;
};

// A floating joint from `world` to the base says what a URDF without
// `world` says: the base moves freely.  RaiSim allows it nowhere else, and
// neither do we (the model has no joint type for a 6-dof joint inside the
// tree), so any other floating joint is an error.
bool TreeBuilder::liftFloatingBase(std::vector<Link>& links, std::vector<RawJoint>& joints, bool& floating) {
  floating = false;
  int lifted = -1;
  int worldChildren = 0;
  bool worldIsChild = false;
  for (const RawJoint& k : joints) {
    if (k.parent == "world") ++worldChildren;
    if (k.child == "world") worldIsChild = true;
  }
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const RawJoint& j = joints[i];
    if (!j.floating) continue;
    if (j.parent == "world" && lifted < 0 && worldChildren == 1 && !worldIsChild) {
      lifted = static_cast<int>(i);
      continue;
    }
    error(j.joint.file, j.joint.line,
          "floating joint '" + j.joint.name + "' from '" + j.parent + "' to '" + j.child +
              "': RaiSim allows a floating joint only as the only joint of the root link `world`");
  }
  if (!ok_) return false;
  if (lifted < 0) return true;
  joints.erase(joints.begin() + lifted);
  for (std::size_t i = 0; i < links.size(); ++i)
    if (links[i].name == "world") {
      links.erase(links.begin() + static_cast<std::ptrdiff_t>(i));
      break;
    }
  floating = true;
  return true;
}

bool TreeBuilder::build(std::vector<Link> links, std::vector<RawJoint> joints, Model& out) {
  bool liftedFloating = false;
  if (!liftFloatingBase(links, joints, liftedFloating)) return false;
  if (links.empty()) {
    error("", 0, "robot has no links");
    return false;
  }
  std::unordered_map<std::string, int> linkIndex;
  for (std::size_t i = 0; i < links.size(); ++i) {
    auto [it, fresh] = linkIndex.emplace(links[i].name, static_cast<int>(i));
    if (!fresh) {
      const Link& first = links[static_cast<std::size_t>(it->second)];
      error(links[i].file, links[i].line,
            "link '" + links[i].name + "' declared twice (first at " + where(first.file, first.line) + ")");
    }
  }
  // Where each joint name was first declared (whether or not that joint
  // made it into the tree).
  std::unordered_map<std::string, std::pair<std::string, int>> declared;
  out.joints.clear();
  for (RawJoint& raw : joints) {
    Joint& j = raw.joint;
    auto [it, fresh] = declared.emplace(j.name, std::pair{j.file, j.line});
    if (!fresh) {
      error(j.file, j.line,
            "joint '" + j.name + "' declared twice (first at " + where(it->second.first, it->second.second) + ")");
      continue;
    }
    auto parent = linkIndex.find(raw.parent);
    auto child = linkIndex.find(raw.child);
    if (parent == linkIndex.end())
      error(j.file, j.line, "joint '" + j.name + "' names parent link '" + raw.parent + "' that does not exist");
    if (child == linkIndex.end())
      error(j.file, j.line, "joint '" + j.name + "' names child link '" + raw.child + "' that does not exist");
    if (parent == linkIndex.end() || child == linkIndex.end()) continue;
    if (parent->second == child->second) {
      error(j.file, j.line, "joint '" + j.name + "' joins link '" + raw.child + "' to itself");
      continue;
    }
    Link& childLink = links[static_cast<std::size_t>(child->second)];
    if (childLink.parentJoint >= 0) {
      const Joint& other = out.joints[static_cast<std::size_t>(childLink.parentJoint)];
      error(j.file, j.line,
            "link '" + raw.child + "' has two parent joints: '" + other.name + "' (" + where(other.file, other.line) +
                ") and '" + j.name + "'");
      continue;
    }
    j.parentLink = parent->second;
    j.childLink = child->second;
    int index = static_cast<int>(out.joints.size());
    childLink.parentJoint = index;
    links[static_cast<std::size_t>(parent->second)].childJoints.push_back(index);
    out.joints.push_back(std::move(j));
  }
  if (!ok_) return false;

  std::vector<int> roots;
  for (std::size_t i = 0; i < links.size(); ++i)
    if (links[i].parentJoint < 0) roots.push_back(static_cast<int>(i));
  if (roots.empty()) {
    const Joint& j = out.joints.front();
    error(j.file, j.line, "robot has no root link: every link has a parent joint, so the joints form a cycle");
    return false;
  }
  if (roots.size() > 1) {
    const Link& a = links[static_cast<std::size_t>(roots[0])];
    const Link& b = links[static_cast<std::size_t>(roots[1])];
    error(b.file, b.line,
          "robot has two root links, '" + a.name + "' (" + where(a.file, a.line) + ") and '" + b.name +
              "': every link but the root needs a parent joint");
    return false;
  }
  // With one root and one parent per link, a link the root does not reach
  // lies on a cycle of joints.
  std::vector<char> reached(links.size(), 0);
  std::vector<int> stack{roots[0]};
  while (!stack.empty()) {
    int l = stack.back();
    stack.pop_back();
    if (reached[static_cast<std::size_t>(l)]) continue;
    reached[static_cast<std::size_t>(l)] = 1;
    for (int j : links[static_cast<std::size_t>(l)].childJoints)
      stack.push_back(out.joints[static_cast<std::size_t>(j)].childLink);
  }
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (reached[i]) continue;
    const Joint& j = out.joints[static_cast<std::size_t>(links[i].parentJoint)];
    error(j.file, j.line,
          "joint '" + j.name + "' closes a cycle: link '" + links[i].name + "' cannot be reached from the root '" +
              links[static_cast<std::size_t>(roots[0])].name + "'");
    return false;
  }

  out.links = std::move(links);
  out.root = roots[0];
  Link& root = out.links[static_cast<std::size_t>(out.root)];
  // RaiSim: a root named `world` fixes the base; the world link itself has
  // no mass (it is the ground the robot is bolted to).
  out.floatingBase = liftedFloating || root.name != "world";
  if (root.name == "world") root.inertial = Inertial{};
  return true;
}

}  // namespace

bool buildTree(const std::string& sourceFile, std::vector<Link> links, std::vector<RawJoint> joints, Model& out,
               Diagnostics& diagnostics) {
  TreeBuilder builder(sourceFile, diagnostics);
  return builder.build(std::move(links), std::move(joints), out);
}

}  // namespace rscene::robot::urdf
