// rscene-diff --review: the two scenes drawn from one camera on one
// OpenGL context, the changes marked from the id pass (render/
// review_highlight.hpp), and the folder written (review.hpp).
#include "rscene-diff/review.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <future>
#include <optional>

#include "core/assets.hpp"
#include "render/camera.hpp"
#include "render/gl_context.hpp"
#include "render/image.hpp"
#include "render/limits.hpp"
#include "render/render_scene.hpp"
#include "render/renderer.hpp"
#include "render/review_highlight.hpp"
#include "render/view.hpp"

namespace rscene::diffout {
namespace {

namespace review = render::review;

std::string join(const std::string& dir, const char* name) {
  return (std::filesystem::path(dir) / name).string();
}

bool writeFile(const std::string& path, const std::string& bytes) {
  return cli::writeOutput(path, [&](Sink& sink) {
    sink.write(bytes);
    return true;
  });
}

// One side built for drawing; an empty side (/dev/null) draws nothing.
struct Built {
  render::RenderScene scene;
  Scene model;
  std::vector<review::Item> items;
  render::ViewImages images;
  bool empty = false;
  bool failed = false;  // did not build
  Diagnostics diagnostics;  // of building, then of drawing; printed for both sides at once
};

// rscene-diff already said what the parser found; building says the rest:
// the new scene's all, the old one's errors and the warnings the new one
// has not (a mesh missing on both sides is said once).
void printBuilt(Built& a, const ReviewSide& before, Built& b, const ReviewSide& after) {
  auto same = [](const Diagnostic& x, const Diagnostic& y) {
    return x.code == y.code && x.message == y.message && x.file == y.file;
  };
  Diagnostics old;
  for (const Diagnostic& d : a.diagnostics)
    if (d.severity == Severity::Error ||
        std::none_of(b.diagnostics.begin(), b.diagnostics.end(), [&](const Diagnostic& n) { return same(d, n); }))
      old.push_back(d);
  cli::printDiagnostics(old, before.name, before.text, cli::colorFor(2));
  cli::printDiagnostics(b.diagnostics, after.name, after.text, cli::colorFor(2));
}

bool build(const ReviewSide& side, Built& out, asset::AssetCache& assets) {
  out.empty = side.empty;
  if (side.empty) return true;
  SceneOptions so;
  so.sceneDir = side.input.path.empty() ? "." : directoryOf(side.input.path);
  so.project = cli::projectPlace(side.input, "");
  Diagnostics diags;
  // A review shows what changed even where a mesh or texture is not at
  // hand (a CI checkout without its LFS files): a missing one is a warning
  // and drawn as rscene-render --allow-missing-assets draws it.
  render::DrawLimits limits;
  limits.allowMissingAssets = true;
  bool ok = render::buildRenderScene(side.document, so, out.model, out.scene, diags, limits, &assets);
  out.failed = !ok;
  cli::hintStdinPaths(side.input, "", diags);
  out.diagnostics = std::move(diags);
  if (!ok) return false;
  out.items = review::assignItemIds(out.scene);
  return true;
}

// Each robot file's line -> the lines of the robots that use it.
review::Referrers robotUsers(const Built& side, const Document& doc) {
  review::Referrers out;
  if (side.empty) return out;
  auto lineOf = [&](int record) {
    return record >= 0 && std::size_t(record) < doc.records.size() ? doc.records[std::size_t(record)].line : 0u;
  };
  for (const Articulated& a : side.model.articulated)
    if (std::uint32_t from = lineOf(a.resourceRecord), to = lineOf(a.recordIndex); from && to) out.emplace(from, to);
  return out;
}

bool sameCamera(const Camera& a, const Camera& b) {
  auto close = [](double x, double y) { return std::abs(x - y) <= 1e-9; };
  return a.path == b.path && (a.world.position - b.world.position).cwiseAbs().maxCoeff() <= 1e-9 &&
         a.world.orientation.angularDistance(b.world.orientation) <= 1e-9 && close(a.verticalFov, b.verticalFov) &&
         close(a.horizontalFov, b.horizontalFov) && a.projection == b.projection &&
         close(a.orthoScale, b.orthoScale) && a.width == b.width && a.height == b.height;
}

const Camera* firstEnabled(const Built& b) {
  if (b.empty) return nullptr;
  for (const Camera& c : b.scene.cameras)
    if (c.enabled) return &c;
  return nullptr;
}

// The one camera both scenes are drawn from.  False (printed) when
// --camera names none.
bool chooseCamera(const ReviewOptions& o, const Built& a, const Built& b, const review::Marks& marks, Camera& out,
                  std::string& how) {
  Eigen::AlignedBox3d all;
  for (const Built* s : {&a, &b})
    if (!s->empty && !s->scene.bounds.isEmpty()) all.extend(s->scene.bounds);
  if (all.isEmpty()) all = Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, 0), Eigen::Vector3d(1, 1, 1));
  auto sized = [&](Camera c) {
    render::ImageSize size = render::cameraImageSize(c, o.width, o.height);
    c.width = size.width, c.height = size.height;
    return c;
  };
  auto framed = [&](const Eigen::AlignedBox3d& box) {
    Camera c;
    render::ImageSize size = render::cameraImageSize(c, o.width, o.height);
    c = review::frameBox(box, double(size.width) / size.height);
    c.width = size.width, c.height = size.height;
    return c;
  };
  // What changed, at least 1 m across (a moved cup is seen with what
  // stands around it); autoCamera() leaves a margin of its own.
  auto framedChanges = [&](Camera& c) {
    if (marks.bounds.isEmpty()) return false;
    Eigen::AlignedBox3d box = marks.bounds;
    Eigen::Vector3d grow = (Eigen::Vector3d::Constant(1.0) - box.sizes()).cwiseMax(0.0) / 2;
    box.min() -= grow;
    box.max() += grow;
    c = framed(box);
    how = "the automatic view of what changed";
    return true;
  };
  if (o.camera == "changes" && framedChanges(out)) return true;
  if (o.camera == "auto" || o.camera == "changes") {  // changes: nothing drawn changed
    out = framed(all);
    how = "the automatic view of both scenes";
    return true;
  }
  if (!o.camera.empty()) {
    for (const Built* s : {&b, &a}) {
      if (s->empty) continue;
      for (const Camera& c : s->scene.cameras)
        if (c.path == o.camera || c.id == o.camera) {
          out = sized(c);
          how = "camera " + c.path + (s == &a ? " (the old scene's)" : "");
          return true;
        }
    }
    std::string error;
    Camera unused;
    render::chooseCamera((b.empty ? a : b).scene, o.camera, unused, &error);
    cli::error("--camera: " + (error.empty() ? "no camera with path or id '" + o.camera + "'" : error));
    return false;
  }
  const Camera* ca = firstEnabled(a);
  const Camera* cb = firstEnabled(b);
  if (ca && cb && sameCamera(*ca, *cb)) {
    out = sized(*cb);
    how = "camera " + cb->path + ", the scenes' own";
    return true;
  }
  if (framedChanges(out)) return true;
  out = framed(all);
  how = "the automatic view of both scenes";
  return true;
}

render::Image greyImage(int w, int h) {
  render::Image im;
  im.width = w, im.height = h;
  im.rgba.assign(std::size_t(w) * h * 4, 255);
  for (std::size_t i = 0; i < im.rgba.size(); i += 4) im.rgba[i] = im.rgba[i + 1] = im.rgba[i + 2] = 200;
  return im;
}

// Draws the side's colour image and, when it has marked parts (`ids`),
// its id image (else one of background only: nothing of it is marked).
bool draw(Built& side, const Camera& camera, asset::AssetCache& assets, bool ids) {
  auto noIds = [&] {
    side.images.segmentation = render::Image{
        camera.width, camera.height, std::vector<std::uint8_t>(std::size_t(camera.width) * camera.height * 4, 0)};
  };
  if (side.empty) {
    side.images.color = greyImage(camera.width, camera.height);
    noIds();
    return true;
  }
  render::RenderOptions ro;
  ro.assets = &assets;
  ro.allowMissingAssets = true;
  Diagnostics diags;
  auto renderer = render::createRenderer(side.scene, ro, diags, {camera});
  bool ok = renderer != nullptr;
  if (ok) {
    render::View view;
    view.name = camera.path;
    view.camera = camera;
    view.passes = {render::Pass::Color};
    if (ids) view.passes.push_back(render::Pass::Segmentation);
    ok = renderer->render(view, side.images, diags);
  }
  if (!ids) noIds();
  bool fine = ok && !hasErrors(diags);
  side.diagnostics = std::move(diags);  // printed with the other side's (printBuilt)
  return fine;
}

// Images of an earlier review would show another change.
void removeImages(const std::string& dir) {
  for (const char* name : {"before.png", "after.png", "changes.png"}) {
    std::error_code ec;
    std::filesystem::remove(join(dir, name), ec);
  }
}

// Whether an id image shows a part marked on its side.
bool showsMarks(const render::Image& ids, const std::vector<review::Mark>& marks) {
  for (int y = 0; y < ids.height; ++y)
    for (int x = 0; x < ids.width; ++x)
      if (int i = review::itemAt(ids, x, y, marks.size()); i >= 0 && marks[std::size_t(i)] != review::Mark::None)
        return true;
  return false;
}

std::string summaryNote(const std::string& how, const review::Marks& m) {
  std::string s = "Drawn from " + how + ".";
  if (m.undrawn)
    s += " " + std::to_string(m.undrawn) + (m.undrawn == 1 ? " record of the change is" : " records of the change are") +
         " not drawn as bodies (lights, environment, cameras ...): see the table.";
  return s;
}

}  // namespace

bool prepareReviewDir(const std::string& dir) {
  struct stat st {};
  if (::lstat(dir.c_str(), &st) == 0) {
    if (S_ISLNK(st.st_mode)) {
      cli::error("--review: '" + dir + "' is a symbolic link; give a folder (it is made when missing)");
      return false;
    }
    if (!S_ISDIR(st.st_mode)) {
      cli::error("--review: '" + dir + "' exists and is not a folder");
      return false;
    }
  } else {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) {
      cli::error("--review: cannot make the folder '" + dir + "': " + ec.message());
      return false;
    }
  }
  std::vector<cli::NamedOutput> outputs;
  for (const char* name : kReviewFiles) outputs.push_back({"--review", join(dir, name)});
  return cli::checkOutputs(outputs);
}

int writeReview(const ReviewOptions& o, const ReviewSide& before, const ReviewSide& after, const DiffResult& result) {
  // One cache for both scenes: a mesh or texture they share is read once.
  render::RenderOptions defaults;
  asset::AssetCache assets(diskFileSystem(), render::assetLimits(defaults));
  Built a, b;
  // The scenes are built while the OpenGL context starts (the context is
  // the calling thread's; the asset cache is the builder's alone until it
  // is done).
  auto built = std::async(std::launch::async, [&] {
    bool ok = build(before, a, assets) && build(after, b, assets);
    printBuilt(a, before, b, after);
    return ok;
  });
  render::Backend backend = o.backend == "gpu" ? render::Backend::Gpu
                            : o.backend == "cpu" ? render::Backend::Cpu
                                                 : render::Backend::Auto;
  std::string error;
  std::unique_ptr<render::GlContext> context;
  if (!before.empty || !after.empty) context = render::GlContext::create(backend, &error);
  if (!built.get()) {
    // The change is still told, without images.
    removeImages(o.dir);
    std::string note = "A scene does not build (" + std::string(a.failed ? before.name : after.name) +
                       "; rscene-validate says why): no images are drawn.";
    writeFile(join(o.dir, "review.md"), reviewMarkdown(before.name, after.name, result, false, note));
    writeFile(join(o.dir, "index.html"), reviewHtml(before.name, after.name, result, "", "", "", note, ""));
    return cli::kTrouble;
  }
  if (!context && (!before.empty || !after.empty)) {
    cli::error("--review: cannot create an OpenGL context: " + error);
    return cli::kTrouble;
  }
  review::Marks marks = review::markChanges(result, a.scene, a.items, b.scene, b.items,
                                            robotUsers(a, before.document), robotUsers(b, after.document));
  Camera camera;
  std::string how;
  if (!chooseCamera(o, a, b, marks, camera, how)) return cli::kTrouble;
  if (std::string problem = render::imageSizeProblem(camera.width, camera.height, render::kDefaultMaxPixels);
      !problem.empty()) {
    cli::error("--review: " + problem);
    return cli::kTrouble;
  }
  // One context: the old scene's renderer is gone before the new one's is made.
  // before.png is encoded while the new scene is drawn.
  auto encode = [](const render::Image* im) { return render::encodePng(*im); };
  auto marked = [](const std::vector<review::Mark>& side) {
    return std::any_of(side.begin(), side.end(), [](review::Mark k) { return k != review::Mark::None; });
  };
  if (!draw(a, camera, assets, marked(marks.oldSide))) {
    printBuilt(a, before, b, after);
    return cli::kTrouble;
  }
  auto beforePng = std::async(std::launch::async, encode, &a.images.color);
  bool drawn = draw(b, camera, assets, marked(marks.newSide));
  printBuilt(a, before, b, after);  // what drawing found (a missing mesh), said once
  if (!drawn) return cli::kTrouble;
  auto afterPng = std::async(std::launch::async, encode, &b.images.color);
  render::Image changes = review::composeChanges(b.images.color, b.images.segmentation, a.images.segmentation, marks,
                                                         &a.images.color);
  std::string changesPng = render::encodePng(changes);
  std::string bp = beforePng.get(), ap = afterPng.get();
  std::string note = summaryNote(how, marks);
  if (marks.added + marks.removed + marks.changed > 0 && !showsMarks(a.images.segmentation, marks.oldSide) &&
      !showsMarks(b.images.segmentation, marks.newSide)) {
    std::string unseen = "what changed is out of the view of " + how + ": --camera changes frames it";
    cli::warning("--review: " + unseen);
    note += " Note: " + unseen + ".";
  }
  std::string md = reviewMarkdown(before.name, after.name, result, true, note);
  std::string html = reviewHtml(before.name, after.name, result, bp, ap, changesPng, note, "");
  if (!writeFile(join(o.dir, "before.png"), bp) || !writeFile(join(o.dir, "after.png"), ap) ||
      !writeFile(join(o.dir, "changes.png"), changesPng) || !writeFile(join(o.dir, "review.md"), md) ||
      !writeFile(join(o.dir, "index.html"), html))
    return cli::kTrouble;
  return result.same() ? cli::kSuccess : cli::kFindings;
}

int writeLineReview(const ReviewOptions& o, const std::string& oldName, const std::string& newName,
                    const std::string& lines) {
  DiffResult none;
  std::string note = "A side does not parse: the change is shown as lines, and no images are drawn.";
  std::string md = reviewMarkdown(oldName, newName, none, false, note, lines);
  std::string html = reviewHtml(oldName, newName, none, "", "", "", note, lines);
  removeImages(o.dir);
  if (!writeFile(join(o.dir, "review.md"), md) || !writeFile(join(o.dir, "index.html"), html)) return cli::kTrouble;
  return cli::kTrouble;
}

}  // namespace rscene::diffout
