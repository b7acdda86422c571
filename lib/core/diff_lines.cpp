#include "core/diff_lines.hpp"

#include <dtl/dtl.hpp>
#include <sstream>
#include <vector>

namespace rscene {
namespace {

// Views into the caller's text: a 128 MB scene is not copied line by line.
std::vector<std::string_view> splitLines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    lines.push_back(text.substr(pos, nl - pos));
    pos = nl + 1;
  }
  return lines;
}

}  // namespace

std::string unifiedDiff(std::string_view before, std::string_view after, std::string_view oldName,
                        std::string_view newName) {
  if (before == after) return {};
  std::vector<std::string_view> a = splitLines(before), b = splitLines(after);
  dtl::Diff<std::string_view, std::vector<std::string_view>> diff(a, b);
  diff.onHuge();  // keeps memory bounded on very different inputs
  diff.compose();
  diff.composeUnifiedHunks();
  std::ostringstream out;
  out << "--- " << oldName << "\n+++ " << newName << "\n";
  // dtl's own printer writes an empty range as `-1,0`; diff(1) and patch(1)
  // use the line before it (`-0,0` for an empty file).
  auto range = [](long long start, long long count) {
    return std::to_string(count == 0 ? start - 1 : start) + "," + std::to_string(count);
  };
  for (const auto& hunk : diff.getUniHunks()) {
    out << "@@ -" << range(hunk.a, hunk.b) << " +" << range(hunk.c, hunk.d) << " @@\n";
    for (const auto& common : hunk.common[0]) out << ' ' << common.first << '\n';
    for (const auto& change : hunk.change) {
      char sign = change.second.type == dtl::SES_ADD ? '+' : change.second.type == dtl::SES_DELETE ? '-' : ' ';
      out << sign << change.first << '\n';
    }
    for (const auto& common : hunk.common[1]) out << ' ' << common.first << '\n';
  }
  return out.str();
}

bool looksBinary(std::string_view text) {
  return text.substr(0, 8000).find('\0') != std::string_view::npos;
}

}  // namespace rscene
