// URDF in RaiSim's dialect (ArticulatedSystem.rst, "URDF convention").
//
// Why tinyxml2 and not urdfdom: the standard reader rejects what RaiSim
// adds to URDF (`capsule` geometry, `spherical` joints, the `rotor_inertia`,
// `spring_mount` and `stiffness` attributes of <dynamics>) and stops at
// the first thing it does not like, while robots found in the wild carry
// gazebo plugins, transmissions and xacro leftovers that RaiSim loads past.
// Reading the XML ourselves keeps every element's line (for messages that
// point into the file) and lets us skip what cannot be used with a
// warning instead of refusing the robot.
//
// What is skipped with an RS7031 warning (the robot still loads): <gazebo>,
// <transmission>, <constraints> and other unknown top-level elements; a
// <limit> whose lower bound is above its upper (the limits are dropped); a
// visual, collision or inertial whose numbers hold an unexpanded xacro
// `${...}`/`$(...)` or a RaiSim template `@@X` (for a joint, the <origin>,
// <axis>, <limit> or <dynamics> holding it); unknown or degenerate
// geometry; <mimic>; a visual mesh or material texture that cannot be
// found (RaiSim itself never reads visual meshes, so a robot whose
// visuals are missing still simulates; render draws what is left).
// A collision mesh that cannot be found is an RS5001 error: the robot
// would not collide as written.  Unknown elements inside a link or joint
// (<self_filter>, <calibration>, <safety_controller>) are ignored silently,
// as every URDF reader does.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <list>
#include <map>
#include <optional>
#include <set>

#include "robot/load.hpp"
#include "robot/robot_paths.hpp"
#include "robot/sensor_set.hpp"
#include "robot/urdf_reader.hpp"
#include "robot/xml_file.hpp"

namespace rscene::robot {
namespace {

using tinyxml2::XMLElement;
using urdf::RawJoint;

// Where an element was written: the URDF or one of its modules.
struct Source {
  std::string file;       // as diagnostics name it
  std::string directory;  // relative mesh paths resolve against it
  bool isModule = false;
};

struct Material {
  std::optional<Eigen::Vector4d> color;
  std::string texture;  // as written
  int line = 0;
  const Source* source = nullptr;
};

enum class Read { Ok, Absent, Skip, Fail };

// A value quoted in a message, cut short: an attribute can be megabytes.
std::string shown(const char* text) {
  std::string_view v(text);
  constexpr std::size_t kMax = 60;
  return v.size() <= kMax ? std::string(v) : std::string(v.substr(0, kMax)) + "...";
}

class UrdfReader {
 public:
  UrdfReader(const std::string& path, const LoadOptions& options, Diagnostics& diagnostics)
      : options_(options), diagnostics_(diagnostics) {
    paths_.resourceDirectory = options.resourceDirectory;
    paths_.robotDirectory = parentDirectory(path);
    // RaiSim loads a URDF with modules from the file it writes into the
    // resource directory, so that is where its sensor sets are looked for.
    sensorDirectory_ = !options.modules.empty() && !options.resourceDirectory.empty() ? options.resourceDirectory
                                                                                       : paths_.robotDirectory;
  }

  // Reads the URDF `doc` (the file `path`) and its modules into `out`.
  bool read(const std::string& path, const tinyxml2::XMLDocument& doc, Model& out);

 private:
  // Diagnostics ------------------------------------------------------------
  void report(Severity s, const char* code, const Source& src, const XMLElement* e, std::string message) {
    diagnostics_.push_back(robotDiagnostic(s, code, src.file, e ? e->GetLineNum() : 0, std::move(message)));
    if (s == Severity::Error) ok_ = false;
  }
  void warn(const Source& src, const XMLElement* e, std::string message) {
    report(Severity::Warning, code::kSkipped, src, e, std::move(message));
  }
  void fail(const Source& src, const XMLElement* e, std::string message) {
    report(Severity::Error, code::kBadFile, src, e, std::move(message));
  }

  // Values -----------------------------------------------------------------
  // <color rgba>: four numbers in 0..1; one outside (a colour written in
  // 0..255) is clamped, with a warning (RS7055).
  template <class Color>
  void color(const Source& src, const XMLElement* c, Color& out) {
    std::vector<double> rgba;
    if (numbers(src, c, "rgba", 4, 4, rgba, "the color is not used") != Read::Ok) return;
    bool outside = false;
    for (double& x : rgba)
      if (x < 0 || x > 1) {
        outside = true;
        x = std::clamp(x, 0.0, 1.0);
      }
    if (outside)
      report(Severity::Warning, rs::RS7055, src, c,
             std::string("<color rgba=\"") + c->Attribute("rgba") +
                 "\"> has a component outside 0..1 (a colour in 0..255?); it is clamped to 0..1");
    out = Eigen::Vector4d(rgba[0], rgba[1], rgba[2], rgba[3]);
  }
  Read numbers(const Source& src, const XMLElement* e, const char* attr, std::size_t minCount, std::size_t maxCount,
               std::vector<double>& out, const std::string& skipping);
  Read number(const Source& src, const XMLElement* e, const char* attr, double& out, const std::string& skipping);
  Read origin(const Source& src, const XMLElement* parent, Pose& out, const std::string& skipping);

  // Elements ---------------------------------------------------------------
  void readMaterial(const Source& src, const XMLElement* e);
  void readLink(const Source& src, const XMLElement* e);
  void readLinkElements(const Source& src, const XMLElement* e, Link& link);
  void readSensorSet(const Source& src, const XMLElement* e, Link& link);
  bool readInertial(const Source& src, const XMLElement* e, Inertial& out);
  bool readGeometry(const Source& src, const XMLElement* owner, const char* what, Geometry& g);
  void readVisualMaterial(const Source& src, const XMLElement* e, Visual& v);
  void readJoint(const Source& src, const XMLElement* e);
  void readJointParts(const Source& src, const XMLElement* e, Joint& j);
  void readTopLevel(const Source& src, const XMLElement* first);
  bool loadModules(const std::string& path, std::list<std::pair<Source, tinyxml2::XMLDocument>>& modules);
  std::string resolve(const Source& src, const std::string& uri) const {
    return resolveRobotFile(paths_, src.directory, uri);
  }

  const LoadOptions& options_;
  Diagnostics& diagnostics_;
  RobotPaths paths_;
  bool ok_ = true;
  std::map<std::string, Material> materials_;
  std::vector<Link> links_;
  std::vector<RawJoint> joints_;
  std::string sensorDirectory_;
  std::list<Source> sensorSources_;  // a list: elements read from a set point at their Source
  std::vector<SensorDef> sensors_;   // of every set, in link order; `link` set after the tree is built
  std::set<std::string> setFindings_;  // file:line:message said about a sensor set file
};

Read UrdfReader::numbers(const Source& src, const XMLElement* e, const char* attr, std::size_t minCount,
                         std::size_t maxCount, std::vector<double>& out, const std::string& skipping) {
  const char* text = e->Attribute(attr);
  if (!text) return Read::Absent;
  std::string tag = std::string("<") + e->Name() + " " + attr + ">";
  if (looksLikeTemplate(text)) {
    warn(src, e, tag + " holds an unexpanded xacro or template expression '" + shown(text) + "'; " + skipping);
    return Read::Skip;
  }
  if (!parseXmlNumbers(text, out) || out.size() < minCount || out.size() > maxCount) {
    std::string want = std::to_string(minCount);
    if (maxCount != minCount) want += " to " + std::to_string(maxCount);
    want += maxCount == 1 ? " finite number" : " finite numbers";
    fail(src, e, tag + " is '" + shown(text) + "', not " + want);
    return Read::Fail;
  }
  return Read::Ok;
}

Read UrdfReader::number(const Source& src, const XMLElement* e, const char* attr, double& out,
                        const std::string& skipping) {
  std::vector<double> v;
  Read r = numbers(src, e, attr, 1, 1, v, skipping);
  if (r == Read::Ok) out = v[0];
  return r;
}

// An <origin xyz rpy> child of `parent`; absent = identity.
Read UrdfReader::origin(const Source& src, const XMLElement* parent, Pose& out, const std::string& skipping) {
  out = Pose{};
  const XMLElement* e = parent->FirstChildElement("origin");
  if (!e) return Read::Absent;
  std::vector<double> xyz, rpy;
  Read a = numbers(src, e, "xyz", 3, 3, xyz, skipping);
  if (a == Read::Skip || a == Read::Fail) return a;
  Read b = numbers(src, e, "rpy", 3, 3, rpy, skipping);
  if (b == Read::Skip || b == Read::Fail) return b;
  if (a == Read::Ok) out.position = {xyz[0], xyz[1], xyz[2]};
  if (b == Read::Ok) out.orientation = rpyToQuaternion(rpy[0], rpy[1], rpy[2]);
  return Read::Ok;
}

void UrdfReader::readMaterial(const Source& src, const XMLElement* e) {
  const char* name = e->Attribute("name");
  if (!name) {
    warn(src, e, "<material> without a name skipped");
    return;
  }
  Material m;
  m.line = e->GetLineNum();
  m.source = &src;
  if (const XMLElement* c = e->FirstChildElement("color")) {
    color(src, c, m.color);
  }
  if (const XMLElement* t = e->FirstChildElement("texture"))
    if (const char* file = t->Attribute("filename")) m.texture = file;
  materials_[name] = m;
}

bool UrdfReader::readInertial(const Source& src, const XMLElement* e, Inertial& out) {
  const std::string skipping = "the link's <inertial> is skipped (no mass)";
  Inertial in;
  Read r = origin(src, e, in.origin, skipping);
  if (r == Read::Skip || r == Read::Fail) return false;
  if (const XMLElement* m = e->FirstChildElement("mass")) {
    r = number(src, m, "value", in.mass, skipping);
    if (r == Read::Skip || r == Read::Fail) return false;
    if (in.mass < 0) {
      fail(src, m, "negative mass " + std::to_string(in.mass));
      return false;
    }
  }
  if (const XMLElement* i = e->FirstChildElement("inertia")) {
    static const char* const kNames[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
    double v[6] = {0, 0, 0, 0, 0, 0};
    for (int k = 0; k < 6; ++k) {
      r = number(src, i, kNames[k], v[k], skipping);
      if (r == Read::Skip || r == Read::Fail) return false;
    }
    in.inertia << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
  }
  out = in;
  return true;
}

// The <geometry> of a <visual> or <collision>; false when the element is
// skipped (a warning or an error says why).
bool UrdfReader::readGeometry(const Source& src, const XMLElement* owner, const char* what, Geometry& g) {
  const std::string skipping = std::string("the <") + what + "> is skipped";
  const XMLElement* geometry = owner->FirstChildElement("geometry");
  const XMLElement* shape = geometry ? geometry->FirstChildElement() : nullptr;
  if (!shape) {
    warn(src, owner, std::string("<") + what + "> without a <geometry> shape skipped");
    return false;
  }
  std::string kind = shape->Name();
  auto positive = [&](double v, const char* attr) {
    if (v > 0) return true;
    warn(src, shape, "<" + kind + " " + attr + "> is not positive; " + skipping);
    return false;
  };
  auto required = [&](Read r, const char* attr) {
    if (r == Read::Absent) warn(src, shape, "<" + kind + "> without " + attr + "; " + skipping);
    return r == Read::Ok;
  };
  if (kind == "box") {
    std::vector<double> size;
    g.kind = GeometryKind::Box;
    if (!required(numbers(src, shape, "size", 3, 3, size, skipping), "size")) return false;
    g.size = {size[0], size[1], size[2]};
    return positive(g.size.minCoeff(), "size");
  }
  if (kind == "sphere") {
    g.kind = GeometryKind::Sphere;
    return required(number(src, shape, "radius", g.radius, skipping), "radius") && positive(g.radius, "radius");
  }
  if (kind == "cylinder" || kind == "capsule") {
    g.kind = kind == "cylinder" ? GeometryKind::Cylinder : GeometryKind::Capsule;
    if (!required(number(src, shape, "radius", g.radius, skipping), "radius") || !positive(g.radius, "radius"))
      return false;
    // RaiSim's capsule says `height` (the distance between the centres of
    // its spheres); URDFs written for other tools say `length`.
    const char* lengthAttr = kind == "capsule" && shape->Attribute("height") ? "height" : "length";
    if (!required(number(src, shape, lengthAttr, g.length, skipping), lengthAttr)) return false;
    if (g.length < 0 || (g.kind == GeometryKind::Cylinder && g.length == 0)) return positive(g.length, lengthAttr);
    return true;
  }
  if (kind == "mesh") {
    g.kind = GeometryKind::Mesh;
    const char* file = shape->Attribute("filename");
    if (!file || !*file) {
      warn(src, shape, "<mesh> without a filename; " + skipping);
      return false;
    }
    if (looksLikeTemplate(file)) {
      warn(src, shape,
           "<mesh filename> holds an unexpanded xacro or template expression '" + shown(file) + "'; " + skipping);
      return false;
    }
    std::vector<double> scale;
    Read r = numbers(src, shape, "scale", 1, 3, scale, skipping);
    if (r == Read::Skip || r == Read::Fail) return false;
    if (r == Read::Ok && scale.size() == 2) {
      fail(src, shape, "<mesh scale> takes 1 or 3 numbers, not 2");
      return false;
    }
    if (r == Read::Ok) g.meshScale = scale.size() == 1 ? Eigen::Vector3d::Constant(scale[0])
                                                         : Eigen::Vector3d(scale[0], scale[1], scale[2]);
    g.meshPath = resolve(src, file);
    if (g.meshPath.empty()) {
      if (std::string(what) == "collision")
        report(options_.allowMissingMeshes ? Severity::Warning : Severity::Error, code::kMissingFile, src, shape,
               "collision mesh '" + std::string(file) + "' not found (paths relative to the URDF, package:// " +
                   "against the resource directory and the URDF's parent directories)" +
                   (options_.allowMissingMeshes ? "; " + skipping + " (--allow-missing-assets)" : std::string()));
      else
        warn(src, shape, "visual mesh '" + std::string(file) + "' not found; " + skipping);
      return false;
    }
    return true;
  }
  warn(src, shape, "unknown geometry <" + kind + ">; " + skipping);
  return false;
}

void UrdfReader::readVisualMaterial(const Source& src, const XMLElement* e, Visual& v) {
  const XMLElement* m = e->FirstChildElement("material");
  if (!m) return;
  if (const char* name = m->Attribute("name")) v.materialName = name;
  std::string texture;
  const Source* textureSource = &src;
  int textureLine = m->GetLineNum();
  // An inline <color>/<texture> wins; otherwise the top-level material of
  // that name.  A name with neither (ANYmal's "orange") keeps the mesh's or
  // the renderer's default colour, as rviz does.
  if (const XMLElement* c = m->FirstChildElement("color")) {
    color(src, c, v.color);
  }
  if (const XMLElement* t = m->FirstChildElement("texture"))
    if (const char* file = t->Attribute("filename")) texture = file;
  auto named = materials_.find(v.materialName);
  if (named != materials_.end()) {
    if (!v.color) v.color = named->second.color;
    if (texture.empty() && !named->second.texture.empty()) {
      texture = named->second.texture;
      textureSource = named->second.source;
      textureLine = named->second.line;
    }
  }
  if (!texture.empty()) {
    v.texture = resolve(*textureSource, texture);
    if (v.texture.empty())
      diagnostics_.push_back(robotDiagnostic(Severity::Warning, code::kSkipped, textureSource->file, textureLine,
                                             "material texture '" + texture + "' not found; drawn without it"));
  }
}

void UrdfReader::readLink(const Source& src, const XMLElement* e) {
  Link link;
  link.line = e->GetLineNum();
  if (src.isModule) link.file = src.file;
  const char* name = e->Attribute("name");
  if (!name || !*name) {
    fail(src, e, "<link> without a name");
    return;
  }
  link.name = name;
  readLinkElements(src, e, link);
  if (const char* sensor = e->Attribute("sensor"); sensor && *sensor) {
    link.sensorSet = sensor;
    readSensorSet(src, e, link);
  } else if (sensor) {
    report(Severity::Warning, code::kSensorSkipped, src, e,
           "link '" + link.name + "' has an empty sensor attribute; no sensor set");
  }
  links_.push_back(std::move(link));
}

// The <inertial>, <visual> and <collision> elements of a URDF <link> or
// of a sensor set's <link> (its first <inertial> only, as every URDF reader).
void UrdfReader::readLinkElements(const Source& src, const XMLElement* e, Link& link) {
  bool haveInertial = false;
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    std::string tag = c->Name();
    if (tag == "inertial" && !haveInertial) {
      haveInertial = readInertial(src, c, link.inertial);
    } else if (tag == "visual") {
      Visual v;
      v.line = c->GetLineNum();
      if (const char* n = c->Attribute("name")) v.name = n;
      Read r = origin(src, c, v.origin, "the <visual> is skipped");
      if (r == Read::Skip || r == Read::Fail || !readGeometry(src, c, "visual", v.geometry)) continue;
      readVisualMaterial(src, c, v);
      link.visuals.push_back(std::move(v));
    } else if (tag == "collision") {
      Collision k;
      k.line = c->GetLineNum();
      if (const char* n = c->Attribute("name")) k.name = n;
      Read r = origin(src, c, k.origin, "the <collision> is skipped");
      if (r == Read::Skip || r == Read::Fail || !readGeometry(src, c, "collision", k.geometry)) continue;
      link.collisions.push_back(std::move(k));
    } else if (tag.rfind("xacro:", 0) == 0) {
      warn(src, c, "unexpanded xacro element <" + tag + "> skipped");
    }
  }
}

// RaiSim's <link sensor="FILE">: the set's body joins the link at the set's
// origin, its sensors go to Model::sensors (robot/sensor_set.hpp).
void UrdfReader::readSensorSet(const Source& src, const XMLElement* e, Link& link) {
  // Two links naming one file (ANYmal's two cameras) read it twice; what
  // the file itself gets wrong is said once.
  std::size_t before = diagnostics_.size();
  struct Dedupe {
    UrdfReader& r;
    std::size_t before;
    ~Dedupe() {
      Diagnostics& d = r.diagnostics_;
      std::size_t kept = before;
      for (std::size_t i = before; i < d.size(); ++i) {
        bool inSet = d[i].code != code::kNoSensorSet;  // the others are in the set file
        if (inSet && !r.setFindings_.insert(d[i].file + ":" + std::to_string(d[i].line) + ":" + d[i].message).second)
          continue;
        if (kept != i) d[kept] = std::move(d[i]);
        ++kept;
      }
      d.resize(kept);
    }
  } dedupe{*this, before};
  SensorSetFile set;
  if (!openSensorSet(options_.fileSystem(), sensorDirectory_, link.sensorSet, src.file, e->GetLineNum(), options_.maxFileBytes, set,
                     diagnostics_)) {
    ok_ = false;
    return;
  }
  const Source& setSource = sensorSources_.emplace_back(Source{set.path, parentDirectory(set.path), true});
  if (set.body) {
    Link body;
    readLinkElements(setSource, set.body, body);
    // In the set's frame; the model's lines refer to the URDF (and the
    // link's module), not to the set's file.
    for (Visual& v : body.visuals) {
      v.origin = set.origin * v.origin;
      v.line = 0;
      link.visuals.push_back(std::move(v));
    }
    for (Collision& c : body.collisions) {
      c.origin = set.origin * c.origin;
      c.line = 0;
      link.collisions.push_back(std::move(c));
    }
    body.inertial.origin = set.origin * body.inertial.origin;
    combineInertial(link.inertial, body.inertial);
  }
  if (!readSensors(set, link.name, sensors_, diagnostics_)) ok_ = false;
}

void UrdfReader::readJointParts(const Source& src, const XMLElement* e, Joint& j) {
  const std::string name = "joint '" + j.name + "'";
  Read r = origin(src, e, j.origin, "the <origin> of " + name + " is ignored");
  if (r == Read::Skip) j.origin = Pose{};
  if (const XMLElement* a = e->FirstChildElement("axis")) {
    std::vector<double> xyz;
    if (numbers(src, a, "xyz", 3, 3, xyz, "the <axis> of " + name + " is ignored (1 0 0)") == Read::Ok) {
      Eigen::Vector3d axis(xyz[0], xyz[1], xyz[2]);
      // A direction: its length is not read.  stableNorm() scales first, so
      // 1e308 1e308 0 is the diagonal, not an overflow to a zero axis
      // (which rscene-sim diverged on while validate and render took it).
      const double length = axis.stableNorm();
      if (length < 1e-12 && j.type != JointType::Fixed)
        fail(src, a, "<axis> of " + name + " has zero length");
      else if (length >= 1e-12)
        j.axis = axis.stableNormalized();
    }
  }
  if (const XMLElement* l = e->FirstChildElement("limit")) {
    const std::string skipping = "the <limit> of " + name + " is ignored";
    double v[4] = {0, 0, 0, 0};
    Read got[4];
    static const char* const kNames[4] = {"lower", "upper", "effort", "velocity"};
    bool skip = false;
    for (int k = 0; k < 4; ++k) {
      got[k] = number(src, l, kNames[k], v[k], skipping);
      skip = skip || got[k] == Read::Skip || got[k] == Read::Fail;
    }
    if (!skip) {
      // Position limits bind revolute, prismatic and (as RaiSim's chain
      // robots write them) spherical joints; a continuous joint's <limit>
      // carries effort and velocity only.
      j.hasLimits = (j.type == JointType::Revolute || j.type == JointType::Prismatic ||
                     j.type == JointType::Spherical) &&
                    (got[0] == Read::Ok || got[1] == Read::Ok);
      j.lower = v[0];
      j.upper = v[1];
      j.effort = v[2];
      j.velocity = v[3];
      bool bothBounds = got[0] == Read::Ok && got[1] == Read::Ok;
      if (j.hasLimits && j.type != JointType::Spherical && bothBounds && j.lower > j.upper) {
        warn(src, l, "<limit> of " + name + " has lower above upper; the joint moves without position limits");
        j.hasLimits = false;
      }
    }
  }
  if (const XMLElement* d = e->FirstChildElement("dynamics")) {
    const std::string skipping = "the <dynamics> of " + name + " is ignored";
    Joint tmp = j;
    bool skip = false;
    for (auto [attr, field] : {std::pair{"damping", &tmp.damping}, std::pair{"friction", &tmp.friction},
                               std::pair{"rotor_inertia", &tmp.rotorInertia}, std::pair{"stiffness", &tmp.stiffness}}) {
      Read r2 = number(src, d, attr, *field, skipping);
      skip = skip || r2 == Read::Skip || r2 == Read::Fail;
    }
    std::size_t mountSize = j.type == JointType::Spherical ? 4 : 1;
    std::vector<double> mount;
    Read m = numbers(src, d, "spring_mount", mountSize, mountSize, mount, skipping);
    skip = skip || m == Read::Skip || m == Read::Fail;
    if (m == Read::Ok && mountSize == 4) {
      Eigen::Vector4d q(mount[0], mount[1], mount[2], mount[3]);
      if (q.norm() < 1e-12) {
        fail(src, d, "<dynamics spring_mount> of " + name + " is a zero quaternion");
        skip = true;
      } else {
        q.normalize();
        mount = {q[0], q[1], q[2], q[3]};
      }
    }
    if (!skip) {
      tmp.springMount = mount;
      j.damping = tmp.damping;
      j.friction = tmp.friction;
      j.rotorInertia = tmp.rotorInertia;
      j.stiffness = tmp.stiffness;
      j.springMount = tmp.springMount;
    }
  }
  if (const XMLElement* m = e->FirstChildElement("mimic"))
    warn(src, m, "<mimic> of " + name + " is not supported; the joint moves on its own");
}

void UrdfReader::readJoint(const Source& src, const XMLElement* e) {
  RawJoint raw;
  Joint& j = raw.joint;
  j.line = e->GetLineNum();
  if (src.isModule) j.file = src.file;
  const char* name = e->Attribute("name");
  const char* type = e->Attribute("type");
  if (!name || !*name) {
    fail(src, e, "<joint> without a name");
    return;
  }
  j.name = name;
  std::string t = type ? type : "";
  static const std::map<std::string, JointType> kTypes = {
      {"fixed", JointType::Fixed},         {"revolute", JointType::Revolute},
      {"continuous", JointType::Continuous}, {"prismatic", JointType::Prismatic},
      {"spherical", JointType::Spherical}, {"floating", JointType::Fixed}};
  auto found = kTypes.find(t);
  if (found == kTypes.end()) {
    fail(src, e, "joint '" + j.name + "' has " + (t.empty() ? std::string("no type") : "type '" + t + "'") +
                     " (RaiSim reads fixed, revolute, continuous, prismatic, spherical, floating)");
    return;
  }
  j.type = found->second;
  raw.floating = t == "floating";
  const XMLElement* parent = e->FirstChildElement("parent");
  const XMLElement* child = e->FirstChildElement("child");
  const char* parentName = parent ? parent->Attribute("link") : nullptr;
  const char* childName = child ? child->Attribute("link") : nullptr;
  if (!parentName || !childName) {
    report(Severity::Error, code::kBadModel, src, e,
           "joint '" + j.name + "' without " + (parentName ? "a <child link>" : "a <parent link>"));
    return;
  }
  raw.parent = parentName;
  raw.child = childName;
  readJointParts(src, e, j);
  joints_.push_back(std::move(raw));
}

void UrdfReader::readTopLevel(const Source& src, const XMLElement* first) {
  for (const XMLElement* e = first; e; e = e->NextSiblingElement()) {
    std::string tag = e->Name();
    if (tag == "link")
      readLink(src, e);
    else if (tag == "joint")
      readJoint(src, e);
    else if (tag == "material")
      continue;  // read before the links (materials may come after their users)
    else if (tag == "gazebo" || tag == "transmission")
      warn(src, e, "<" + tag + "> is for other simulators; skipped");
    else if (tag == "constraints")
      warn(src, e, "<constraints> not used yet; skipped");
    else
      warn(src, e, "unknown element <" + tag + "> skipped");
  }
}

// Each module parsed as its own document, so that its lines stay its own
// (RaiSim pastes the text before </robot> and loads a generated file; the
// result is the same elements, and nothing is written to disk here).  A
// module that wraps its fragment in <robot> is unwrapped.
bool UrdfReader::loadModules(const std::string& path,
                             std::list<std::pair<Source, tinyxml2::XMLDocument>>& modules) {
  for (const std::string& module : options_.modules) {
    std::string found;
    std::vector<std::string> tried = moduleCandidates(paths_, module);
    for (const std::string& candidate : tried)
      if (options_.fileSystem().stat(candidate).kind == FileKind::Regular) {
        found = candidate;
        break;
      }
    if (found.empty()) {
      std::string list;
      for (const std::string& c : tried) list += (list.empty() ? "" : ", ") + c;
      diagnostics_.push_back(robotDiagnostic(Severity::Error, code::kNoModule, path, 0,
                                             "module '" + module + "' not found (tried " + list + ")"));
      ok_ = false;
      continue;
    }
    auto& [src, doc] = modules.emplace_back(std::piecewise_construct, std::forward_as_tuple(), std::forward_as_tuple());
    src.file = found;
    src.directory = parentDirectory(found);
    src.isModule = true;
    if (!readXmlFile(options_.fileSystem(), found, options_.maxFileBytes, doc, diagnostics_)) ok_ = false;
  }
  return ok_;
}

bool UrdfReader::read(const std::string& path, const tinyxml2::XMLDocument& doc, Model& out) {
  Source base{path, parentDirectory(path), false};
  const XMLElement* robot = doc.RootElement();
  if (!robot || std::string(robot->Name()) != "robot") {
    diagnostics_.push_back(robotDiagnostic(Severity::Error, code::kBadFile, path, robot ? robot->GetLineNum() : 0,
                                           "URDF root element is <" + std::string(robot ? robot->Name() : "") +
                                               ">, not <robot>"));
    return false;
  }
  std::list<std::pair<Source, tinyxml2::XMLDocument>> modules;  // a list: materials point at their Source
  if (!loadModules(path, modules)) return false;
  // The elements of the URDF, then those of each module in the order given.
  std::vector<std::pair<const Source*, const XMLElement*>> parts{{&base, robot->FirstChildElement()}};
  for (auto& [src, mdoc] : modules) {
    const XMLElement* first = mdoc.FirstChildElement();
    if (first && std::string(first->Name()) == "robot" && !first->NextSiblingElement())
      first = first->FirstChildElement();  // a fragment wrapped in <robot>
    parts.emplace_back(&src, first);
  }
  // Materials first, wherever they are written: a visual may name one
  // declared further down.
  for (auto [src, first] : parts)
    for (const XMLElement* e = first; e; e = e->NextSiblingElement())
      if (std::string(e->Name()) == "material") readMaterial(*src, e);
  for (auto [src, first] : parts) readTopLevel(*src, first);
  if (!ok_) return false;
  out = Model{};
  out.sourceFile = path;
  if (const char* name = robot->Attribute("name")) out.name = name;
  if (!urdf::buildTree(path, std::move(links_), std::move(joints_), out, diagnostics_)) return false;
  for (SensorDef& d : sensors_) d.link = out.findLink(d.set);
  out.sensors = std::move(sensors_);
  return true;
}

}  // namespace

namespace urdf {

bool loadDocument(const std::string& path, const tinyxml2::XMLDocument& doc, const LoadOptions& options, Model& out,
                  Diagnostics& diagnostics) {
  UrdfReader reader(path, options, diagnostics);
  Model model;
  if (!reader.read(path, doc, model)) return false;
  out = std::move(model);
  return true;
}

}  // namespace urdf

bool loadUrdf(const std::string& path, const LoadOptions& options, Model& out, Diagnostics& diagnostics) {
  tinyxml2::XMLDocument doc;
  if (!readXmlFile(options.fileSystem(), path, options.maxFileBytes, doc, diagnostics)) return false;
  return urdf::loadDocument(path, doc, options, out, diagnostics);
}

}  // namespace rscene::robot
