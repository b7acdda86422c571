// rscene-from-xml: a RaiSim world configuration XML (templates expanded by
// lib/xml's front end) as a version-1 .rscene in canonical form.
#include <CLI/CLI.hpp>

#include <cctype>
#include <filesystem>
#include <map>
#include <iostream>

#include "core/codes.hpp"
#include "common/cli.hpp"
#include "core/io.hpp"
#include "xml/from_xml.hpp"
#include "xml/xml_tree.hpp"

namespace {

// NAME=VALUE, NAME as it follows @@ in the XML (letters, digits, _).
bool parseParam(const std::string& text, std::map<std::string, std::string>& params) {
  std::size_t eq = text.find('=');
  std::string name = text.substr(0, eq);
  bool ok = eq != std::string::npos && !name.empty();
  for (char c : name) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
  if (!ok) {
    rscene::cli::error("--param '" + text + "': expected NAME=VALUE, NAME of letters, digits and _ (without @@)");
    return false;
  }
  params[name] = text.substr(eq + 1);
  return true;
}

std::string folderOf(const std::string& path) {
  std::string dir = std::filesystem::path(path).parent_path().string();
  return dir.empty() ? "." : dir;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace rscene;
  CLI::App app{"Write a RaiSim world configuration XML as a canonical version-1 .rscene scene."};
  cli::setup(app, "rscene-from-xml");
  std::string file = "-", output, stdinName;
  std::vector<std::string> paramTexts;
  bool absolutePaths = false, quiet = false;
  std::string relativeTo;
  cli::addInputOperand(app, file, "World XML file");
  cli::addOutputOption(app, output, "Write the scene to FILE (atomically) instead of standard output");
  app.add_option("--param", paramTexts, "Set the template parameter @@NAME to VALUE (repeatable)")
      ->type_name("NAME=VALUE")
      ->allow_extra_args(false);
  CLI::Option* absolute = app.add_flag("--absolute-paths", absolutePaths, "Write asset paths absolute instead of relative to the output");
  // Standard output has no folder: the paths are written relative to the
  // current one unless this says where the output will be read from.
  app.add_option("--relative-to", relativeTo,
                 "Standard output only: write asset paths relative to DIR, the folder the output will be read from")
      ->type_name("DIR")
      ->excludes(absolute);
  app.add_flag("-q,--quiet", quiet, "Print errors only: no warnings, no list of what was not converted");
  cli::addStdinFilename(app, stdinName, true);
  if (int rc = cli::parseArgs(app, argc, argv); rc >= 0) return rc;
  if (!relativeTo.empty() && !output.empty() && output != "-") {
    cli::error("--relative-to is for standard output: with -o FILE, paths are relative to FILE's folder");
    return cli::kTrouble;
  }

  xml::LoadOptions loadOptions;
  for (const std::string& p : paramTexts)
    if (!parseParam(p, loadOptions.params)) return cli::kTrouble;
  std::string outPath = output.empty() ? "-" : output;
  if (!cli::checkOutputs({{"-o", outPath}})) return cli::kTrouble;

  cli::Input in;
  in.isStdin = file.empty() || file == "-";
  in.display = in.isStdin ? (stdinName.empty() ? "<stdin>" : stdinName) : file;
  in.path = in.isStdin ? stdinName : file;
  // The top file and standard input are capped like included files: a
  // 100 MiB world is refused, not read whole.
  if (std::string why; !readFile(in.isStdin ? "/dev/stdin" : file, in.text, &why, loadOptions.limits.maxFileBytes)) {
    Diagnostic d;
    d.code = rs::RS8101;
    d.file = in.display;
    d.message = "cannot read: " + why;
    cli::printDiagnostics({d}, in.display, "", cli::colorFor(2));
    return cli::kTrouble;
  }
  std::string baseDir = in.path.empty() ? "." : folderOf(in.path);
  xml::LoadResult loaded = xml::loadWorldText(in.text, in.display, baseDir, loadOptions);
  Diagnostics diags = loaded.diagnostics;
  xml::FromXmlResult converted;
  if (loaded.ok()) {
    xml::FromXmlOptions options;
    options.outputDir = outPath != "-" ? folderOf(outPath) : relativeTo.empty() ? "." : relativeTo;
    options.absolutePaths = absolutePaths;
    converted = xml::worldToScene(*loaded.root, options);
    diags.insert(diags.end(), converted.diagnostics.begin(), converted.diagnostics.end());
  }
  // Findings in the top file print with its source line (printDiagnostics
  // shows the line only for findings without a file of their own).
  Diagnostics shown;
  for (Diagnostic& d : diags) {
    if (quiet && d.severity != Severity::Error) continue;
    if (d.file == in.display) d.file.clear();
    shown.push_back(std::move(d));
  }
  cli::printDiagnostics(shown, in.display, in.text, cli::colorFor(2));
  if (!loaded.ok() || !converted.ok()) return cli::kTrouble;
  if (!quiet && !converted.notConverted.empty()) {
    std::string list;
    for (const std::string& what : converted.notConverted) list += (list.empty() ? "" : ", ") + what;
    cli::warning("not converted: " + list);
  }
  return cli::writeOutput(outPath, [&](Sink& s) { s.write(converted.text); return true; }) ? cli::kSuccess
                                                                                          : cli::kTrouble;
}
