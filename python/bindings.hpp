// What the parts of the `rscene._rscene` extension share: the document and
// simulation objects Python holds, and the conversions every binding file
// uses.  module.cpp binds documents and simulation; each other python/*.cpp
// binds one more part and is registered from module.cpp.
#pragma once

#include <pybind11/pybind11.h>

#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "asset/cache.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "core/writer.hpp"
#include "sim/prepare.hpp"

namespace rscene::python {

namespace py = pybind11;

// A parsed scene as Python holds it: the lossless document, the text it was
// read from (for validate's lines and carets), where it came from, and the
// loader's warnings.
struct PyDocument {
  Document doc;
  std::string source;  // as read (a document from JSON: its canonical text)
  std::string path;    // "" when not read from a file
  Diagnostics diagnostics;
};

// A scene made ready to step, as rscene-sim prepares it (sim/prepare.hpp),
// stepped by the library's loop (sim/run.hpp) so that every state is
// checked as the tool checks it.
struct PySimulation {
  std::shared_ptr<PyDocument> source;
  Document doc;  // the document the world writes back into
  asset::AssetCache assets;
  sim::Prepared prepared;
  Diagnostics diagnostics;  // warnings of the preparation
  std::optional<Diagnostic> failure;  // a run that stopped: no more steps
  bool started = false;  // the start state was checked (and sensors sampled) by a first step() call
  std::uint64_t chunk = 64;  // steps stepped without the GIL between checks for Ctrl-C (adapted to ~50 ms)
  // What only module.cpp's simulation part uses (the sensors' recorder and
  // latest readings, names of records): its own type there.
  std::shared_ptr<void> extra;
  // step() runs without the GIL: two Python threads that share one
  // simulation take turns instead of racing in Bullet.
  mutable std::mutex mutex;
};

// Text from the library as a Python str (bytes that are not UTF-8 become
// U+FFFD rather than a UnicodeDecodeError).
py::str pystr(const std::string& s);
py::dict diagnosticDict(const Diagnostic& d);
py::list diagnosticList(const Diagnostics& ds);
// Writes what `write` gives to `path` through the tools' output routine
// (atomic; a symlink's target rewritten, a device or FIFO written through),
// without the GIL; the message of a refusal, or "" on success.  An empty
// path or one with a NUL byte raises ValueError.
std::string saveText(const std::string& path, const std::function<void(Sink&)>& write);

// The further parts, each in its own file, registered from module.cpp.
void bindRender(py::module_& m);  // render.cpp
void bindScene(py::module_& m);   // scene.cpp

}  // namespace rscene::python
