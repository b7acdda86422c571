// rscene-from-xml's mapping: an expanded RaiSim world (xml_tree.hpp) as
// version-1 .rscene records in canonical form.  Every element and
// attribute of WorldConfigurationFile.rst maps to a record field, or is
// reported (a warning listing what has no .rscene equivalent, never a
// silent drop); the camelCase aliases and both articulatedSystem
// spellings are read.
#pragma once
#include <string>
#include <vector>

#include "core/diagnostic.hpp"
#include "core/filesystem.hpp"
#include "xml/xml_tree.hpp"

namespace rscene::xml {

struct FromXmlOptions {
  // Asset paths (meshes, URDFs, heightmap PNGs) are written relative to
  // this directory (where the .rscene goes: -o's directory, or the current
  // directory for standard output), or absolute when `absolutePaths`.
  std::string outputDir = ".";
  bool absolutePaths = false;
  // Where height-map PNGs and text files are read from (nullptr: the disk).
  const FileSystem* files = nullptr;
  const FileSystem& fileSystem() const { return files ? *files : diskFileSystem(); }
};

struct FromXmlResult {
  std::string text;  // canonical .rscene text (empty on error)
  Diagnostics diagnostics;
  // What the XML says that the scene cannot hold (e.g. "sphere 'a': lin_vel"),
  // for the one warning line the tool prints.
  std::vector<std::string> notConverted;
  bool ok() const { return !hasErrors(diagnostics); }
};

FromXmlResult worldToScene(const Element& raisim, const FromXmlOptions& options);

}  // namespace rscene::xml
