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
std::string_view lineOf(std::string_view text, std::uint32_t line);

}  // namespace rscene
