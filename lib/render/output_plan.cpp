#include "render/output_plan.hpp"

#include <map>

#include "core/text.hpp"
#include "scene/reader.hpp"
#include "scene/sensor_check.hpp"

namespace rscene::render {
namespace {

std::string sibling(const std::string& path, const char* extension) {
  std::size_t slash = path.find_last_of('/');
  std::size_t dot = path.find_last_of('.');
  bool hasExtension = dot != std::string::npos && (slash == std::string::npos || dot > slash + 1);
  return (hasExtension ? path.substr(0, dot) : path) + extension;
}

class Planner {
 public:
  Planner(const std::vector<View>& views, const OutputRequest& request, const ViewSources& sources,
          OutputPlan& plan, ViewFindings& found)
      : views_(views), request_(request), sources_(sources), plan_(plan), found_(found) {}

  bool plan() { return patterns() && oneColorImageForStdout() && firstFrameFiles(); }

 private:
  // Every view's passes with their patterns.
  bool patterns() {
    // Frames have increasing times: {time} names each one once too.
    if (!request_.output.empty() && request_.frames && !patternHas(request_.output, "frame") &&
        !patternHas(request_.output, "time")) {
      found_.error = "-o '" + request_.output +
                     "' has no {frame} or {time}: every frame of --trajectory would write the same file";
      return false;
    }
    for (std::size_t i = 0; i < views_.size(); ++i) {
      const View& v = views_[i];
      std::string pattern = request_.output;
      if (pattern.empty()) {
        if (request_.reference) continue;  // --reference alone writes only a missing baseline
        if (v.outputPath.empty() || v.outputPath == "-") {
          found_.error = "nothing to write: '" + v.name +
                         "' has no outputPath; give -o FILE (-o - for standard output)" +
                         (v.sensor ? std::string() : ", --reference FILE") +
                         " or -o PATTERN such as '{name}.{kind}.png'";
          return false;
        }
        if (std::string why = outputPathProblem(v.outputPath); !why.empty()) {
          reportAt(&sources_.document, v.recordIndex, "outputPath", code::kOutputPath,
                   "outputPath '" + v.outputPath + "' " + why + ": a scene may only write below the current folder",
                   found_.diagnostics, Severity::Error, "give -o PATTERN to write elsewhere");
          continue;
        }
        pattern = outputPathPattern(v.outputPath, v.passes.size() > 1, request_.frames);
      }
      for (Pass pass : v.passes) plan_.outputs.push_back({i, pass, pattern});
    }
    return found_.ok();
  }

  bool oneColorImageForStdout() {
    const std::vector<PlannedOutput>& outputs = plan_.outputs;
    if (request_.output != "-" || (outputs.size() == 1 && outputs[0].pass == Pass::Color)) return true;
    if (outputs.size() == 1)
      found_.error = "-o - writes one color image; '" + views_[0].name + "' makes a " +
                     passName(outputs[0].pass) + " image and its " +
                     (outputs[0].pass == Pass::Depth ? ".npy" : ".json") + " beside it: give -o FILE or -o PATTERN";
    else
      found_.error = "-o - writes one color image; these views make " + std::to_string(outputs.size()) +
                     " images and their files: give -o PATTERN such as 'out/{name}.{kind}.png'";
    return false;
  }

  bool firstFrameFiles() {
    std::map<std::string, std::size_t> owners;  // path -> the output (index) writing it
    for (std::size_t k = 0; k < plan_.outputs.size(); ++k) {
      const PlannedOutput& o = plan_.outputs[k];
      const View& v = views_[o.view];
      std::string path;
      if (!expandPattern(o.pattern, outputFields(v, o.pass, 0, 0), path, &found_.error)) return false;
      if (std::string why = imageExtensionProblem(path); !why.empty()) {
        if (!request_.output.empty())
          found_.error = "-o '" + request_.output + "': " + why + "; end -o with .png";
        else if (v.recordIndex < 0)
          found_.error = "'" + v.name + "': " + why;
        else
          reportAt(&sources_.document, v.recordIndex, "outputPath", code::kOutputPath, "outputPath: " + why,
                   found_.diagnostics, Severity::Error, "end outputPath with .png");
        return false;
      }
      for (const std::string& file : filesOf(path, o.pass)) {
        auto [it, added] = owners.emplace(file, k);
        if (!added) {
          found_.error = collision(file, plan_.outputs[it->second], o);
          return false;
        }
        plan_.files.push_back(file);
      }
    }
    return true;
  }

  // Why two images would go to one file, and what to change: one view's
  // several passes, two views of one name, or a pattern without {name}.
  std::string collision(const std::string& file, const PlannedOutput& first, const PlannedOutput& second) const {
    const View& a = views_[first.view];
    const View& b = views_[second.view];
    const std::string& output = request_.output;
    std::string head = "two images would go to '" + file + "': ";
    if (&first == &second)  // the image and the .npy or .json written beside it
      return head + "the " + std::string(passName(first.pass)) + " image of '" + a.name +
             "' is PNG and its companion file goes beside it under the same name; end the pattern with .png [RS9048]";
    if (first.view == second.view) {
      std::string kinds;
      for (Pass p : a.passes) kinds += (kinds.empty() ? "" : ", ") + std::string(passName(p));
      return head + "view '" + a.name + "' makes several images (" + kinds + "); put {kind} in -o, such as '" +
             outputPathPattern(first.pattern, true, false) + "' [RS9048]";
    }
    if (a.name == b.name) {
      bool ids = !a.id.empty() || !b.id.empty();
      return head + "two views are named '" + a.name + "': " + declaredAt(a, sources_) + " and " +
             declaredAt(b, sources_) + "; rename the record" +
             (ids && !patternHas(output, "id") ? ", or use {id} in -o" : "") + " [RS9048]";
    }
    std::string fix = output.empty() ? "give the records different outputPath, or -o PATTERN with {name}"
                                     : "use {name} and {kind} in -o, or give the records different outputPath";
    return head + "'" + a.name + "' (" + passName(first.pass) + ") and '" + b.name + "' (" + passName(second.pass) +
           "); " + fix + " [RS9048]";
  }

  const std::vector<View>& views_;
  const OutputRequest& request_;
  const ViewSources& sources_;
  OutputPlan& plan_;
  ViewFindings& found_;
};

}  // namespace

std::vector<std::string> filesOf(const std::string& image, Pass pass) {
  if (pass == Pass::Depth) return {image, sibling(image, ".npy")};
  if (pass == Pass::Segmentation) return {image, sibling(image, ".json")};
  return {image};
}

OutputFields outputFields(const View& v, Pass pass, std::uint64_t frame, double time) {
  OutputFields f;
  f.name = fileNameOf(v.name);
  f.id = v.id.empty() ? "" : fileNameOf(v.id);
  f.kind = passName(pass);
  f.frame = frame;
  appendNumber(f.time, time);
  return f;
}

bool planOutputs(const std::vector<View>& views, const OutputRequest& request, const ViewSources& sources,
                 OutputPlan& plan, ViewFindings& found) {
  plan = {};
  return Planner(views, request, sources, plan, found).plan();
}

std::string outputPathAt(const PlannedOutput& output, const View& v, std::uint64_t frame, double time) {
  std::string path, error;
  expandPattern(output.pattern, outputFields(v, output.pass, frame, time), path, &error);
  return path;
}

}  // namespace rscene::render
