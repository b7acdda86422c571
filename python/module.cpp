// The `rscene._rscene` extension: lib/core's documents (load, canonical
// text, safe save, validate, diff, JSON) for Python.  The public API is
// python/rscene/__init__.py, which wraps these functions; errors the C++
// side finds come back as Python exceptions, never a crash.
#include <pybind11/pybind11.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "bindings.hpp"

#include "asset/cache.hpp"
#include "asset/obj_surface.hpp"
#include "core/assets.hpp"
#include "core/check.hpp"
#include "core/diff.hpp"
#include "core/filesystem.hpp"
#include "core/json.hpp"
#include "core/loader.hpp"
#include "core/output_file.hpp"
#include "core/writer.hpp"
#include "robot/check.hpp"
#include "robot/load.hpp"
#include "scene/validate.hpp"
#include "sim/prepare.hpp"
#include "sim/run.hpp"
#include "sim/world.hpp"

namespace py = pybind11;
using namespace rscene;
using namespace rscene::python;

namespace {

struct Parsed {
  std::shared_ptr<PyDocument> document;  // null when the text has errors
  Diagnostics diagnostics;
};

Parsed parseText(std::string text, std::string path) {
  if (text.size() > kMaxInputBytes) throw py::value_error("scene text is larger than 4 GiB, the loader's limit");
  Parsed out;
  std::string source = text;
  LoadResult r;
  {
    py::gil_scoped_release release;
    r = parse(std::move(text));
  }
  out.diagnostics = std::move(r.diagnostics);
  if (hasErrors(out.diagnostics)) return out;
  auto d = std::make_shared<PyDocument>();
  d->doc = std::move(r.document);
  d->source = std::move(source);
  d->path = std::move(path);
  d->diagnostics = out.diagnostics;
  out.document = std::move(d);
  return out;
}

Parsed parseJson(const std::string& json) {
  Parsed out;
  JsonLoadResult r;
  {
    py::gil_scoped_release release;
    r = fromJson(json);
  }
  out.diagnostics = std::move(r.diagnostics);
  if (hasErrors(out.diagnostics)) return out;
  auto d = std::make_shared<PyDocument>();
  d->doc = std::move(r.document);
  d->source = canonicalText(d->doc);
  // The canonical text is the document validate sees: reparse it so that
  // records have lines in that text (records from JSON carry JSON lines).
  LoadResult again = parse(d->source);
  if (again.ok()) d->doc = std::move(again.document);
  d->diagnostics = out.diagnostics;
  out.document = std::move(d);
  return out;
}

std::string formatDoc(const PyDocument& d) {
  py::gil_scoped_release release;
  return canonicalText(d.doc);
}

// Writes the canonical text through the tools' output routine; the message
// of a refusal, or "" on success.
std::string saveDoc(const PyDocument& d, const std::string& path) {
  if (path.empty()) throw py::value_error("save() needs a path, not an empty string");
  if (path.find('\0') != std::string::npos) throw py::value_error("embedded null byte in path");
  std::string error;
  bool ok;
  {
    py::gil_scoped_release release;
    ok = writeOutputFile(path, [&](Sink& sink) {
      writeCanonical(d.doc, sink);
      return true;
    }, &error);
  }
  if (ok) return {};
  return error.empty() ? std::string("cannot write") : error;
}

Diagnostics validateDoc(const PyDocument& d, const std::string& profile, bool checkFiles,
                        const std::string& baseDir) {
  CheckOptions co;
  if (profile == "raisim") co.profile = Profile::RaiSim;
  else if (profile == "engine2") co.profile = Profile::Engine2;
  else throw py::value_error("profile must be 'engine2' or 'raisim', not '" + profile + "'");
  co.checkFiles = checkFiles;
  if (baseDir.find('\0') != std::string::npos) throw py::value_error("embedded null byte in base_dir");
  co.sceneDir = !baseDir.empty() ? baseDir : d.path.empty() ? std::string(".") : directoryOf(d.path);
  py::gil_scoped_release release;
  // As rscene-validate checks one scene (cmd/rscene-validate/main.cpp).
  Document scratch;
  CollectDiagnostics keep;
  robot::ModelCache models;
  asset::AssetCache meshes;
  robot::RobotCheckOptions ro{co.checkFiles, co.fileExists, meshes.meshReader(asset::MeshContent::Geometry)};
  validateScene(d.source, co, scratch, keep,
                [&](const Document& doc, const Scene& s, std::vector<SceneFinding>& out) {
                  robot::checkRobots(doc, s, ro, models, out);
                },
                asset::objSurfaceReader(diskFileSystem()), meshes.meshReader(asset::MeshContent::Geometry));
  return std::move(keep.all);
}

py::dict fieldDict(const FieldDiff& f) {
  py::dict o;
  o["name"] = pystr(f.name);
  o["change"] = changeName(f.change);
  o["type"] = std::string(typeName(f.type));
  o["key_form"] = f.keyForm;
  o["entry"] = f.entry;
  o["old"] = pystr(f.oldValue);
  o["new"] = pystr(f.newValue);
  o["old_default"] = f.oldDefault;
  o["new_default"] = f.newDefault;
  o["summarized"] = f.summarized;
  o["old_count"] = f.oldCount;
  o["new_count"] = f.newCount;
  o["changed_count"] = f.changedCount;
  o["listed_count"] = f.listedCount;
  o["max_delta"] = f.maxDelta;
  return o;
}

py::list diffDocs(const PyDocument& a, const PyDocument& b, double tolerance, double relTolerance,
                  bool ignoreEditorState, std::vector<std::string> ignore) {
  if (!(tolerance >= 0) || !(relTolerance >= 0)) throw py::value_error("tolerances must be finite and >= 0");
  DiffOptions o;
  o.tolerance = tolerance;
  o.relTolerance = relTolerance;
  o.ignoreEditorState = ignoreEditorState;
  for (const std::string& name : ignore)
    if (auto bad = checkIgnoreName(name, a.doc, b.doc)) throw py::value_error("ignore: " + *bad);
  o.ignore = std::move(ignore);
  DiffResult r;
  {
    py::gil_scoped_release release;
    r = diff(a.doc, b.doc, o);
  }
  py::list out;
  for (const RecordDiff& rd : r.records) {
    py::dict o2;
    o2["change"] = changeName(rd.change);
    o2["tag"] = pystr(rd.tag);
    o2["key"] = pystr(rd.key);
    o2["path"] = pystr(rd.path);
    o2["old_path"] = pystr(rd.oldPath);
    o2["old_line"] = rd.oldLine;
    o2["new_line"] = rd.newLine;
    py::list fs;
    for (const FieldDiff& f : rd.fields) fs.append(fieldDict(f));
    o2["fields"] = fs;
    out.append(o2);
  }
  return out;
}

// Prepares `d`; (simulation or None, diagnostics, usage error).
py::tuple makeSimulation(const std::shared_ptr<PyDocument>& d) {
  auto s = std::make_unique<PySimulation>();
  s->source = d;
  s->doc = d->doc;
  sim::PrepareOptions po;
  po.scene.sceneDir = d->path.empty() ? std::string(".") : directoryOf(d->path);
  po.steps = 0;
  std::string usage;
  bool ok;
  {
    py::gil_scoped_release release;
    ok = sim::prepareSimulation(s->doc, po, s->assets, s->prepared, s->diagnostics, usage);
  }
  py::list diags = diagnosticList(s->diagnostics);
  if (!usage.empty()) throw py::value_error(usage);
  if (!ok || !s->prepared.world) return py::make_tuple(py::none(), diags);
  return py::make_tuple(py::cast(std::move(s)), diags);
}

// Steps `n` times; a failure (a state that is not finite, the pair cap)
// comes back as a diagnostic and ends the simulation.
py::object stepSimulation(PySimulation& s, long long n) {
  if (n < 0) throw py::value_error("step(n): n must be >= 0");
  if (s.failure) throw py::value_error("the simulation stopped at an earlier failure: " + s.failure->message);
  sim::RunResult r;
  {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(s.mutex);
    sim::RunOptions ro;
    // runWorld steps until the world has taken ro.steps in all.
    ro.steps = s.prepared.world->steps() + static_cast<std::uint64_t>(n);
    r = sim::runWorld(*s.prepared.world, s.doc, ro);
  }
  if (r.failure) {
    s.failure = r.failure;
    return diagnosticDict(*r.failure);
  }
  return py::none();
}

py::array_t<double> poseArray(const Pose& p) {
  py::array_t<double> a(7);
  auto v = a.mutable_unchecked<1>();
  for (int i = 0; i < 3; ++i) v(i) = p.position[i];
  v(3) = p.orientation.w();
  v(4) = p.orientation.x();
  v(5) = p.orientation.y();
  v(6) = p.orientation.z();
  return a;
}

}  // namespace

namespace rscene::python {

// Scene values are percent-decoded and may hold any bytes.
py::str pystr(const std::string& s) {
  PyObject* o = PyUnicode_DecodeUTF8(s.data(), static_cast<Py_ssize_t>(s.size()), "replace");
  if (!o) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(o);
}

py::dict diagnosticDict(const Diagnostic& d) {
  py::dict o;
  o["code"] = pystr(d.code);
  o["severity"] = severityName(d.severity);
  o["line"] = d.line;
  o["column"] = d.column;
  o["message"] = pystr(d.message);
  o["hint"] = pystr(d.hint);
  o["tag"] = pystr(d.tag);
  o["field"] = pystr(d.field);
  o["file"] = pystr(d.file);
  return o;
}

py::list diagnosticList(const Diagnostics& ds) {
  py::list l;
  for (const Diagnostic& d : ds) l.append(diagnosticDict(d));
  return l;
}

}  // namespace rscene::python

PYBIND11_MODULE(_rscene, m) {
  m.doc() = "rscene's C++ core (use the `rscene` package, not this module)";

  py::class_<PyDocument, std::shared_ptr<PyDocument>>(m, "_Document")
      .def_property_readonly("source", [](const PyDocument& d) { return py::bytes(d.source); })
      .def_property_readonly("path", [](const PyDocument& d) { return py::bytes(d.path); })
      .def_property_readonly("version", [](const PyDocument& d) { return d.doc.version; })
      .def_property_readonly("record_count", [](const PyDocument& d) { return d.doc.records.size(); })
      .def_property_readonly("diagnostics", [](const PyDocument& d) { return diagnosticList(d.diagnostics); })
      .def("tags", [](const PyDocument& d) {
        py::list l;
        for (const Record& r : d.doc.records) l.append(pystr(std::string(d.doc.tag(r))));
        return l;
      });

  // Each returns (document or None, diagnostics).
  m.def("parse", [](py::bytes text, py::bytes path) {
    Parsed p = parseText(std::string(text), std::string(path));
    return py::make_tuple(p.document ? py::cast(p.document) : py::none(), diagnosticList(p.diagnostics));
  }, py::arg("text"), py::arg("path") = "");
  m.def("from_json_text", [](const std::string& json) {
    Parsed p = parseJson(json);
    return py::make_tuple(p.document ? py::cast(p.document) : py::none(), diagnosticList(p.diagnostics));
  });
  m.def("format", [](const PyDocument& d) { return py::bytes(formatDoc(d)); });
  m.def("to_json_text", [](const PyDocument& d) {
    std::string json;
    {
      py::gil_scoped_release release;
      json = toJson(d.doc, JsonStyle{false});
    }
    return pystr(json);
  });
  m.def("save", [](const PyDocument& d, py::bytes path) { return saveDoc(d, std::string(path)); });
  m.def("validate", [](const PyDocument& d, const std::string& profile, bool checkFiles, py::bytes baseDir) {
    return diagnosticList(validateDoc(d, profile, checkFiles, std::string(baseDir)));
  });
  m.def("diff", &diffDocs);

  py::class_<PySimulation>(m, "_Simulation")
      .def("step", &stepSimulation)
      .def_property_readonly("time", [](const PySimulation& s) { std::lock_guard<std::mutex> l(s.mutex); return s.prepared.world->time(); })
      .def_property_readonly("steps", [](const PySimulation& s) { std::lock_guard<std::mutex> l(s.mutex); return s.prepared.world->steps(); })
      .def_property_readonly("time_step", [](const PySimulation& s) { std::lock_guard<std::mutex> l(s.mutex); return s.prepared.world->timeStep(); })
      .def_property_readonly("contact_count", [](const PySimulation& s) { std::lock_guard<std::mutex> l(s.mutex); return s.prepared.world->contactCount(); })
      .def_property_readonly("at_rest", [](const PySimulation& s) { std::lock_guard<std::mutex> l(s.mutex); return s.prepared.world->atRest(); })
      .def_property_readonly("diagnostics", [](const PySimulation& s) { return diagnosticList(s.diagnostics); })
      .def("body_pose", [](const PySimulation& s, const std::string& name) -> py::object {
        std::optional<Pose> p;
        {
          std::lock_guard<std::mutex> l(s.mutex);
          p = s.prepared.world->bodyPose(name);
        }
        if (!p) return py::none();
        return poseArray(*p);
      })
      .def("body_velocity", [](const PySimulation& s, const std::string& name) -> py::object {
        // The velocity of the record frame's origin, as body_pose places it.
        Eigen::Vector3d v, w;
        {
          std::lock_guard<std::mutex> l(s.mutex);
          std::optional<Pose> p = s.prepared.world->bodyPose(name);
          if (!p || !s.prepared.world->pointVelocity(name, p->position, v, w)) return py::none();
        }
        py::array_t<double> a(6);
        auto r = a.mutable_unchecked<1>();
        for (int i = 0; i < 3; ++i) r(i) = v[i], r(i + 3) = w[i];
        return std::move(a);
      })
      .def("document_text", [](const PySimulation& s) {
        std::string text;
        {
          py::gil_scoped_release release;
          std::lock_guard<std::mutex> l(s.mutex);
          Document out = s.doc;
          s.prepared.world->writeBack(out);
          text = canonicalText(out);
        }
        return py::bytes(text);
      });
  m.def("simulation", &makeSimulation);
  bindRender(m);
  bindScene(m);
}
