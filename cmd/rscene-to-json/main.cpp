// rscene-to-json: writes a scene as lossless JSON (lib/core/json.hpp).
#include <unistd.h>

#include <CLI/CLI.hpp>

#include "common/cli.hpp"
#include "core/json.hpp"
#include "core/loader.hpp"

int main(int argc, char** argv) {
  using namespace rscene;
  CLI::App app{"Write a .rscene scene as lossless JSON (rscene-from-json reads it back)."};
  cli::setup(app, "rscene-to-json");
  std::string file = "-", output, stdinName;
  bool compact = false, pretty = false, schema = false;
  cli::addInputOperand(app, file);
  cli::addOutputOption(app, output, "Write the JSON to FILE (atomically) instead of standard output");
  auto* compactFlag = app.add_flag("-c,--compact", compact, "One line of JSON (the default when stdout is not a terminal)");
  app.add_flag("-p,--pretty", pretty, "Indented JSON (the default on a terminal)")->excludes(compactFlag);
  app.add_flag("--schema", schema, "Print the JSON Schema (2020-12) of the JSON form and exit");
  cli::addStdinFilename(app, stdinName, false);
  if (int rc = cli::parseArgs(app, argc, argv); rc >= 0) return rc;

  if (schema) {
    std::string text = jsonSchema();
    return cli::writeOutput(output, [&](Sink& s) { s.write(text); return true; }) ? cli::kSuccess : cli::kTrouble;
  }
  cli::Input in;
  if (!cli::readInput(file, stdinName, in)) return cli::kTrouble;
  LoadResult loaded = parse(std::move(in.text));
  cli::printDiagnostics(loaded.diagnostics, in.display, loaded.document.buffer(), cli::colorFor(2));
  if (!loaded.ok()) return cli::kTrouble;

  JsonStyle style;
  bool toTerminal = (output.empty() || output == "-") && ::isatty(1) == 1;
  style.pretty = pretty || (!compact && toTerminal);
  return cli::writeOutput(output, [&](Sink& s) { writeJson(loaded.document, s, style); return true; })
             ? cli::kSuccess
             : cli::kTrouble;
}
