// rscene-to-xml's mapping: the physics side of a scene (the typed scene
// model, lib/scene) as a RaiSim world configuration XML: gravity, time
// step, ERP, the default material and pair_prop, every simulated body,
// articulated systems with their state, wires.  Names are the record
// paths.  What has no XML equivalent is listed in `notExported`.
#pragma once
#include <string>
#include <vector>

#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "scene/scene.hpp"

namespace rscene::xml {

struct ToXmlOptions {
  // Asset paths are written as "[THIS_DIR]/" + the path relative to this
  // directory (the XML's: -o's directory, or the current directory for
  // standard output), or absolute when `absolutePaths`.
  std::string outputDir = ".";
  bool absolutePaths = false;
};

struct ToXmlResult {
  std::string xml;  // the document, ending in a newline (empty on error)
  Diagnostics diagnostics;
  // Records and fields with no XML equivalent ("3 lights", "camera
  // /World/Cam", "object /World/Ball: visual material"), for the one
  // warning line the tool prints.
  std::vector<std::string> notExported;
  bool ok() const { return !hasErrors(diagnostics); }
};

ToXmlResult sceneToXml(const Document& doc, const Scene& scene, const ToXmlOptions& options);

}  // namespace rscene::xml
