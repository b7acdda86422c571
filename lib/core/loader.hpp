// Reads scene text into a Document.  Accepts versions 1 and 2, CRLF, tabs,
// comments, `%XX` in either case and every object layout; refuses what
// cannot be read without guessing (see DESIGN.md) with RS1xxx diagnostics.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostic.hpp"
#include "core/document.hpp"

namespace rscene {

struct LoadResult {
  Document document;
  Diagnostics diagnostics;  // errors stop the load; warnings do not
  // Record lines that end with a lone `\` (ascending): the writer meant a
  // continuation line, which the format does not have.
  std::vector<std::uint32_t> continuedLines;
  bool ok() const { return !hasErrors(diagnostics); }
};

// Parses `text`, which the document takes over (no copy).  Never throws on
// bad input; only std::bad_alloc escapes.
LoadResult parse(std::string text);

// Gives every diagnostic on a line in `continuedLines`, or on the line
// after one, the hint that the format has no continuation lines (the loader
// does this for its own; a pass over the document calls it for the rest).
void hintContinuations(const std::vector<std::uint32_t>& continuedLines, Diagnostics& ds);

// Largest input the loader takes: spans are 32-bit offsets.
inline constexpr std::size_t kMaxInputBytes = 0xfffffff0u;

}  // namespace rscene
