// Where a render's images go, decided before anything is drawn: every
// view's passes, each with the pattern its files are named by (-o, or the
// record's outputPath), and every file of the first frame checked: no two
// the same, every image a .png, no outputPath a scene may not write.  The
// caller writes (and makes folders); nothing here touches the disk.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "render/view.hpp"
#include "render/view_select.hpp"
#include "render/views.hpp"

namespace rscene::render {

// One image a view writes per frame: the pattern its path comes from.
struct PlannedOutput {
  std::size_t view = 0;  // index into the views planned
  Pass pass = Pass::Color;
  std::string pattern;
};

struct OutputRequest {
  std::string output;      // -o FILE or PATTERN, "-" = standard output; "" = each record's outputPath
  bool frames = false;     // a trajectory: several frames per view
  bool reference = false;  // --reference: a view without an outputPath writes nothing (without -o)
};

struct OutputPlan {
  std::vector<PlannedOutput> outputs;  // grouped by view, in view order
  std::vector<std::string> files;      // every file of the first frame, images and their companions
};

// The files one image becomes: the image, then its .npy (depth) or legend
// .json (segmentation), the extension replaced ("cam.depth.png" ->
// "cam.depth.npy"), else appended.
std::vector<std::string> filesOf(const std::string& image, Pass pass);

// The pattern fields of view `v`'s `pass` image at `frame` and `time`.
OutputFields outputFields(const View& v, Pass pass, std::uint64_t frame, double time);

// Plans the outputs of `views`.  False with found.error (a usage error)
// or found.diagnostics (at a record's outputPath) when the run must not
// start.
bool planOutputs(const std::vector<View>& views, const OutputRequest& request, const ViewSources& sources,
                 OutputPlan& plan, ViewFindings& found);

// The path of `output` (of view `v`) at `frame` and `time`: its pattern
// expanded (planOutputs() has checked that it expands).
std::string outputPathAt(const PlannedOutput& output, const View& v, std::uint64_t frame, double time);

}  // namespace rscene::render
