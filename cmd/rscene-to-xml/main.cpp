// rscene-to-xml: the physics side of a scene as a RaiSim world
// configuration XML (lib/xml/to_xml.hpp; the mapping is in the man page).
#include <CLI/CLI.hpp>

#include "common/cli.hpp"
#include "core/assets.hpp"
#include "core/loader.hpp"
#include "scene/check.hpp"
#include "scene/scene.hpp"
#include "robot/check.hpp"
#include "scene/validate.hpp"
#include "xml/to_xml.hpp"

int main(int argc, char** argv) {
  using namespace rscene;
  CLI::App app{"Write the physics of a .rscene scene as a RaiSim world configuration XML."};
  cli::setup(app, "rscene-to-xml");
  std::string file = "-", output, stdinName;
  bool absolutePaths = false, quiet = false;
  std::string relativeTo;
  cli::addInputOperand(app, file);
  cli::addOutputOption(app, output, "Write the XML to FILE (atomically) instead of standard output");
  cli::addStdinFilename(app, stdinName, true);
  CLI::Option* absolute = app.add_flag("--absolute-paths", absolutePaths,
               "Write asset paths absolute instead of [THIS_DIR]/ and the path from the XML's folder");
  // Standard output has no folder: the paths are written relative to the
  // current one unless this says where the output will be read from.
  app.add_option("--relative-to", relativeTo,
                 "Standard output only: write asset paths relative to DIR, the folder the output will be read from")
      ->type_name("DIR")
      ->excludes(absolute);
  app.add_flag("-q,--quiet", quiet, "Do not print the line listing what the XML cannot hold");
  if (int rc = cli::parseArgs(app, argc, argv); rc >= 0) return rc;
  if (!relativeTo.empty() && !output.empty() && output != "-") {
    cli::error("--relative-to is for standard output: with -o FILE, paths are relative to FILE's folder");
    return cli::kTrouble;
  }
  // Before any work: -o must name something writeOutput() can replace.
  if (!cli::checkOutputs({{"-o", output.empty() ? "-" : output}})) return cli::kTrouble;

  cli::Input in;
  if (!cli::readInput(file, stdinName, in)) return cli::kTrouble;
  LoadResult loaded = parse(std::move(in.text));
  const Document& doc = loaded.document;
  bool color = cli::colorFor(2);
  auto print = [&](Diagnostics ds) {
    cli::hintStdinPaths(in, {}, ds);
    cli::printDiagnostics(ds, in.display, doc.buffer(), color);
  };
  if (!loaded.ok()) return print(loaded.diagnostics), cli::kTrouble;

  // Assets resolve against the scene's folder (--stdin-filename's for
  // standard input, else the current one), as in rscene-sim.
  SceneOptions so;
  so.sceneDir = in.path.empty() ? "." : directoryOf(in.path);
  so.project = cli::projectPlace(in, {});
  Scene scene;
  Diagnostics ds = loaded.diagnostics;
  // What rscene-sim refuses (a dynamic body without mass, a zero size ...)
  // is refused here too: RaiSim could not load it either.  Missing mesh
  // files are not checked: the XML names them all the same.
  bool built = robot::checkDocument(doc, so.sceneDir, ds) && buildScene(doc, so, scene, ds) && checkScene(doc, scene, {}, ds);
  if (!built) return print(ds), cli::kTrouble;

  xml::ToXmlOptions xo;
  xo.outputDir = !output.empty() && output != "-" ? directoryOf(output) : relativeTo.empty() ? "." : relativeTo;
  xo.absolutePaths = absolutePaths;
  xml::ToXmlResult result = xml::sceneToXml(doc, scene, xo);
  ds.insert(ds.end(), result.diagnostics.begin(), result.diagnostics.end());
  print(ds);
  if (!result.ok()) return cli::kTrouble;
  if (!quiet && !result.notExported.empty()) {
    std::string list;
    for (const std::string& s : result.notExported) list += (list.empty() ? "" : ", ") + s;
    cli::warning("not in the XML: " + list);
  }
  return cli::writeOutput(output.empty() ? "-" : output, [&](Sink& s) { s.write(result.xml); return true; })
             ? cli::kSuccess
             : cli::kTrouble;
}
