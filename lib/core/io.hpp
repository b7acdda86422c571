// Whole-file entry points in the style of Engine 2's RSceneIO.hpp:
// errors come back as "line N: message".  File reading lives here and
// writing forwards to core/output_file.hpp, so every tool shares them;
// nothing here prints.
#pragma once
#include <functional>
#include <string>
#include <string_view>

#include "core/document.hpp"
#include "core/loader.hpp"
#include "core/writer.hpp"

namespace rscene {

bool loadString(std::string text, Document& doc, std::string* error = nullptr);
bool loadFile(const std::string& path, Document& doc, std::string* error = nullptr);
std::string saveString(const Document& doc);
bool saveFile(const Document& doc, const std::string& path, std::string* error = nullptr);

// Reads a whole file (also a pipe, /dev/stdin); `error` gets strerror-style
// text.  With `maxBytes` > 0 a file longer than that is an error
// (fileTooLarge()) found before more than a read past the cap is held.
bool readFile(const std::string& path, std::string& out, std::string* error, std::size_t maxBytes = 0);

// Writes `path` through the one output routine, writeOutputFile() in
// core/output_file.hpp: atomic replacement of a regular file (mode and
// owner kept), symlinks kept, devices and FIFOs written through, read-only
// and hard-linked files refused.  Kept under this name for library users.
bool writeFileAtomic(const std::string& path, const std::function<bool(Sink&)>& produce, std::string* error);

// "line N: message" for the first error of a load.
std::string firstError(const Diagnostics& diagnostics);

// Whether two documents hold the same scene record for record, in writer
// order (the invariant `parse(fmt(x)) == parse(x)`).  On a difference,
// `why` says where.
bool sameDocument(const Document& a, const Document& b, std::string* why = nullptr);

}  // namespace rscene
