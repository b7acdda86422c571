#include "core/suggest.hpp"

#include <algorithm>

namespace rscene {
namespace {

char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

}  // namespace

std::size_t editDistance(std::string_view a, std::string_view b) {
  const std::size_t n = a.size(), m = b.size();
  // Three rows suffice for the adjacent-transposition rule.
  std::vector<std::size_t> prev2(m + 1), prev(m + 1), cur(m + 1);
  for (std::size_t j = 0; j <= m; ++j) prev[j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1]))
        cur[j] = std::min(cur[j], prev2[j - 2] + 1);
    }
    std::swap(prev2, prev);
    std::swap(prev, cur);
  }
  return prev[m];
}

std::string closestName(std::string_view word, const std::vector<std::string_view>& candidates) {
  // Long unknown words are not typos of anything; skip the quadratic work.
  if (word.empty() || word.size() > 64) return {};
  std::size_t limit = std::max<std::size_t>(1, (word.size() + 1) / 3);
  std::size_t best = limit + 1;
  std::string_view found;
  for (std::string_view c : candidates) {
    std::size_t lenDiff = c.size() > word.size() ? c.size() - word.size() : word.size() - c.size();
    if (lenDiff > limit) continue;
    std::size_t d = editDistance(word, c);
    if (d < best) {
      best = d;
      found = c;
    }
  }
  return std::string(found);
}

}  // namespace rscene
