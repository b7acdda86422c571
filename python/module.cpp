// The `rscene._rscene` extension: lib/core's documents (load, canonical
// text, safe save, validate, diff, JSON) for Python.  The public API is
// python/rscene/__init__.py, which wraps these functions; errors the C++
// side finds come back as Python exceptions, never a crash.
#include <pybind11/pybind11.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/eigen.h>

#include <functional>
#include <memory>
#include <mutex>
#include <algorithm>
#include <unordered_map>
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
#include "core/project.hpp"
#include "core/writer.hpp"
#include "robot/check.hpp"
#include "robot/entry_names.hpp"
#include "robot/load.hpp"
#include "scene/validate.hpp"
#include "robot/kinematics.hpp"
#include "robot/sensors.hpp"
#include "sim/prepare.hpp"
#include "sim/run.hpp"
#include "sim/sensor_recorder.hpp"
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
  // generalizedCoordinate[LF_KFE]: entries named by joint, as rscene-diff
  // names them, where the robot model is readable.
  robot::EntryNames joints;
  joints.addSide(a.doc, a.path.empty() ? std::string(".") : directoryOf(a.path));
  joints.addSide(b.doc, b.path.empty() ? std::string(".") : directoryOf(b.path));
  o.entryNames = std::ref(joints);
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

void prepareExtras(PySimulation& s);

// Prepares `d`; (simulation or None, diagnostics, usage error).
// rscene-sim's flags in lib/sim's findings as Python says them: the flag
// Python has as its keyword; a limit Python cannot raise as a limit.
Diagnostic simWords(Diagnostic d) {
  auto replace = [](std::string& s, const std::string& from, const std::string& to) {
    for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
      s.replace(at, from.size(), to);
  };
  for (std::string* s : {&d.message, &d.hint}) {
    replace(*s, "--allow-missing-assets", "allow_missing_assets=True");
    replace(*s, "; the simulation stopped and nothing was written", "; the simulation stopped");
    replace(*s, "springs or --pd-gains too stiff", "springs or PD gains too stiff");
    replace(*s, "raise the limit with --max-pairs N (each pair costs about 8.5 KB), or spread the bodies out",
            "spread the bodies out (rscene-sim --max-pairs N raises the limit; each pair costs about 8.5 KB)");
  }
  return d;
}

Diagnostics simWords(const Diagnostics& ds) {
  Diagnostics out;
  for (const Diagnostic& d : ds) out.push_back(simWords(d));
  return out;
}

// `baseDir` and `allowMissing` as rscene-sim's --base-dir and
// --allow-missing-assets.
py::tuple makeSimulation(const std::shared_ptr<PyDocument>& d, bool allowMissing, py::bytes baseDirBytes) {
  std::string baseDir(baseDirBytes);
  if (baseDir.find('\0') != std::string::npos) throw py::value_error("embedded null byte in base_dir");
  auto s = std::make_unique<PySimulation>();
  s->source = d;
  s->doc = d->doc;
  sim::PrepareOptions po;
  po.scene.sceneDir = d->path.empty() ? std::string(".") : directoryOf(d->path);
  po.scene.baseDir = baseDir;
  // The project as the tool finds it: from the scene's folder, or for a
  // scene with no file from the base folder.
  std::string projectDir = d->path.empty() ? baseDir : po.scene.sceneDir;
  if (!projectDir.empty()) po.scene.project = projectPlaceOf(projectDir, diskFileSystem());
  po.allowMissingAssets = allowMissing;
  po.steps = 0;
  std::string usage;
  bool ok;
  {
    py::gil_scoped_release release;
    ok = sim::prepareSimulation(s->doc, po, s->assets, s->prepared, s->diagnostics, usage);
  }
  s->diagnostics = simWords(s->diagnostics);
  py::list diags = diagnosticList(s->diagnostics);
  if (!usage.empty()) throw py::value_error(usage);
  if (!ok || !s->prepared.world) return py::make_tuple(py::none(), diags);
  {
    py::gil_scoped_release release;
    prepareExtras(*s);
  }
  return py::make_tuple(py::cast(std::move(s)), diags);
}

py::array_t<double> poseArray(const Pose& p);

// The latest reading of every recorded sensor (SensorRecorder's output).
struct LatestReadings : sim::SensorOutput {
  struct Scan {
    bool any = false;
    std::uint64_t index = 0;
    double time = 0;
    Pose pose;
    std::vector<Eigen::Vector3f> points;  // sensor frame
  };
  std::vector<Scan> scans;                          // per sensor (LiDARs)
  std::vector<std::optional<sim::ImuReading>> imus;  // per sensor (IMUs)
  bool lidarScan(std::size_t sensor, std::uint64_t index, double time, const Pose& pose,
                 const std::vector<Eigen::Vector3f>& points) override {
    Scan& sc = scans[sensor];
    sc.any = true;
    sc.index = index;
    sc.time = time;
    sc.pose = pose;
    sc.points = points;
    return true;
  }
  bool imuReading(std::size_t sensor, const sim::ImuReading& reading) override {
    imus[sensor] = reading;
    return true;
  }
};

// PySimulation::extra.
struct SimExtras {
  std::unordered_map<int, std::string> recordPaths;  // record index -> path, of bodies contacts name
  std::unique_ptr<sim::SensorRecorder> recorder;     // null: no LiDAR or IMU
  std::unordered_map<std::string, std::size_t> sensorByName;  // name and id -> recorder's index
  LatestReadings latest;
};

SimExtras& extras(const PySimulation& s) { return *static_cast<SimExtras*>(s.extra.get()); }

bool sampleSensors(PySimulation& s) { return extras(s).recorder->sample(extras(s).latest); }

// RS7024 (a reading or sensor pose that was not finite), as rscene-sim says it.
Diagnostic sensorFailure(const PySimulation& s) {
  Diagnostics ds;
  extras(s).recorder->faultDiagnostic(s.doc, ds);
  if (!ds.empty()) return ds.front();
  Diagnostic d;
  d.code = "RS7024";
  d.message = "a sensor's reading was not finite";
  return d;
}

// The names contacts give, and the sensors rscene-sim --sensors would
// record, planned without its output files (two sensors naming one file
// are both kept: Python holds readings, not files).
void prepareExtras(PySimulation& s) {
  auto x = std::make_shared<SimExtras>();
  const Scene& sc = s.prepared.scene;
  auto names = [&](const auto& list) {
    for (const auto& n : list) x->recordPaths[n.recordIndex] = n.path;
  };
  names(sc.objects);
  names(sc.compounds);
  names(sc.terrains);
  names(sc.articulated);
  Diagnostics scratch;  // the preparation reported these already
  std::vector<std::shared_ptr<const robot::Model>> models;
  for (const robot::RobotInstance& r : s.prepared.robots) models.push_back(r.model);
  std::vector<robot::SensorSpec> all = robot::collectSensors(s.doc, sc, models, scratch);
  for (robot::SensorSpec& spec : all) spec.outputPath.clear();
  std::vector<sim::RecordedSensor> planned;
  for (robot::SensorSpec& spec : all) {
    // One at a time, each with an output of its own: planSensors' output
    // clashes are about files, which Python does not write.
    Diagnostics one;
    std::vector<sim::RecordedSensor> p = sim::planSensors(s.doc, {spec}, {}, one);
    for (sim::RecordedSensor& r : p) planned.push_back(std::move(r));
  }
  if (!planned.empty()) {
    for (std::size_t i = 0; i < planned.size(); ++i) {
      x->sensorByName[planned[i].spec.name] = i;
      if (!planned[i].spec.id.empty()) x->sensorByName.emplace(planned[i].spec.id, i);
    }
    x->latest.scans.resize(planned.size());
    x->latest.imus.resize(planned.size());
    x->recorder = std::make_unique<sim::SensorRecorder>(s.prepared.scene, *s.prepared.world, std::move(planned));
  }
  s.extra = x;
}

// Steps `n` times; a failure (a state that is not finite, the pair cap)
// comes back as (diagnostic, false) and ends the simulation: each later
// call gives (that diagnostic, true).  The steps run
// without the GIL in chunks of about 50 ms; between chunks Ctrl-C (any
// Python signal handler that raises) ends the call with KeyboardInterrupt,
// the world stopped between two steps, consistent and steppable again.
py::object stepSimulation(PySimulation& s, long long n) {
  if (n < 0) throw py::value_error("step(n): n must be >= 0");
  // (failure, earlier): Python raises SimulationError with the failure's
  // diagnostic, saying for a later call that it is an earlier one's.
  if (s.failure) return py::make_tuple(diagnosticDict(*s.failure), true);
  // Counted by this call (another thread may step the same world between
  // two chunks).
  std::uint64_t remaining = static_cast<std::uint64_t>(n);
  for (;;) {
    sim::RunResult r;
    bool done;
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(s.mutex);
      sim::World& world = *s.prepared.world;
      sim::RunOptions ro;
      // runWorld steps until the world has taken ro.steps in all.
      ro.steps = world.steps() + std::min(remaining, s.chunk);
      ro.checkStart = !s.started;
      if (extras(s).recorder) ro.sample = [&s] { return sampleSensors(s); };
      std::uint64_t before = world.steps();
      r = sim::runWorld(world, s.doc, ro);
      s.started = true;
      std::uint64_t took = world.steps() - before;
      if (took == s.chunk && r.stepSeconds < 0.025 && s.chunk < (std::uint64_t{1} << 40)) s.chunk *= 2;
      else if (took > 1 && r.stepSeconds > 0.1) s.chunk = std::max<std::uint64_t>(1, s.chunk / 2);
      remaining -= took;
      done = remaining == 0 || took == 0;
    }
    if (r.failure) {
      s.failure = simWords(*r.failure);
      return py::make_tuple(diagnosticDict(*s.failure), false);
    }
    if (r.sampleFailed) {
      s.failure = sensorFailure(s);
      return py::make_tuple(diagnosticDict(*s.failure), false);
    }
    if (done) return py::none();
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
}

// The simulated robot named by `name` (path or id): its index, or -1 with
// what the name is instead ("" when the scene has no such record).
py::tuple robotLookup(const PySimulation& s, const std::string& name) {
  int index = s.prepared.world->robotIndex(name);
  if (index >= 0) return py::make_tuple(index, "");
  const Scene& sc = s.prepared.scene;
  auto is = [&](const auto& list) {
    for (const auto& n : list)
      if (n.path == name || (!n.id.empty() && n.id == name)) return true;
    return false;
  };
  for (const Articulated& a : sc.articulated)
    if (a.path == name || (!a.id.empty() && a.id == name))
      return py::make_tuple(-1, a.leftOut ? "an articulated system left out (its robot file is missing)"
                                          : "an articulated system that is not simulated");
  const char* what = is(sc.objects) ? "an object" : is(sc.compounds) ? "a compound" : is(sc.sensors) ? "a sensor"
                   : is(sc.cameras) ? "a camera" : is(sc.lights) ? "a light" : is(sc.terrains) ? "a terrain region"
                   : is(sc.wires) ? "a wire" : is(sc.deformables) ? "a deformable" : is(sc.granulars) ? "a granular record"
                   : "";
  return py::make_tuple(-1, what);
}

void checkRobot(const PySimulation& s, int robot) {
  if (robot < 0 || robot >= s.prepared.world->robotCount()) throw py::index_error("no robot of that index");
}

py::array_t<double> vectorArray(const Eigen::VectorXd& v) {
  py::array_t<double> a(v.size());
  std::copy(v.data(), v.data() + v.size(), a.mutable_data());
  return a;
}

py::dict robotInfo(const PySimulation& s, int robot) {
  checkRobot(s, robot);
  const robot::RobotInstance& in = s.prepared.world->robotInstance(robot);
  const robot::Model& m = *in.model;
  const robot::Coordinates& c = in.coordinates;
  py::dict o;
  o["path"] = pystr(in.record->path);
  o["id"] = pystr(in.record->id);
  py::list joints;
  for (int j : c.joints) joints.append(pystr(m.joints[static_cast<std::size_t>(j)].name));
  o["joint_names"] = joints;
  py::list qn, un;
  for (const std::string& n : robot::coordinateNames(m, c, false)) qn.append(pystr(n));
  for (const std::string& n : robot::coordinateNames(m, c, true)) un.append(pystr(n));
  o["coordinate_names"] = qn;
  o["velocity_names"] = un;
  o["floating_base"] = m.floatingBase;
  py::list links;
  for (const robot::Link& l : m.links) links.append(pystr(l.name));
  o["link_names"] = links;
  return o;
}

// (q, u) now.
py::tuple robotState(const PySimulation& s, int robot) {
  checkRobot(s, robot);
  Eigen::VectorXd q, u;
  {
    std::lock_guard<std::mutex> l(s.mutex);
    s.prepared.world->robotState(robot, q, u);
  }
  return py::make_tuple(vectorArray(q), vectorArray(u));
}

// Each: "" or why nothing changed (a ValueError in Python).
std::string robotSetPd(PySimulation& s, int robot, const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                       const Eigen::VectorXd& kp, const Eigen::VectorXd& kd) {
  checkRobot(s, robot);
  std::lock_guard<std::mutex> l(s.mutex);
  return s.prepared.world->setRobotPd(robot, q, u, kp, kd);
}

std::string robotSetForce(PySimulation& s, int robot, const Eigen::VectorXd& tau) {
  checkRobot(s, robot);
  std::lock_guard<std::mutex> l(s.mutex);
  return s.prepared.world->setRobotGeneralizedForce(robot, tau);
}

std::string robotSetState(PySimulation& s, int robot, const Eigen::VectorXd& q, const Eigen::VectorXd& u) {
  checkRobot(s, robot);
  std::lock_guard<std::mutex> l(s.mutex);
  return s.prepared.world->setRobotState(robot, q, u);
}

// The sensors recorded: (name, id, kind) each, in the recorder's order.
py::list sensorList(const PySimulation& s) {
  py::list l;
  if (!extras(s).recorder) return l;
  for (const sim::RecordedSensor& r : extras(s).recorder->sensors())
    l.append(py::make_tuple(pystr(r.spec.name), pystr(r.spec.id), pystr(r.spec.kindName)));
  return l;
}

// Index of the sensor named `name` (its name or a record's id), or -1.
long sensorIndex(const PySimulation& s, const std::string& name) {
  auto it = extras(s).sensorByName.find(name);
  return it == extras(s).sensorByName.end() ? -1 : static_cast<long>(it->second);
}

// The latest scan of LiDAR `i`: None before its first, else a dict with
// time, index, pose (7) and points (N, 3) float32 in the sensor frame.
py::object lidarScan(const PySimulation& s, long i) {
  const LatestReadings::Scan* sc;
  py::array_t<float> points;
  py::dict o;
  {
    std::lock_guard<std::mutex> l(s.mutex);
    if (i < 0 || static_cast<std::size_t>(i) >= extras(s).latest.scans.size()) throw py::index_error("no sensor of that index");
    sc = &extras(s).latest.scans[static_cast<std::size_t>(i)];
    if (!sc->any) return py::none();
    points = py::array_t<float>({static_cast<py::ssize_t>(sc->points.size()), py::ssize_t(3)});
    float* p = points.mutable_data();
    for (std::size_t k = 0; k < sc->points.size(); ++k)
      for (int c = 0; c < 3; ++c) p[3 * k + c] = sc->points[k][c];
    o["time"] = sc->time;
    o["index"] = sc->index;
    o["pose"] = poseArray(sc->pose);
  }
  o["points"] = points;
  return o;
}

// The latest reading of IMU `i`: None before its first, else a dict with
// time, specific_force (3) and angular_velocity (3), sensor frame.
py::object imuReading(const PySimulation& s, long i) {
  std::optional<sim::ImuReading> r;
  {
    std::lock_guard<std::mutex> l(s.mutex);
    if (i < 0 || static_cast<std::size_t>(i) >= extras(s).latest.imus.size()) throw py::index_error("no sensor of that index");
    r = extras(s).latest.imus[static_cast<std::size_t>(i)];
  }
  if (!r) return py::none();
  py::dict o;
  o["time"] = r->time;
  o["specific_force"] = vectorArray(r->specificForce);
  o["angular_velocity"] = vectorArray(r->angularVelocity);
  return o;
}

// The contact points after the last step, as numpy arrays: body_a, body_b
// (record paths; "" for none), link_a, link_b (a robot's link, else ""),
// position (N, 3), normal (N, 3: B's, toward A), depth (N), impulse (N).
py::dict contactArrays(const PySimulation& s) {
  std::vector<sim::World::Contact> cs;
  {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> l(s.mutex);
    cs = s.prepared.world->contacts();
  }
  const auto n = static_cast<py::ssize_t>(cs.size());
  py::array_t<double> position({n, py::ssize_t(3)}), normal({n, py::ssize_t(3)}), depth(n), impulse(n);
  py::list a, b, la, lb;
  double* p = position.mutable_data();
  double* nm = normal.mutable_data();
  double* d = depth.mutable_data();
  double* im = impulse.mutable_data();
  const auto& paths = extras(s).recordPaths;
  auto path = [&](int record) -> py::str {
    auto it = paths.find(record);
    return pystr(it == paths.end() ? std::string() : it->second);
  };
  for (std::size_t i = 0; i < cs.size(); ++i) {
    const sim::World::Contact& c = cs[i];
    for (int k = 0; k < 3; ++k) p[3 * i + k] = c.position[k], nm[3 * i + k] = c.normal[k];
    d[i] = c.depth;
    im[i] = c.impulse;
    a.append(path(c.recordA));
    b.append(path(c.recordB));
    la.append(pystr(c.linkA));
    lb.append(pystr(c.linkB));
  }
  py::dict o;
  o["body_a"] = a;
  o["body_b"] = b;
  o["link_a"] = la;
  o["link_b"] = lb;
  o["position"] = position;
  o["normal"] = normal;
  o["depth"] = depth;
  o["impulse"] = impulse;
  return o;
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

std::string saveText(const std::string& path, const std::function<void(Sink&)>& write) {
  if (path.empty()) throw py::value_error("save() needs a path, not an empty string");
  if (path.find('\0') != std::string::npos) throw py::value_error("embedded null byte in path");
  std::string error;
  bool ok;
  {
    py::gil_scoped_release release;
    ok = writeOutputFile(path, [&](Sink& sink) {
      write(sink);
      return true;
    }, &error);
  }
  if (ok) return {};
  return error.empty() ? std::string("cannot write") : error;
}

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
  // The canonical text; the message of a refusal, or "" on success.
  m.def("save", [](const PyDocument& d, py::bytes path) {
    return saveText(std::string(path), [&](Sink& sink) { writeCanonical(d.doc, sink); });
  });
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
        return a;
      })
      .def("robot_lookup", &robotLookup)
      .def("robot_info", &robotInfo)
      .def("robot_state", &robotState)
      .def("robot_set_pd", &robotSetPd)
      .def("robot_set_force", &robotSetForce)
      .def("robot_set_state", &robotSetState)
      .def("contacts", &contactArrays)
      .def("body_paths", [](const PySimulation& s) {
        // Every body contacts may name (objects, compounds, terrains, robots).
        py::list l;
        for (const auto& [record, path] : extras(s).recordPaths) l.append(pystr(path));
        return l;
      })
      .def("sensor_list", &sensorList)
      .def("sensor_index", &sensorIndex)
      .def("lidar_scan", &lidarScan)
      .def("imu_reading", &imuReading)
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
