// Rendering for Python (issue 28): rscene-render's drawing pipeline
// (lib/render: buildRenderScene, collectViews/selectViews/sizeViews, the
// view Renderer) behind one object, `_Renderer`, that keeps its scene
// uploaded across frames and poses.  A simulation's poses reach it the way
// `rscene-sim --trajectory | rscene-render --trajectory` carries them: one
// trajectory frame of the world's states, read back and applied by the
// same poser (robot/trajectory_read.hpp), so a drawn frame is what the
// tool draws for that frame.
//
// One EGL context serves the whole process (EGL displays are shared within
// a process, and GlContext's destructor terminates its display): every GL
// call runs under one mutex with the context made current on the calling
// thread, with the GIL released.
//
// Built only where lib/render is (RSCENE_PYTHON_RENDER); elsewhere the
// functions say rendering is not available.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"

#ifdef RSCENE_PYTHON_RENDER
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <tuple>
#include <algorithm>
#include <string>
#include <vector>

#include "core/assets.hpp"
#include "core/project.hpp"
#include "render/camera.hpp"
#include "render/gl_context.hpp"
#include "render/limits.hpp"
#include "render/render_scene.hpp"
#include "render/renderer.hpp"
#include "render/view.hpp"
#include "render/view_output.hpp"
#include "render/view_select.hpp"
#include "render/views.hpp"
#include "robot/sensors.hpp"
#include "robot/trajectory_format.hpp"
#include "robot/trajectory_read.hpp"
#include "sim/world.hpp"

namespace rscene::python {
namespace {

// The process's one context, made on first use and kept to the end (never
// destroyed: renderers freed at exit still find it).
struct SharedGl {
  std::mutex mutex;
  render::GlContext* context = nullptr;
  std::string error;
};
SharedGl& sharedGl() {
  static SharedGl* gl = new SharedGl;
  return *gl;
}

// Holds the GL mutex with the context current on this thread.  Take it
// with the GIL released.
class GlLock {
 public:
  GlLock() : lock_(sharedGl().mutex) {
    SharedGl& gl = sharedGl();
    if (!gl.context) {
      if (!gl.error.empty()) return;
      std::string error;
      gl.context = render::GlContext::create(render::Backend::Auto, &error).release();
      if (!gl.context) {
        gl.error = "cannot create an OpenGL context: " + (error.empty() ? std::string("no EGL display") : error);
        return;
      }
    } else if (!gl.context->makeCurrent()) {
      error_ = "cannot make the OpenGL context current on this thread";
      return;
    }
    ok_ = true;
  }
  ~GlLock() {
    if (ok_) sharedGl().context->release();
  }
  bool ok() const { return ok_; }
  std::string error() const { return error_.empty() ? sharedGl().error : error_; }

 private:
  std::lock_guard<std::mutex> lock_;
  bool ok_ = false;
  std::string error_;
};

// A failure with the findings that explain it: Python raises RenderError.
struct RenderFailure {
  std::string message;
  Diagnostics diagnostics;
  bool environment = false;  // no OpenGL here: RuntimeError, not the scene's fault
};

// The tools' flag names in lib/render's messages and hints, as the Python
// arguments say them; a limit Python cannot raise is named as a limit.
std::string pythonWords(std::string s) {
  auto replace = [&](const std::string& from, const std::string& to) {
    for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
      s.replace(at, from.size(), to);
  };
  replace("give --width and --height, or raise --max-pixels", "give a smaller width and height");
  replace("raise --max-pixels, or give the sensor", "give the sensor");
  replace(", or raise --max-instances", "");
  replace("--max-instances", "the instance limit");
  replace("--allow-missing-assets", "allow_missing_assets=True");
  replace("rscene-render draws cameras and camera-like sensors; rscene-sim --sensors records it",
          "cameras and camera-like sensors are drawn; Simulation.lidar() and imu() read it");
  replace("--width and --height", "width and height");
  replace("--width/--height", "width/height");
  replace("--max-pixels", "the pixel limit");
  replace("--camera auto", "camera='auto'");
  replace("--camera", "camera");
  replace("leave out camera", "give camera=None");
  return s;
}

// What a draw call asks for: a view by name (camera, sensor, "auto", ""
// for the first enabled camera) or the look-at form, a size, the passes.
struct ViewChoice {
  std::string camera;
  bool lookAt = false;
  Eigen::Vector3d from = Eigen::Vector3d::Zero(), to = Eigen::Vector3d::UnitX();
  double fov = 50;
  int width = 0, height = 0;
};

// Where makeRenderer() placed everything a simulation's poses move: a
// plain draw after draw(sim) puts it all back, exactly (the document as
// written, as a fresh renderer draws it).
struct RestPlaces {
  struct Placed {
    Eigen::Affine3d world;
    Eigen::AlignedBox3d bounds, localBounds;
    std::optional<Eigen::Affine3d> placeholderWorld;
  };
  std::vector<Placed> drawables;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> wires;
  std::vector<std::vector<Eigen::Vector3f>> surfaces;
  struct Batch {
    std::vector<Eigen::Affine3d> worlds;
    std::vector<Eigen::AlignedBox3d> instanceBounds;
    Eigen::AlignedBox3d bounds;
  };
  std::vector<Batch> instanced;
  Eigen::AlignedBox3d bounds;

  void keep(const render::RenderScene& s) {
    for (const render::Drawable& d : s.drawables) drawables.push_back({d.world, d.bounds, d.localBounds, d.placeholderWorld});
    for (const render::WireSpan& w : s.wires) wires.emplace_back(w.a, w.b);
    for (const render::DeformedSurface& f : s.surfaces) surfaces.push_back(f.positions);
    for (const render::Instanced& b : s.instanced) instanced.push_back({b.worlds, b.instanceBounds, b.bounds});
    bounds = s.bounds;
  }
  void restore(render::RenderScene& s) const {
    for (std::size_t i = 0; i < drawables.size() && i < s.drawables.size(); ++i) {
      render::Drawable& d = s.drawables[i];
      d.world = drawables[i].world;
      d.bounds = drawables[i].bounds;
      d.localBounds = drawables[i].localBounds;
      d.placeholderWorld = drawables[i].placeholderWorld;
    }
    for (std::size_t i = 0; i < wires.size() && i < s.wires.size(); ++i) std::tie(s.wires[i].a, s.wires[i].b) = wires[i];
    for (std::size_t i = 0; i < surfaces.size() && i < s.surfaces.size(); ++i)
      if (s.surfaces[i].positions != surfaces[i]) {
        s.surfaces[i].positions = surfaces[i];
        ++s.surfaces[i].version;  // re-uploaded
      }
    for (std::size_t i = 0; i < instanced.size() && i < s.instanced.size(); ++i) {
      render::Instanced& b = s.instanced[i];
      if (b.worlds.size() == instanced[i].worlds.size() &&
          std::equal(b.worlds.begin(), b.worlds.end(), instanced[i].worlds.begin(),
                     [](const Eigen::Affine3d& x, const Eigen::Affine3d& y) { return x.matrix() == y.matrix(); }))
        continue;
      b.worlds = instanced[i].worlds;
      b.instanceBounds = instanced[i].instanceBounds;
      b.bounds = instanced[i].bounds;
      ++b.version;  // re-uploaded
    }
    s.bounds = bounds;
  }
};

struct PyRenderer {
  std::shared_ptr<PyDocument> source;
  std::string display;  // the scene's name in messages
  std::unique_ptr<asset::AssetCache> assets;
  Scene model;
  render::RenderScene scene;
  render::RenderOptions options;
  std::vector<robot::SensorSpec> sensors;
  robot::BodyPoses rest, poses;
  robot::ParticlePositions particles;
  RestPlaces restPlaces;     // the scene as built, for a plain draw after draw(sim)
  std::vector<render::View> views;  // every view of the scene, at rest
  std::unique_ptr<robot::TrajectoryPoser> poser;
  std::unique_ptr<render::Renderer> renderer;  // freed under the GL lock
  Diagnostics warnings;
  std::string legend;
  std::uint64_t frame = 0;   // draws so far: a sensor's noise seed moves on per frame, as rscene-render's
  bool still = false;        // made for one view at rest (render()): tessellated for it, poses fixed
  bool moved = false;        // posed by a simulation: a plain draw puts the scene back at rest first
  std::vector<Camera> particleViews;  // the cameras particles were last tessellated for
  std::mutex mutex;          // one draw at a time

  ~PyRenderer() {
    if (!renderer) return;
    py::gil_scoped_release release;
    GlLock gl;
    renderer.reset();  // without a context (none could be made) there is nothing to free
  }
};

std::string failureText(const std::string& message, const Diagnostics& ds) {
  if (!message.empty()) return message;
  for (const Diagnostic& d : ds)
    if (d.severity == Severity::Error) return d.message;
  return "cannot render the scene";
}

// lib/render's findings as Python shows them (pythonWords).
Diagnostic pythonDiagnostic(Diagnostic d) {
  d.message = pythonWords(std::move(d.message));
  d.hint = pythonWords(std::move(d.hint));
  return d;
}

void keepWarnings(PyRenderer& r, const Diagnostics& ds) {
  for (const Diagnostic& d : ds)
    if (d.severity != Severity::Error) r.warnings.push_back(pythonDiagnostic(d));
}

// The one view `choice` names, sized and posed; throws RenderFailure.
render::View chooseView(PyRenderer& r, const ViewChoice& choice, std::vector<std::string>& warnings) {
  render::ViewRequest request;
  request.camera = choice.camera;
  request.width = choice.width;
  request.height = choice.height;
  request.lookAt = choice.lookAt;
  request.lookFrom = choice.from;
  request.lookTo = choice.to;
  request.lookFov = choice.fov;
  if (choice.lookAt)
    if (std::string why = render::lookAtProblem(choice.from, choice.to, choice.fov); !why.empty())
      throw RenderFailure{"look-at camera: " + why, {}};
  render::ViewSources sources{r.source->doc, r.model, r.scene, r.sensors, r.display};
  render::ViewFindings found;
  std::vector<render::View> chosen = render::selectViews(r.views, request, sources, found);
  if (!found.ok()) throw RenderFailure{pythonWords(found.error), found.diagnostics};
  render::sizeViews(chosen, request, sources, found);
  if (!found.ok()) throw RenderFailure{pythonWords(found.error), found.diagnostics};
  for (const std::string& w : found.warnings) warnings.push_back(pythonWords(w));
  if (chosen.size() != 1) throw RenderFailure{"no view to draw", {}};
  if (r.moved) render::poseViews(chosen, r.model, r.scene, r.sensors, r.rest, r.poses);
  if (std::string why = render::viewProblem(chosen[0]); !why.empty())
    throw RenderFailure{"view '" + chosen[0].name + "': " + why, {}};
  return chosen[0];
}

// Builds the scene of `doc` as rscene-render does; the renderer itself is
// made by the first draw (in the GL lock).
// `baseDir` (rscene-render --base-dir): where relative asset paths
// resolve, in place of the document's folder; `allowMissing`
// (--allow-missing-assets): a missing mesh drawn as a placeholder, a robot
// whose file is missing left out, each with a warning.
std::unique_ptr<PyRenderer> makeRenderer(const std::shared_ptr<PyDocument>& doc, int samples, bool post,
                                         bool transparent, bool allowMissing, const std::string& baseDir) {
  auto r = std::make_unique<PyRenderer>();
  r->source = doc;
  r->display = doc->path.empty() ? std::string("<scene>") : doc->path;
  r->options.samples = samples;
  r->options.post = post;
  r->options.transparent = transparent;
  r->options.allowMissingAssets = allowMissing;
  r->assets = std::make_unique<asset::AssetCache>(diskFileSystem(), render::assetLimits(r->options));
  r->options.assets = r->assets.get();
  SceneOptions so;
  so.sceneDir = doc->path.empty() ? std::string(".") : directoryOf(doc->path);
  so.baseDir = baseDir;
  // As the tool finds the project: from the scene's folder, or for a scene
  // with no file (stdin there) from the base folder.
  std::string projectDir = doc->path.empty() ? baseDir : so.sceneDir;
  if (!projectDir.empty()) so.project = projectPlaceOf(projectDir, diskFileSystem());
  render::DrawLimits limits;
  limits.allowMissingAssets = allowMissing;
  Diagnostics diags;
  if (!render::buildRenderScene(doc->doc, so, r->model, r->scene, diags, limits, r->assets.get()))
    throw RenderFailure{"", diags};
  keepWarnings(*r, diags);
  diags.clear();
  r->sensors = robot::collectSensors(doc->doc, r->model, r->scene.robotModels, diags);
  r->rest = robot::restPoses(r->model, r->scene.robotModels);
  r->poses = r->rest;
  r->views = render::collectViews(doc->doc, r->model, r->scene, r->sensors, r->rest, diags);
  if (hasErrors(diags)) throw RenderFailure{"", diags};
  keepWarnings(*r, diags);
  r->legend = render::segmentationLegendJson(r->scene);
  r->restPlaces.keep(r->scene);
  return r;
}

// The simulation's state now, as one trajectory frame written and read
// back (what rscene-sim --trajectory hands rscene-render --trajectory),
// applied to the renderer's scene.  Under r.mutex, with the GIL released.
void poseFromSimulation(PyRenderer& r, PySimulation& s) {
  std::string text;
  double time = 0;
  {
    std::lock_guard<std::mutex> lock(s.mutex);
    const sim::World& world = *s.prepared.world;
    std::vector<robot::RobotState> robots = world.robotStates();
    robot::TrajectoryWriter writer(robot::TrajectoryFormat::Jsonl, robots);
    time = world.time();
    writer.append(text, time, world.states(), robots, world.particleStates());
  }
  r.poses = r.rest;
  if (!text.empty()) {
    if (!r.poser)
      r.poser = std::make_unique<robot::TrajectoryPoser>(r.model, r.scene.robotModels, render::particleCounts(r.scene));
    std::istringstream in(text);
    robot::TrajectoryReader reader(in, "<simulation>", render::trajectoryLimits(r.scene));
    robot::TrajectoryFrame frame;
    Diagnostics diags;
    if (!reader.next(frame, diags) || !r.poser->apply(frame, "<simulation>", r.poses, diags, &r.particles)) {
      std::string why = failureText("", diags);
      throw RenderFailure{"the simulation does not match the renderer's scene (make both from one document): " + why,
                          {}};
    }
  }
  render::poseScene(r.scene, {&r.poses.objects, &r.poses.compounds, &r.poses.robotLinks, &r.particles});
  r.moved = true;
}

// Back to the document as written after draw(sim) (a plain draw shows
// what a fresh renderer shows).  The next frame of a simulation moves every
// particle record again: its versions differ from those restored.
void poseAtRest(PyRenderer& r) {
  r.poses = r.rest;
  r.restPlaces.restore(r.scene);
  for (auto* list : {&r.particles.deformables, &r.particles.granulars})
    for (robot::ParticlePositions::Record& p : *list) {
      p.given = false;
      p.points.clear();
    }
  for (render::DeformedSurface& f : r.scene.surfaces) f.framesVersion = ~std::uint64_t{0};
  for (render::Instanced& b : r.scene.instanced) b.framesVersion = ~std::uint64_t{0};
  r.moved = false;
}

struct Drawn {
  render::ViewImages images;
  std::string view;
  std::vector<std::string> warnings;  // of choosing the view (a sensor keeps its own size)
};

// Draws `choice` with `passes`, after posing from `sim` when given.
Drawn draw(PyRenderer& r, PySimulation* sim, const ViewChoice& choice, const std::vector<render::Pass>& passes) {
  std::lock_guard<std::mutex> lock(r.mutex);
  bool reset = false;
  if (sim) {
    if (r.still) throw RenderFailure{"this renderer draws the scene at rest only", {}};
    poseFromSimulation(r, *sim);
  } else if (r.moved) {
    poseAtRest(r);
    reset = true;
  }
  Drawn out;
  render::View view = chooseView(r, choice, out.warnings);
  view.passes = passes;
  // Sensor noise is drawn anew at each frame, as rscene-render's frames are.
  view.noiseSeed += r.frame * 0x9E3779B97F4A7C15ull;
  GlLock gl;
  if (!gl.ok()) throw RenderFailure{gl.error(), {}, true};
  Diagnostics diags;
  if (!r.renderer) {
    // render(): tessellated for its one view, as rscene-render's still is
    // (same pixels); a Renderer: for any view and pose, as along a
    // trajectory.
    r.renderer = r.still ? render::createRenderer(r.scene, r.options, diags, {view.camera})
                         : render::Renderer::create(r.scene, r.options, diags);
    if (!r.renderer) throw RenderFailure{"", diags};
    keepWarnings(r, diags);
    diags.clear();
  } else if (sim || reset) {
    r.renderer->updatePoses();
  }
  auto samePlace = [](const Camera& a, const Camera& b) {
    return a.world.position == b.world.position && a.world.orientation.coeffs() == b.world.orientation.coeffs();
  };
  if (!r.still && (sim || reset || r.particleViews.size() != 1 || !samePlace(r.particleViews[0], view.camera))) {
    r.particleViews = {view.camera};
    r.renderer->setParticleViews(r.particleViews);
  }
  out.view = view.name;
  if (!r.renderer->render(view, out.images, diags)) throw RenderFailure{"", diags};
  keepWarnings(r, diags);
  ++r.frame;
  return out;
}

render::Pass passOf(const std::string& name) {
  if (name == "rgb" || name == "color") return render::Pass::Color;
  if (name == "depth") return render::Pass::Depth;
  if (name == "segmentation") return render::Pass::Segmentation;
  throw py::value_error("unknown pass '" + name + "': use 'rgb', 'depth' or 'segmentation'");
}

py::array_t<std::uint8_t> rgbaArray(const render::Image& image) {
  py::array_t<std::uint8_t> a({image.height, image.width, 4});
  if (!image.rgba.empty()) std::memcpy(a.mutable_data(), image.rgba.data(), image.rgba.size());
  return a;
}

py::array_t<float> depthArray(const std::vector<float>& depth, int width, int height) {
  py::array_t<float> a({height, width});
  if (!depth.empty()) std::memcpy(a.mutable_data(), depth.data(), depth.size() * sizeof(float));
  return a;
}

// A ValueError subclass made by __init__.py: (message, diagnostics).
// `scene`: the document's path, for the diagnostics' file names.
[[noreturn]] void raise(const RenderFailure& f, const std::string& scene) {
  if (f.environment) throw std::runtime_error(f.message);
  py::module_ pkg = py::module_::import("rscene");
  py::object error = pkg.attr("_render_error");
  Diagnostics shown;
  for (const Diagnostic& d : f.diagnostics) shown.push_back(pythonDiagnostic(d));
  py::object exc = error(pystr(failureText(f.message, shown)), diagnosticList(shown), pystr(scene));
  PyErr_SetObject(exc.get_type().ptr(), exc.ptr());
  throw py::error_already_set();
}

ViewChoice choiceOf(const py::object& camera, const py::object& look, int width, int height) {
  ViewChoice c;
  if (width < 0 || height < 0) throw py::value_error("width and height must be positive");
  if (width > render::kMaxImageSide || height > render::kMaxImageSide)
    throw py::value_error("width/height: at most " + std::to_string(render::kMaxImageSide) + " pixels a side");
  c.width = width;
  c.height = height;
  if (!camera.is_none()) c.camera = camera.cast<std::string>();
  if (!look.is_none()) {
    auto t = look.cast<std::tuple<std::vector<double>, std::vector<double>, double>>();
    const auto& [from, to, fov] = t;
    if (from.size() != 3 || to.size() != 3) throw py::value_error("look-at: position and target are 3 numbers each");
    c.lookAt = true;
    c.from = Eigen::Vector3d(from[0], from[1], from[2]);
    c.to = Eigen::Vector3d(to[0], to[1], to[2]);
    c.fov = fov;
  }
  return c;
}

}  // namespace

void bindRender(py::module_& m) {
  m.attr("render_available") = true;
  py::class_<PyRenderer>(m, "_Renderer")
      .def_property_readonly("legend", [](const PyRenderer& r) { return pystr(r.legend); })
      .def_property_readonly("diagnostics", [](const PyRenderer& r) { return diagnosticList(r.warnings); })
      .def_property_readonly("views", [](const PyRenderer& r) {
        py::list l;
        for (const render::View& v : r.views) {
          py::dict d;
          d["name"] = pystr(v.name);
          d["id"] = pystr(v.id);
          d["sensor"] = v.sensor;
          d["enabled"] = v.camera.enabled;
          d["width"] = v.camera.width;
          d["height"] = v.camera.height;
          l.append(d);
        }
        return l;
      })
      .def_property_readonly("backend", [](const PyRenderer&) -> py::object {
        SharedGl& gl = sharedGl();
        std::lock_guard<std::mutex> lock(gl.mutex);
        if (!gl.context) return py::none();
        const render::ContextInfo& i = gl.context->info();
        return py::make_tuple(i.backend, pystr(i.renderer));
      })
      .def("draw", [](PyRenderer& r, py::object sim, py::object camera, py::object look, int width, int height,
                      std::vector<std::string> passNames) {
        std::vector<render::Pass> passes;
        for (const std::string& n : passNames) passes.push_back(passOf(n));
        if (passes.empty()) throw py::value_error("no pass to draw");
        ViewChoice choice = choiceOf(camera, look, width, height);
        PySimulation* s = sim.is_none() ? nullptr : sim.cast<PySimulation*>();
        Drawn d;
        bool failed = false;
        RenderFailure failure;
        {
          py::gil_scoped_release release;
          try {
            d = draw(r, s, choice, passes);
          } catch (RenderFailure& f) {
            failure = std::move(f);
            failed = true;
          }
        }
        if (failed) raise(failure, r.source->path);
        py::dict out;
        py::list warnings;
        for (const std::string& w : d.warnings) warnings.append(pystr(w));
        out["warnings"] = warnings;
        out["view"] = pystr(d.view);
        for (render::Pass p : passes) {
          if (p == render::Pass::Color) out["rgb"] = rgbaArray(d.images.color);
          if (p == render::Pass::Depth) out["depth"] = depthArray(d.images.depth, d.images.width, d.images.height);
          if (p == render::Pass::Segmentation) out["segmentation"] = rgbaArray(d.images.segmentation);
        }
        return out;
      });
  m.def("renderer", [](const std::shared_ptr<PyDocument>& doc, bool still, int samples, bool post, bool transparent,
                       bool allowMissing, py::bytes baseDirBytes) {
    if (samples < 1 || samples > 64) throw py::value_error("samples must be 1 to 64");
    std::string baseDir(baseDirBytes);
    if (baseDir.find('\0') != std::string::npos) throw py::value_error("embedded null byte in base_dir");
    std::unique_ptr<PyRenderer> r;
    bool failed = false;
    RenderFailure failure;
    {
      py::gil_scoped_release release;
      try {
        r = makeRenderer(doc, samples, post, transparent, allowMissing, baseDir);
        r->still = still;
      } catch (RenderFailure& f) {
        failure = std::move(f);
        failed = true;
      }
    }
    if (failed) raise(failure, doc->path);
    return r;
  });
}

}  // namespace rscene::python

#else  // no lib/render in this build

namespace rscene::python {
void bindRender(py::module_& m) { m.attr("render_available") = false; }
}  // namespace rscene::python

#endif
