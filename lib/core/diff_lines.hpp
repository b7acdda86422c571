// Plain line diffs, for what a semantic diff cannot compare: rscene-fmt
// --diff (a file against its canonical form) and rscene-diff's git mode
// when a side does not parse.  dtl stays private to the .cpp.
#pragma once
#include <string>
#include <string_view>

namespace rscene {

// `diff -u` text from `before` to `after` with `--- oldName` / `+++ newName`
// headers and 3 lines of context; empty when the texts are equal.
std::string unifiedDiff(std::string_view before, std::string_view after, std::string_view oldName,
                        std::string_view newName);

// Whether text is binary by git's rule: a NUL byte in its first 8000 bytes.
bool looksBinary(std::string_view text);

}  // namespace rscene
