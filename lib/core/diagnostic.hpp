// Diagnostics are values: the library never prints.  Drivers render them
// with report.hpp as `file:line:col: error: message [RS1001]`.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace rscene {

enum class Severity { Note, Warning, Error };

struct Diagnostic {
  Severity severity = Severity::Error;
  std::string code;     // stable: RS1xxx syntax, RS2xxx types, RS3xxx references, ...
  std::uint32_t line = 0;    // 1-based; 0 = the whole file
  std::uint32_t column = 0;  // 1-based byte column; 0 = unknown
  std::string message;  // lower-case, no final period
  std::string hint;     // optional, e.g. "did you mean `color`?"
  std::string tag;      // record tag, when there is one
  std::string field;    // field name, when there is one
  // The file the line and column are in, when it is not the scene itself
  // (a robot's URDF or MJCF file, a module); empty: the scene.
  std::string file;
};

using Diagnostics = std::vector<Diagnostic>;

inline bool hasErrors(const Diagnostics& ds) {
  for (const Diagnostic& d : ds)
    if (d.severity == Severity::Error) return true;
  return false;
}

const char* severityName(Severity s);

}  // namespace rscene
