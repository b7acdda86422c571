// Reads scene text into a Document.  Accepts versions 1 and 2, CRLF, tabs,
// comments, `%XX` in either case and every object layout; refuses what
// cannot be read without guessing (see DESIGN.md) with RS1xxx diagnostics.
#pragma once
#include <string>
#include <string_view>

#include "core/diagnostic.hpp"
#include "core/document.hpp"

namespace rscene {

struct LoadResult {
  Document document;
  Diagnostics diagnostics;  // errors stop the load; warnings do not
  bool ok() const { return !hasErrors(diagnostics); }
};

// Parses `text`, which the document takes over (no copy).  Never throws on
// bad input; only std::bad_alloc escapes.
LoadResult parse(std::string text);

// Largest input the loader takes: spans are 32-bit offsets.
inline constexpr std::size_t kMaxInputBytes = 0xfffffff0u;

}  // namespace rscene
