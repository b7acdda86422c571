// A compiled MuJoCo model read into the robot model (mjcf.hpp).
//
// Frames.  MuJoCo places a body at body_pos/body_quat in its parent's
// frame, then applies the body's joints in sequence, each about its own
// anchor jnt_pos along jnt_axis (in the body frame as moved by the joints
// before it): a hinge or ball is Trans(a) Rot Trans(-a), a slide Trans(d e),
// with hinge and slide values taken relative to qpos0 (the joint's ref).
// The robot model has one joint per link and puts the child link's frame at
// the joint, so a body with n joints becomes n links: n-1 massless
// intermediate ones named "BODY::JOINT", then the body's own link, whose
// frame is the body frame moved to the last joint's anchor ("shift").
// Geoms and the inertial are re-expressed in that link frame.  The ref
// offset goes into the joint origin, so the model's coordinates are
// MuJoCo's qpos entry for entry.  tests/robot/mjcf_test.cpp checks the
// result against mj_kinematics on every Gymnasium model.
#include <mujoco/mujoco.h>

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "robot/load.hpp"
#include "robot/mjcf.hpp"

namespace rscene::robot {
namespace {

Eigen::Vector3d vec3(const mjtNum* v) { return {v[0], v[1], v[2]}; }

Pose poseOf(const mjtNum* p, const mjtNum* q) {
  Eigen::Quaterniond r(q[0], q[1], q[2], q[3]);
  return {vec3(p), r.norm() > 1e-12 ? r.normalized() : Eigen::Quaterniond::Identity()};
}

Pose translation(const Eigen::Vector3d& v) {
  Pose p;
  p.position = v;
  return p;
}

// MuJoCo's default geom rgba: a geom that keeps it shows its material's.
bool isDefaultRgba(const float* c) { return c[0] == 0.5f && c[1] == 0.5f && c[2] == 0.5f && c[3] == 1.0f; }

class Converter {
 public:
  Converter(const mjModel& m, const std::string& path, const std::map<std::string, std::string>& meshFiles, Model& out,
            Diagnostics& diags)
      : m_(m), path_(path), meshFiles_(meshFiles), out_(out), diags_(diags) {
    for (int j = 0; j < m.njnt; ++j) jointNames_.insert(nameOf(mjOBJ_JOINT, j, "joint"));
    for (int b = 0; b < m.nbody; ++b) linkNames_.insert(nameOf(mjOBJ_BODY, b, "body"));
  }

  bool run() {
    out_.name = m_.names ? m_.names : "";
    linkOfBody_.assign(static_cast<std::size_t>(m_.nbody), -1);
    shift_.assign(static_cast<std::size_t>(m_.nbody), Eigen::Vector3d::Zero());
    if (!checkStructure()) return false;
    if (out_.floatingBase) {
      out_.root = addLink(nameOf(mjOBJ_BODY, first_, "body"));
      linkOfBody_[static_cast<std::size_t>(first_)] = out_.root;
      const int j = m_.body_jntadr[first_];
      // The free joint's qpos0: the body's pos and quat in the file.
      const int qadr = m_.jnt_qposadr[j];
      out_.baseStart = poseOf(m_.qpos0 + qadr, m_.qpos0 + qadr + 3);
      if (m_.dof_damping[m_.jnt_dofadr[j]] != 0 || m_.dof_armature[m_.jnt_dofadr[j]] != 0 ||
          m_.dof_frictionloss[m_.jnt_dofadr[j]] != 0)
        warn(code::kSkipped, "free joint '" + nameOf(mjOBJ_JOINT, j, "joint") +
                                 "': damping, armature and frictionloss of a floating base are ignored");
    } else {
      out_.root = addLink("world");
      linkOfBody_[0] = out_.root;
    }
    // Bodies come parents first (MuJoCo numbers them depth-first).
    for (int b = 1; b < m_.nbody; ++b)
      if (!(out_.floatingBase && b == first_)) addBody(b);
    for (int b = 0; b < m_.nbody; ++b) addElements(b);
    // What shapes the dynamics beyond the tree is not in the robot model.
    if (m_.ntendon > 0)
      warn(code::kSkipped, std::to_string(m_.ntendon) + " tendon(s) ignored: the robot model has no tendons");
    if (m_.neq > 0)
      warn(code::kSkipped,
           std::to_string(m_.neq) + " equality constraint(s) ignored: the robot model has no loop constraints");
    return true;
  }

 private:
  struct MeshFrame {
    bool ok = false;
    std::string file;
    Pose frame;  // the file's vertices in MuJoCo's compiled mesh frame
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  };

  std::string nameOf(int type, int id, const char* fallback) const {
    const char* n = mj_id2name(&m_, type, id);
    if (n && *n) return n;
    return fallback + std::to_string(id);
  }

  void report(Severity s, const char* code, std::string message) {
    Diagnostic d;
    d.severity = s;
    d.code = code;
    d.message = std::move(message);
    d.file = path_;
    diags_.push_back(std::move(d));
  }
  void warn(const char* code, std::string message) { report(Severity::Warning, code, std::move(message)); }
  bool error(const char* code, std::string message) {
    report(Severity::Error, code, std::move(message));
    return false;
  }

  // A name for a link or joint made up here, distinct from every name the
  // file gives.
  static std::string unique(std::set<std::string>& taken, const std::string& want) {
    std::string name = want;
    for (int i = 2; taken.count(name); ++i) name = want + "_" + std::to_string(i);
    taken.insert(name);
    return name;
  }

  // What the robot model cannot hold: a free joint anywhere but alone on
  // the first top-level body, or other top-level bodies beside it.
  bool checkStructure() {
    first_ = -1;
    for (int b = 1; b < m_.nbody && first_ < 0; ++b)
      if (m_.body_parentid[b] == 0) first_ = b;
    if (first_ < 0) return error(code::kBadModel, "the MJCF model has no body under <worldbody>");
    for (int j = 0; j < m_.njnt; ++j) {
      if (m_.jnt_type[j] != mjJNT_FREE) continue;
      const int b = m_.jnt_bodyid[j];
      const std::string what = "free joint '" + nameOf(mjOBJ_JOINT, j, "joint") + "' of body '" +
                               nameOf(mjOBJ_BODY, b, "body") + "'";
      if (b != first_)
        return error(code::kMjcfUnsupported,
                     what + ": only the first body under <worldbody> may be free (it is the robot's floating base)");
      if (m_.body_jntnum[b] != 1) return error(code::kMjcfUnsupported, what + " shares its body with other joints");
      out_.floatingBase = true;
    }
    if (!out_.floatingBase) return true;
    for (int b = first_ + 1; b < m_.nbody; ++b)
      if (m_.body_parentid[b] == 0)
        return error(code::kMjcfUnsupported, "body '" + nameOf(mjOBJ_BODY, b, "body") +
                                                 "' is a second body under <worldbody> beside the floating base '" +
                                                 nameOf(mjOBJ_BODY, first_, "body") + "'; one file, one robot");
    return true;
  }

  int addLink(const std::string& name) {
    Link l;
    l.name = name;
    out_.links.push_back(std::move(l));
    return static_cast<int>(out_.links.size()) - 1;
  }

  void connect(Joint joint, int parent, int child) {
    joint.parentLink = parent;
    joint.childLink = child;
    out_.joints.push_back(std::move(joint));
    const int index = static_cast<int>(out_.joints.size()) - 1;
    out_.links[static_cast<std::size_t>(parent)].childJoints.push_back(index);
    out_.links[static_cast<std::size_t>(child)].parentJoint = index;
  }

  void addBody(int b) {
    const std::string bodyName = nameOf(mjOBJ_BODY, b, "body");
    const int parentBody = m_.body_parentid[b];
    int parent = linkOfBody_[static_cast<std::size_t>(parentBody)];
    // The body frame at q = 0, in the frame of the parent's link.
    Pose before = translation(-shift_[static_cast<std::size_t>(parentBody)]) *
                  poseOf(m_.body_pos + 3 * b, m_.body_quat + 4 * b);
    const int n = m_.body_jntnum[b];
    if (n == 0) {
      Joint weld;
      weld.name = unique(jointNames_, bodyName + "_fixed");
      weld.type = JointType::Fixed;
      weld.origin = before;
      int link = addLink(bodyName);
      connect(std::move(weld), parent, link);
      linkOfBody_[static_cast<std::size_t>(b)] = link;
      return;
    }
    Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k) {
      const int j = m_.body_jntadr[b] + k;
      Joint joint = jointOf(j);
      anchor = vec3(m_.jnt_pos + 3 * j);
      Pose offset;  // the ref: q = qpos0 puts the body where the file does
      const double ref = m_.qpos0[m_.jnt_qposadr[j]];
      if (m_.jnt_type[j] == mjJNT_HINGE) offset.orientation = Eigen::AngleAxisd(-ref, joint.axis);
      if (m_.jnt_type[j] == mjJNT_SLIDE) offset.position = -ref * joint.axis;
      joint.origin = before * translation(anchor) * offset;
      if (joint.coordinateDim() == 1) joint.initial = ref;  // a record without coordinates starts at qpos0
      const bool last = k == n - 1;
      int link = addLink(last ? bodyName : unique(linkNames_, bodyName + "::" + joint.name));
      connect(std::move(joint), parent, link);
      parent = link;
      before = translation(-anchor);
    }
    linkOfBody_[static_cast<std::size_t>(b)] = parent;
    shift_[static_cast<std::size_t>(b)] = anchor;
  }

  Joint jointOf(int j) {
    Joint joint;
    joint.name = nameOf(mjOBJ_JOINT, j, "joint");
    joint.axis = vec3(m_.jnt_axis + 3 * j);
    if (joint.axis.norm() > 1e-12) joint.axis.normalize();
    const bool limited = m_.jnt_limited[j] != 0;
    const int dof = m_.jnt_dofadr[j];
    const int qadr = m_.jnt_qposadr[j];
    switch (m_.jnt_type[j]) {
      case mjJNT_HINGE: joint.type = limited ? JointType::Revolute : JointType::Continuous; break;
      case mjJNT_SLIDE: joint.type = JointType::Prismatic; break;
      default: joint.type = JointType::Spherical; break;  // ball; free never reaches here
    }
    if (limited && joint.type != JointType::Spherical) {
      joint.hasLimits = true;
      joint.lower = m_.jnt_range[2 * j];
      joint.upper = m_.jnt_range[2 * j + 1];
    } else if (limited) {
      warn(code::kSkipped, "ball joint '" + joint.name +
                               "': its range (a cone) is ignored; a spherical joint of the robot model has no limit");
    }
    // Damping, armature and friction loss are per dof; a ball joint's three
    // come from one attribute, so the first stands for all.  Armature is
    // the reflected rotor inertia: both add to the mass matrix diagonal.
    joint.damping = m_.dof_damping[dof];
    joint.rotorInertia = m_.dof_armature[dof];
    joint.friction = m_.dof_frictionloss[dof];
    joint.stiffness = m_.jnt_stiffness[j];
    if (joint.stiffness != 0) {
      const int width = joint.type == JointType::Spherical ? 4 : 1;
      joint.springMount.assign(m_.qpos_spring + qadr, m_.qpos_spring + qadr + width);
    }
    return joint;
  }

  // Geoms and inertial of body b on its link.  World geoms are not part of
  // a floating robot and a plane is the scene's ground, not the robot's: a
  // fixed-base model keeps the other world geoms (a rail) on its world link.
  void addElements(int b) {
    const int link = linkOfBody_[static_cast<std::size_t>(b)];
    if (link < 0) {  // the world of a floating robot
      for (int g = m_.body_geomadr[0]; g >= 0 && g < m_.body_geomadr[0] + m_.body_geomnum[0]; ++g)
        if (m_.geom_type[g] != mjGEOM_PLANE)
          warn(code::kSkipped, "world geom '" + nameOf(mjOBJ_GEOM, g, "geom") +
                                   "' is not part of the floating robot; skipped (the scene holds what is around it)");
      return;
    }
    Link& l = out_.links[static_cast<std::size_t>(link)];
    const Pose toLink = translation(-shift_[static_cast<std::size_t>(b)]);
    if (b != 0) {
      l.inertial.mass = m_.body_mass[b];
      l.inertial.origin = toLink * poseOf(m_.body_ipos + 3 * b, m_.body_iquat + 4 * b);
      l.inertial.inertia = vec3(m_.body_inertia + 3 * b).asDiagonal();
    }
    for (int g = m_.body_geomadr[b]; g >= 0 && g < m_.body_geomadr[b] + m_.body_geomnum[b]; ++g) {
      if (b == 0 && m_.geom_type[g] == mjGEOM_PLANE) continue;
      addGeom(g, toLink, l);
    }
  }

  void addGeom(int g, const Pose& toLink, Link& l) {
    const std::string name = nameOf(mjOBJ_GEOM, g, "geom");
    const mjtNum* s = m_.geom_size + 3 * g;
    Geometry geometry;
    Pose meshOffset;  // a mesh file's vertices in MuJoCo's compiled mesh frame
    switch (m_.geom_type[g]) {
      case mjGEOM_SPHERE:
        geometry.kind = GeometryKind::Sphere;
        geometry.radius = s[0];
        break;
      case mjGEOM_CAPSULE:
      case mjGEOM_CYLINDER:
        geometry.kind = m_.geom_type[g] == mjGEOM_CAPSULE ? GeometryKind::Capsule : GeometryKind::Cylinder;
        geometry.radius = s[0];
        geometry.length = 2 * s[1];
        break;
      case mjGEOM_BOX:
        geometry.kind = GeometryKind::Box;
        geometry.size = 2 * vec3(s);
        break;
      case mjGEOM_ELLIPSOID:
        // The robot model has no ellipsoid: the sphere of the same volume.
        geometry.kind = GeometryKind::Sphere;
        geometry.radius = std::cbrt(s[0] * s[1] * s[2]);
        warn(code::kMjcfApproximated, "ellipsoid geom '" + name + "' is approximated by a sphere of radius " +
                                          std::to_string(geometry.radius) + " (the same volume)");
        break;
      case mjGEOM_MESH: {
        const MeshFrame* mesh = meshFrame(m_.geom_dataid[g], name);
        if (!mesh) return;
        geometry.kind = GeometryKind::Mesh;
        geometry.meshPath = mesh->file;
        geometry.meshScale = mesh->scale;
        meshOffset = mesh->frame;
        break;
      }
      default:
        warn(code::kSkipped, std::string(m_.geom_type[g] == mjGEOM_PLANE ? "plane" : "height field") + " geom '" +
                                 name + "' on a body is skipped: the robot model has no such shape");
        return;
    }
    const Pose origin = toLink * poseOf(m_.geom_pos + 3 * g, m_.geom_quat + 4 * g) * meshOffset;
    Visual v;
    v.name = name;
    v.origin = origin;
    v.geometry = geometry;
    const float* rgba = m_.geom_rgba + 4 * g;
    const int mat = m_.geom_matid[g];
    if (mat >= 0 && isDefaultRgba(rgba)) rgba = m_.mat_rgba + 4 * mat;
    v.color = Eigen::Vector4d(rgba[0], rgba[1], rgba[2], rgba[3]);
    if (mat >= 0) v.materialName = nameOf(mjOBJ_MATERIAL, mat, "material");
    l.visuals.push_back(std::move(v));
    // contype = conaffinity = 0: MuJoCo never collides it; drawn only.
    if (m_.geom_contype[g] == 0 && m_.geom_conaffinity[g] == 0) return;
    Collision c;
    c.name = name;
    c.origin = origin;
    c.geometry = geometry;
    l.collisions.push_back(std::move(c));
  }

  // The file and frame of mesh `id`, or nullptr after a warning.
  const MeshFrame* meshFrame(int id, const std::string& geom) {
    auto [it, fresh] = meshFrames_.try_emplace(id);
    MeshFrame& f = it->second;
    const std::string mesh = nameOf(mjOBJ_MESH, id, "mesh");
    if (fresh) {
      auto file = meshFiles_.find(mesh);
      std::string why = "it has no file (vertices written in the model)";
      if (file != meshFiles_.end()) {
        f.file = file->second;
        f.ok = mjcfMeshFrame(f.file, m_.mesh_vert + 3 * m_.mesh_vertadr[id], m_.mesh_vertnum[id], f.frame, f.scale,
                             why);
      }
      if (!f.ok) warn(code::kSkipped, "mesh '" + mesh + "' is skipped: " + why);
    }
    if (!f.ok) {
      warn(code::kSkipped, "mesh geom '" + geom + "' is skipped: its mesh '" + mesh + "' cannot be used");
      return nullptr;
    }
    return &f;
  }

  const mjModel& m_;
  const std::string& path_;
  const std::map<std::string, std::string>& meshFiles_;
  std::map<int, MeshFrame> meshFrames_;  // by mesh id, worked out once
  Model& out_;
  Diagnostics& diags_;
  std::set<std::string> jointNames_, linkNames_;
  std::vector<int> linkOfBody_;               // per body: the link carrying its geoms and inertial
  std::vector<Eigen::Vector3d> shift_;        // per body: its link frame = body frame * Trans(shift)
  int first_ = -1;                            // the first body under the world
};

}  // namespace

bool convertMjcf(const mjModel_& m, const std::string& path, const std::map<std::string, std::string>& meshFiles,
                 Model& out, Diagnostics& diagnostics) {
  out = Model{};
  out.sourceFile = path;
  out.floatingBase = false;
  Converter converter(m, path, meshFiles, out, diagnostics);
  return converter.run();
}

}  // namespace rscene::robot
