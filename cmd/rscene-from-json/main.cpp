// rscene-from-json: turns the JSON form back into canonical scene text.
#include <CLI/CLI.hpp>

#include "common/cli.hpp"
#include "core/json.hpp"
#include "core/writer.hpp"

int main(int argc, char** argv) {
  using namespace rscene;
  CLI::App app{"Write the canonical .rscene text of a scene in rscene-to-json's JSON form."};
  cli::setup(app, "rscene-from-json");
  std::string file = "-", output, stdinName;
  cli::addInputOperand(app, file, "JSON file");
  cli::addOutputOption(app, output, "Write the scene to FILE (atomically) instead of standard output");
  cli::addStdinFilename(app, stdinName, false);
  if (int rc = cli::parseArgs(app, argc, argv); rc >= 0) return rc;

  cli::Input in;
  if (!cli::readInput(file, stdinName, in)) return cli::kTrouble;
  JsonLoadResult loaded = fromJson(in.text);
  cli::printDiagnostics(loaded.diagnostics, in.display, in.text, cli::colorFor(2));
  if (!loaded.ok()) return cli::kTrouble;
  return cli::writeOutput(output, [&](Sink& s) { writeCanonical(loaded.document, s); return true; })
             ? cli::kSuccess
             : cli::kTrouble;
}
