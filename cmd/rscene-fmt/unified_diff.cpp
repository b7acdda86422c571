#include "rscene-fmt/unified_diff.hpp"

#include <dtl/dtl.hpp>
#include <sstream>
#include <vector>

namespace rscene::fmt {
namespace {

std::vector<std::string> splitLines(std::string_view text) {
  std::vector<std::string> lines;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    lines.emplace_back(text.substr(pos, nl - pos));
    pos = nl + 1;
  }
  return lines;
}

}  // namespace

std::string unifiedDiff(std::string_view before, std::string_view after, const std::string& name) {
  if (before == after) return {};
  std::vector<std::string> a = splitLines(before), b = splitLines(after);
  dtl::Diff<std::string, std::vector<std::string>> diff(a, b);
  diff.onHuge();  // keeps memory bounded on very different inputs
  diff.compose();
  diff.composeUnifiedHunks();
  std::ostringstream out;
  out << "--- " << name << "\n+++ " << name << " (formatted)\n";
  diff.printUnifiedFormat(out);
  return out.str();
}

}  // namespace rscene::fmt
