// Renders a diagnostic as text for people: `file:line:col: error: message
// [RS1003]`, the source line, a caret under the column and a hint.  Returns
// a string; printing is the driver's job.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostic.hpp"

namespace rscene {

std::string formatDiagnostic(const Diagnostic& d, std::string_view file, std::string_view sourceLine, bool color);

// The 1-based line `line` of `text` without its line ending (empty if none).
// Scans from the start: for one line, not for one per finding.
std::string_view lineOf(std::string_view text, std::uint32_t line);

// The source lines a set of findings needs, found in one pass over `text`
// and kept as views (memory grows with the lines asked for, not the file):
// looking each up with lineOf() made printing N findings O(N * size).
class SourceLines {
 public:
  SourceLines(std::string_view text, std::vector<std::uint32_t> lines);
  // As lineOf(text, line) for a line passed to the constructor; empty for
  // any other.
  std::string_view operator()(std::uint32_t line) const;

 private:
  std::vector<std::uint32_t> lines_;  // sorted, unique
  std::vector<std::string_view> text_;  // per entry of lines_
};

}  // namespace rscene
