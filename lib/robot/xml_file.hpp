// Reading a robot file (URDF, URDF module, MJCF) into a tinyxml2 document:
// one size-capped read through lib/core's file access (regular files only,
// so a FIFO or /dev/zero is refused instead of read without end), then the
// XML parse, each failure a diagnostic naming the file.
#pragma once
#include <tinyxml2.h>

#include <cstddef>
#include <string>

#include "core/diagnostic.hpp"

namespace rscene::robot {

// A diagnostic about `file` at `line` (0: the whole file).
Diagnostic robotDiagnostic(Severity severity, const char* code, const std::string& file, int line,
                           std::string message);

// Reads `path` (at most `maxBytes`) and parses it.  Returns false after an
// RS5001 (missing, not a regular file) or RS7030 (too large, unreadable,
// not well-formed XML) error.
bool readXmlFile(const std::string& path, std::size_t maxBytes, tinyxml2::XMLDocument& doc,
                 Diagnostics& diagnostics);

// True when `text` holds something a preprocessor should have replaced:
// xacro's ${...} and $(...), RaiSim template variables @@NAME.
bool looksLikeTemplate(const char* text);

}  // namespace rscene::robot
