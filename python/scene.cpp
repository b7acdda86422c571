// The typed scene for Python (issue 28): lib/scene's Scene (the one
// schema-driven model validate, sim and render read) as dicts of numpy
// arrays that python/rscene/_scene.py wraps, and the edit of one record's
// fields in place: the new values are encoded by the JSON form's reader
// (core/json.hpp, rscene-from-json: the schema's types) and patched into
// the text as read, so every other byte of the file stays as written.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"

#include "core/assets.hpp"
#include "core/check.hpp"
#include "core/json.hpp"
#include "core/loader.hpp"
#include "core/output_file.hpp"
#include "core/project.hpp"
#include "core/text.hpp"
#include "core/writer.hpp"
#include "robot/instance.hpp"
#include "robot/kinematics.hpp"
#include "robot/load.hpp"
#include "scene/scene.hpp"

namespace rscene::python {
namespace {

py::array_t<double> vec(const Eigen::VectorXd& v) {
  py::array_t<double> a(v.size());
  auto m = a.mutable_unchecked<1>();
  for (Eigen::Index i = 0; i < v.size(); ++i) m(i) = v[i];
  return a;
}
template <int N>
py::array_t<double> vec(const Eigen::Matrix<double, N, 1>& v) {
  return vec(Eigen::VectorXd(v));
}
py::array_t<double> vec(const std::vector<double>& v) {
  return vec(Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()))));
}
py::array_t<double> quat(const Eigen::Quaterniond& q) {
  return vec(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()));
}

// What every record view has: its index into the document, tag and line.
py::dict base(const Document& doc, int recordIndex) {
  py::dict d;
  d["record"] = recordIndex;
  if (recordIndex >= 0 && static_cast<std::size_t>(recordIndex) < doc.records.size()) {
    const Record& r = doc.records[static_cast<std::size_t>(recordIndex)];
    d["tag"] = pystr(std::string(doc.tag(r)));
    d["line"] = r.line;
  } else {
    d["tag"] = py::none();
    d["line"] = 0;
  }
  return d;
}

void node(py::dict& d, const std::string& path, const std::string& id) {
  d["path"] = pystr(path);
  d["id"] = pystr(id);
}

void pose(py::dict& d, const Pose& local, const Pose& world) {
  d["position"] = vec(local.position);
  d["orientation"] = quat(local.orientation);
  d["world_position"] = vec(world.position);
  d["world_orientation"] = quat(world.orientation);
}

py::object optionalText(const std::string& s) { return s.empty() ? py::object(py::none()) : py::object(pystr(s)); }
// A camera's or sensor's outputPath: none when unset or "-" (the record's "no file").
py::object optionalOutput(const std::string& s) { return s == "-" ? py::object(py::none()) : optionalText(s); }

py::dict objectDict(const Document& doc, const Object& o) {
  py::dict d = base(doc, o.recordIndex);
  node(d, o.path, o.id);
  d["parent_id"] = pystr(o.parentId);
  d["primitive"] = pystr(o.primitive);
  pose(d, o.local, o.world);
  d["scale"] = vec(o.scale);
  d["radius"] = o.radius;
  d["height"] = o.height;
  d["mass"] = o.mass;
  d["body_mode"] = std::string(bodyModeName(o.bodyMode));
  d["material"] = pystr(o.material);
  d["contact_material"] = pystr(o.contactMaterial);
  d["visible"] = o.visible && !o.hiddenByGroup;
  d["collidable"] = o.collidable;
  d["collision_group"] = o.collisionGroup;
  d["collision_mask"] = o.collisionMask;
  d["mesh_path"] = optionalText(o.meshPath);
  d["collision_mesh_path"] = optionalText(o.collisionMeshPath);
  d["semantic_class"] = o.semanticClass.empty() || o.semanticClass == "-" ? py::object(py::none())
                                                                          : py::object(pystr(o.semanticClass));
  d["instance_id"] = o.instanceId >= 0 ? py::object(py::int_(o.instanceId)) : py::object(py::none());
  d["inertia_diagonal"] = o.hasInertia ? py::object(vec(o.inertiaDiagonal)) : py::object(py::none());
  return d;
}

py::dict compoundDict(const Document& doc, const Compound& c) {
  py::dict d = base(doc, c.recordIndex);
  node(d, c.path, c.id);
  d["parent_id"] = pystr(c.parentId);
  pose(d, c.local, c.world);
  d["scale"] = vec(c.scale);
  d["mass"] = c.mass;
  d["body_mode"] = std::string(bodyModeName(c.bodyMode));
  d["material"] = pystr(c.material);
  d["contact_material"] = pystr(c.contactMaterial);
  d["visible"] = c.visible && !c.hiddenByGroup;
  d["collidable"] = c.collidable;
  d["center_of_mass"] = c.hasCenterOfMass ? py::object(vec(c.centerOfMass)) : py::object(py::none());
  d["inertia_diagonal"] = c.hasInertia ? py::object(vec(c.inertiaDiagonal)) : py::object(py::none());
  py::list children;
  for (const CompoundChild& ch : c.children) {
    py::dict k = base(doc, ch.recordIndex);
    k["primitive"] = pystr(ch.primitive);
    k["position"] = vec(ch.local.position);
    k["orientation"] = quat(ch.local.orientation);
    k["scale"] = vec(ch.scale);
    k["size"] = vec(ch.size);
    k["radius"] = ch.radius;
    k["height"] = ch.height;
    k["material"] = pystr(ch.material);
    k["contact_material"] = pystr(ch.contactMaterial);
    k["mesh_path"] = optionalText(ch.meshPath);
    children.append(k);
  }
  d["children"] = children;
  return d;
}

py::list names(const std::vector<std::string>& v) {
  py::list l;
  for (const std::string& s : v) l.append(pystr(s));
  return l;
}

py::dict robotDict(const Document& doc, const Articulated& a, robot::ModelCache& models, Diagnostics& diags,
                   bool loadRobots) {
  py::dict d = base(doc, a.recordIndex);
  node(d, a.path, a.id);
  d["parent_id"] = pystr(a.parentId);
  d["resource"] = pystr(a.resourceRef);
  d["source_path"] = pystr(a.sourcePath);
  pose(d, a.local, a.world);
  d["scale"] = vec(a.scale);
  d["visible"] = a.visible && !a.hiddenByGroup;
  d["collidable"] = a.collidable;
  d["generalized_coordinate"] = a.hasCoordinate ? py::object(vec(a.generalizedCoordinate)) : py::object(py::none());
  d["generalized_velocity"] = a.hasVelocity ? py::object(vec(a.generalizedVelocity)) : py::object(py::none());
  d["joint_order"] = names(a.jointOrder);
  // The model's names and the state the record gives, read as sim and
  // render read it (robot::makeInstance); None where the model does not load.
  d["joint_names"] = py::none();
  d["coordinate_names"] = py::none();
  d["velocity_names"] = py::none();
  d["q"] = py::none();
  d["u"] = py::none();
  d["floating_base"] = py::none();
  if (!loadRobots || a.leftOut) return d;
  robot::RobotInstance in;
  robot::makeInstance(doc, a, models, in, diags);
  if (!in.model) return d;
  std::vector<std::string> joints;
  for (int j : in.coordinates.joints) joints.push_back(in.model->joints[static_cast<std::size_t>(j)].name);
  d["joint_names"] = names(joints);
  d["coordinate_names"] = names(robot::coordinateNames(*in.model, in.coordinates, false));
  d["velocity_names"] = names(robot::coordinateNames(*in.model, in.coordinates, true));
  d["floating_base"] = in.model->floatingBase;
  if (in.q.size() == in.coordinates.coordinateDim) d["q"] = vec(in.q);
  if (in.u.size() == in.coordinates.velocityDim) d["u"] = vec(in.u);
  return d;
}

py::dict cameraDict(const Document& doc, const Camera& c) {
  py::dict d = base(doc, c.recordIndex);
  node(d, c.path, c.id);
  pose(d, c.local, c.world);
  d["vertical_fov"] = c.verticalFov;
  d["horizontal_fov"] = c.horizontalFov;
  d["near_plane"] = c.nearPlane;
  d["far_plane"] = c.farPlane;
  d["width"] = c.width;
  d["height"] = c.height;
  d["render_mode"] = pystr(c.renderMode);
  d["projection"] = pystr(c.projection);
  d["ortho_scale"] = c.orthoScale;
  d["enabled"] = c.enabled;
  d["output_path"] = optionalOutput(c.outputPath);
  return d;
}

py::dict sensorDict(const Document& doc, const Sensor& s) {
  py::dict d = base(doc, s.recordIndex);
  node(d, s.path, s.id);
  d["kind"] = pystr(s.kind);
  d["parent_object"] = pystr(s.parentObject);
  d["parent_link"] = pystr(s.parentLink);
  pose(d, s.local, s.world);
  const SensorParams& p = s.params;
  d["width"] = p.width;
  d["height"] = p.height;
  d["vertical_fov"] = p.verticalFov;
  d["horizontal_fov"] = p.horizontalFov;
  d["near_plane"] = p.nearPlane;
  d["far_plane"] = p.farPlane;
  d["intrinsics"] = p.fx > 0 ? py::object(vec(Eigen::Vector4d(p.fx, p.fy, p.cx, p.cy))) : py::object(py::none());
  d["update_rate"] = p.updateRate;
  d["lidar_channels"] = p.lidarChannels;
  d["lidar_samples"] = p.lidarSamples;
  d["lidar_min_pitch"] = p.lidarMinPitch;
  d["lidar_max_pitch"] = p.lidarMaxPitch;
  d["lidar_min_range"] = p.lidarMinRange;
  d["lidar_max_range"] = p.lidarMaxRange;
  d["segmentation"] = p.segmentation;
  d["noise_mean"] = p.noiseMean;
  d["noise_stddev"] = p.noiseStddev;
  d["noise_seed"] = p.noiseSeed;
  d["enabled"] = s.enabled;
  d["output_path"] = optionalOutput(s.outputPath);
  return d;
}

py::dict lightDict(const Document& doc, const Light& l) {
  py::dict d = base(doc, l.recordIndex);
  node(d, l.path, l.id);
  d["type"] = pystr(l.type);
  d["direction"] = vec(l.direction);
  d["position"] = vec(l.position);
  d["intensity"] = l.intensity;
  d["color"] = vec(l.color);
  d["range"] = l.range;
  d["cone_angle"] = l.coneAngle;
  d["inner_cone_angle"] = l.innerConeAngle;
  d["radius"] = l.radius;
  d["area_size"] = vec(l.areaSize);
  d["shadows"] = l.shadows;
  d["negative"] = l.negative;
  d["visible"] = !l.hiddenByGroup;
  return d;
}

py::dict materialDict(const Document& doc, const Material& m) {
  py::dict d = base(doc, m.recordIndex);
  d["id"] = pystr(m.id);
  d["name"] = pystr(m.name);
  d["color"] = vec(m.color);
  d["metallic"] = m.metallic;
  d["roughness"] = m.roughness;
  d["emissive"] = vec(m.emissive);
  d["emissive_strength"] = m.emissiveStrength;
  d["double_sided"] = m.doubleSided;
  d["alpha_mode"] = pystr(m.alphaMode);
  return d;
}

SceneOptions sceneOptions(const PyDocument& d) {
  SceneOptions so;
  so.sceneDir = d.path.empty() ? std::string(".") : directoryOf(d.path);
  if (!d.path.empty()) so.project = projectPlaceOf(so.sceneDir, diskFileSystem());
  return so;
}

py::dict sceneDict(const PyDocument& d, bool loadRobots) {
  Scene s;
  Diagnostics diags;
  {
    py::gil_scoped_release release;
    buildScene(d.doc, sceneOptions(d), s, diags);
  }
  robot::ModelCache models;
  py::dict out;
  out["time_step"] = s.timeStep;
  out["gravity"] = vec(s.gravity);
  py::list objects, compounds, robots, cameras, sensors, lights, materials;
  for (const Object& o : s.objects) objects.append(objectDict(d.doc, o));
  for (const Compound& c : s.compounds) compounds.append(compoundDict(d.doc, c));
  for (const Articulated& a : s.articulated) robots.append(robotDict(d.doc, a, models, diags, loadRobots));
  for (const Camera& c : s.cameras) cameras.append(cameraDict(d.doc, c));
  for (const Sensor& x : s.sensors) sensors.append(sensorDict(d.doc, x));
  for (const Light& l : s.lights) lights.append(lightDict(d.doc, l));
  for (const Material& m : s.materials) materials.append(materialDict(d.doc, m));
  out["objects"] = objects;
  out["compounds"] = compounds;
  out["robots"] = robots;
  out["cameras"] = cameras;
  out["sensors"] = sensors;
  out["lights"] = lights;
  out["materials"] = materials;
  out["diagnostics"] = diagnosticList(diags);
  return out;
}

// --- editing ------------------------------------------------------------

std::string describe(const Document& doc, std::size_t i) {
  const Record& r = doc.records[i];
  std::string path = nodePath(doc, r);
  return std::string(doc.tag(r)) + (path.empty() ? "" : " '" + path + "'") + " (line " + std::to_string(r.line) + ")";
}

// The record `selector` names: a node's path (with or without the leading
// '/') or id, or the tag of a record kind the scene has once.
std::size_t findRecord(const Document& doc, const std::string& selector) {
  if (selector.empty()) throw py::value_error("empty record name");
  std::vector<std::size_t> found;
  for (std::size_t i = 1; i < doc.records.size(); ++i) {
    const Record& r = doc.records[i];
    if (!r.kind || !r.kind->isNode()) continue;
    std::string path = nodePath(doc, r);
    bool samePath = path == selector || (!path.empty() && path[0] == '/' && path.compare(1, std::string::npos, selector) == 0);
    if (samePath || nodeId(doc, r) == selector) found.push_back(i);
  }
  if (found.empty())
    for (std::size_t i = 1; i < doc.records.size(); ++i)
      if (doc.tag(doc.records[i]) == selector) found.push_back(i);
  if (found.size() == 1) return found[0];
  if (found.empty()) throw py::key_error("no record with path, id or tag '" + selector + "'");
  std::string list;
  for (std::size_t k = 0; k < found.size() && k < 5; ++k) {
    if (k) list += ", ";
    list += describe(doc, found[k]);
  }
  throw py::value_error("'" + selector + "' names " + std::to_string(found.size()) + " records (" + list +
                        "): give its record number (the views' .record)");
}

std::size_t checkIndex(const Document& doc, long long index) {
  if (index < 1 || static_cast<std::size_t>(index) >= doc.records.size())
    throw py::key_error("record " + std::to_string(index) + " is not in the document (1 to " +
                          std::to_string(doc.records.size() - 1) + ")");
  return static_cast<std::size_t>(index);
}

// The record's canonical line in a document of its own (the header, then
// it), as JSON: what _scene.py edits.
std::string recordJson(const PyDocument& d, std::size_t index) {
  const Document& doc = d.doc;
  std::string text;
  appendCanonicalRecord(doc, doc.records[0], text);
  appendCanonicalRecord(doc, doc.records[index], text);
  LoadResult one = parse(text);
  if (!one.ok() || one.document.records.size() != 2)
    throw py::value_error("record " + describe(doc, index) + " cannot be edited field by field");
  return toJson(one.document, JsonStyle{false});
}

struct Patch {
  std::size_t offset, length;
  std::string text;
};

// The record's positional tokens that field `name` takes (layout order).
std::vector<std::uint32_t> positionalTokens(const Record& r, const std::string& name) {
  std::vector<std::uint32_t> out;
  const Layout* layout = r.kind ? r.kind->layoutFor(r.positionalCount) : nullptr;
  if (!layout) return out;
  for (std::uint32_t t = 0; t < layout->tokens.size(); ++t)
    if (layout->fields[static_cast<std::size_t>(layout->tokens[t].first)].name == name) out.push_back(t);
  return out;
}

// `d` with the fields `edited` of record `index` taken from `edit` (a
// document of the header and the edited record, from the JSON form) and
// the keys `removed` taken out; every other byte as in d.source.
std::shared_ptr<PyDocument> applyEdit(const PyDocument& d, std::size_t index, const std::string& editJson,
                                      const std::vector<std::string>& edited, const std::vector<std::string>& removed) {
  JsonLoadResult parsed = fromJson(editJson);
  if (!parsed.ok() || parsed.document.records.size() != 2) {
    std::string why;
    for (const Diagnostic& x : parsed.diagnostics)
      if (x.severity == Severity::Error) {
        why = x.message;
        break;
      }
    throw py::value_error("the new value does not fit the field: " + why);
  }
  const Document& edit = parsed.document;
  const Record& n = edit.records[1];

  // The source text the document's spans point into (a document made from
  // JSON whose canonical text did not read back has other spans: edit its
  // canonical text then).
  std::string source = d.source;
  Document base = d.doc;
  auto spansMatch = [&](const Record& r) {
    for (std::uint32_t i = 0; i < r.fieldCount; ++i) {
      const Field& f = base.field(r, i);
      Span s = f.value;
      if (std::size_t(s.offset) + s.length > source.size() || source.compare(s.offset, s.length, base.text(s)) != 0)
        return false;
    }
    return true;
  };
  if (!spansMatch(base.records[index])) {
    source = canonicalText(base);
    LoadResult again = parse(source);
    if (!again.ok()) throw py::value_error("this document cannot be edited (its text does not read back)");
    base = std::move(again.document);
  }
  const Record& r = base.records[index];
  const int version = base.version;

  std::vector<Patch> patches;
  for (const std::string& name : edited) {
    if (r.kind && r.kind->key(name)) {
      const Field* now = edit.find(n, name);
      if (!now) throw py::value_error("field '" + name + "': no value came back from the JSON form");
      std::string raw(edit.text(now->value));
      // Re-encoded for the file's own version (the JSON form writes the newest).
      std::string value;
      const FieldDef* def = r.kind->key(name);
      appendCanonical(value, raw, def->type, version);
      if (const Field* old = base.find(r, name))
        patches.push_back({old->value.offset, old->value.length, value});
      else {
        std::uint32_t end = r.tag.offset + r.tag.length;
        for (std::uint32_t i = 0; i < r.fieldCount; ++i) {
          const Field& f = base.field(r, i);
          end = std::max(end, f.value.offset + f.value.length);
        }
        patches.push_back({end, 0, " " + name + "=" + value});
      }
      continue;
    }
    std::vector<std::uint32_t> tokens = positionalTokens(r, name);
    if (tokens.empty()) throw py::value_error("record " + describe(base, index) + " has no field '" + name + "'");
    const Layout* layout = r.kind->layoutFor(r.positionalCount);
    for (std::uint32_t t : tokens) {
      const Field* old = base.positional(r, t);
      const Field* now = edit.positional(n, t);
      if (!old || !now) throw py::value_error("field '" + name + "': token " + std::to_string(t) + " is missing");
      const FieldDef& def = layout->fields[static_cast<std::size_t>(layout->tokens[t].first)];
      // A vector spread over tokens holds a number in each.
      ValueType type = def.width > 1 ? ValueType::Number : def.type;
      std::string value;
      appendCanonical(value, edit.text(now->value), type, version);
      patches.push_back({old->value.offset, old->value.length, value});
    }
  }
  for (const std::string& name : removed) {
    if (!r.kind || !r.kind->key(name)) {
      if (!positionalTokens(r, name).empty())
        throw py::value_error("field '" + name + "' is positional: it cannot be removed, only set");
      throw py::value_error("record " + describe(base, index) + " has no key '" + name + "'");
    }
    for (std::uint32_t i = 0; i < r.fieldCount; ++i) {
      const Field& f = base.field(r, i);
      if (!f.isKey() || base.text(f.key) != name) continue;
      std::size_t start = f.key.offset;
      while (start > 0 && (source[start - 1] == ' ' || source[start - 1] == '\t')) --start;
      patches.push_back({start, f.value.offset + f.value.length - start, ""});
    }
  }
  // From the end of the text back, so that earlier offsets hold; keys
  // added at one place go in the order given (the last inserted first).
  std::vector<std::size_t> order(patches.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return patches[a].offset != patches[b].offset ? patches[a].offset > patches[b].offset : a > b;
  });
  for (std::size_t i : order) source.replace(patches[i].offset, patches[i].length, patches[i].text);

  auto out = std::make_shared<PyDocument>();
  LoadResult again = parse(source);
  if (!again.ok()) {
    std::string why;
    for (const Diagnostic& x : again.diagnostics)
      if (x.severity == Severity::Error) {
        why = x.message;
        break;
      }
    throw py::value_error("the edit does not read back: " + why);
  }
  // A value of the wrong type (a word for a number, two numbers for a
  // vec3): the validator's own check of the type, at the edited field.
  Diagnostics found = check(again.document, CheckOptions{});
  const std::uint32_t line = again.document.records[index].line;
  for (const Diagnostic& x : found) {
    if (x.severity != Severity::Error || x.line != line || x.code.rfind("RS2", 0) != 0) continue;
    bool ours = std::find(edited.begin(), edited.end(), x.field) != edited.end();
    if (ours) throw py::value_error("field '" + x.field + "': " + x.message + " [" + x.code + "]");
  }
  out->doc = std::move(again.document);
  out->source = std::move(source);
  out->path = d.path;
  out->diagnostics = std::move(again.diagnostics);
  return out;
}

}  // namespace

void bindScene(py::module_& m) {
  // Document.save(as_written=True): the text as read, edits patched in,
  // through the tools' output routine; the refusal's message or "".
  m.def("save_source", [](const PyDocument& d, py::bytes path) {
    return saveText(std::string(path), [&](Sink& sink) { sink.write(d.source); });
  });
  m.def("scene", &sceneDict, py::arg("doc"), py::arg("load_robots") = true);
  m.def("find_record", [](const PyDocument& d, py::object selector) -> std::size_t {
    if (py::isinstance<py::int_>(selector)) {
      // A number past long long is no record either (KeyError, not OverflowError).
      int overflow = 0;
      long long n = PyLong_AsLongLongAndOverflow(selector.ptr(), &overflow);
      if (n == -1 && PyErr_Occurred()) throw py::error_already_set();
      if (overflow)
        throw py::key_error("record " + py::str(selector).cast<std::string>() + " is not in the document (1 to " +
                            std::to_string(d.doc.records.size() - 1) + ")");
      return checkIndex(d.doc, n);
    }
    return findRecord(d.doc, selector.cast<std::string>());
  });
  m.def("record_json", [](const PyDocument& d, std::size_t index) {
    return pystr(recordJson(d, checkIndex(d.doc, static_cast<long long>(index))));
  });
  m.def("record_fields", [](const PyDocument& d, std::size_t index) {
    const Record& r = d.doc.records[checkIndex(d.doc, static_cast<long long>(index))];
    py::list positional, keys;
    py::dict types;  // name -> the schema type's name ("number", "uint64", ...)
    if (const Layout* layout = r.kind ? r.kind->layoutFor(r.positionalCount) : nullptr)
      for (const FieldDef& f : layout->fields) {
        positional.append(f.name);
        types[py::str(f.name)] = std::string(typeName(f.type));
      }
    if (r.kind)
      for (const FieldDef& f : r.kind->keys) {
        keys.append(f.name);
        types[py::str(f.name)] = std::string(typeName(f.type));
      }
    return py::make_tuple(positional, keys, types);
  });
  m.def("edit", [](const PyDocument& d, std::size_t index, const std::string& json, std::vector<std::string> edited,
                   std::vector<std::string> removed) {
    return applyEdit(d, checkIndex(d.doc, static_cast<long long>(index)), json, edited, removed);
  });
}

}  // namespace rscene::python
