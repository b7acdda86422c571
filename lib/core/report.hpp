// Renders a diagnostic as text for people: `file:line:col: error: message
// [RS1003]`, the source line, a caret under the column and a hint.  Returns
// a string; printing is the driver's job.
#pragma once
#include <string>
#include <string_view>

#include "core/diagnostic.hpp"

namespace rscene {

std::string formatDiagnostic(const Diagnostic& d, std::string_view file, std::string_view sourceLine, bool color);

// The 1-based line `line` of `text` without its line ending (empty if none).
// Scans from the start: for one line, not for one per finding.
std::string_view lineOf(std::string_view text, std::uint32_t line);

// The lines under findings printed as they come: a cursor that walks from
// the line it last found, forward or back, so findings in line order cost
// one pass over the text in all (lineOf() per finding made printing N of
// them O(N * size)), and nothing is kept.
class LineCursor {
 public:
  explicit LineCursor(std::string_view text) : text_(text) {}
  // As lineOf(text, line).
  std::string_view operator()(std::uint32_t line);

 private:
  std::string_view text_;
  std::uint32_t line_ = 1;  // the line that starts at pos_
  std::size_t pos_ = 0;
};

}  // namespace rscene
