#pragma once
#include <string>
#include <string_view>

namespace rscene::fmt {

// `diff -u` style text from `before` to `after` (empty when equal), with
// `---`/`+++` headers naming `name`.
std::string unifiedDiff(std::string_view before, std::string_view after, const std::string& name);

}  // namespace rscene::fmt
