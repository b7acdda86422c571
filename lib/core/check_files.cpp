// RS5001 (--check-files): every asset path names an existing file, found
// by the rule of compat-notes.md ("Asset path resolution").
#include "core/codes.hpp"
#include "core/assets.hpp"
#include "core/check_context.hpp"
#include "core/text.hpp"

namespace rscene::checks {

void checkFiles(Context& ctx, const Record& r) {
  // asset_root and a robot's resourceDirectory name directories (lib/robot
  // reads what is in them: --check-files reads the robot), and output paths
  // are written, not read.
  if (r.kind->tag == "asset_root") return;
  forEachValue(ctx, r, [&](const FieldDef& def, const Field& f) {
    if (def.type != ValueType::Path || def.name.rfind("output", 0) == 0 || def.name == "resourceDirectory") return;
    std::string path = percentDecode(ctx.doc.text(f.value));
    if (path.empty()) return;
    std::string resolved = resolveAsset(ctx.opt.sceneDir, ctx.opt.project, ctx.doc.version, ctx.index.assetRoot, path,
                                           ctx.opt.fileExists);
    if (ctx.opt.fileExists(resolved)) return;
    ctx.report(rs::RS5001, r, f.value, def.name, "file '" + path + "' " + whyNotAFile(resolved) + " (resolved to '" + resolved + "')",
               ctx.opt.project.empty() ? "paths resolve against the scene's directory, then against asset_root"
                                         : "paths resolve against the scene's directory, then against asset_root, then against "
                                           "the project's asset_directory");
  });
}

}  // namespace rscene::checks
