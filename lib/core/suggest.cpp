#include "core/suggest.hpp"

#include <algorithm>
#include <vector>

namespace rscene {
namespace {

char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

}  // namespace

namespace {

// The distance, or any value above `limit` as soon as every alignment
// costs more than it (a row's minimum never decreases).
std::size_t boundedDistance(std::string_view a, std::string_view b, std::size_t limit) {
  const std::size_t n = a.size(), m = b.size();
  // Three rows suffice for the adjacent-transposition rule; short words
  // (all names) keep them on the stack.
  constexpr std::size_t kStack = 65;
  std::size_t stack[3][kStack];
  std::vector<std::size_t> heap;
  std::size_t *prev2 = stack[0], *prev = stack[1], *cur = stack[2];
  if (m + 1 > kStack) {
    heap.resize(3 * (m + 1));
    prev2 = heap.data();
    prev = prev2 + m + 1;
    cur = prev + m + 1;
  }
  for (std::size_t j = 0; j <= m; ++j) prev[j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    cur[0] = i;
    std::size_t rowMin = cur[0];
    for (std::size_t j = 1; j <= m; ++j) {
      std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1]))
        cur[j] = std::min(cur[j], prev2[j - 2] + 1);
      rowMin = std::min(rowMin, cur[j]);
    }
    std::swap(prev2, prev);
    std::swap(prev, cur);
    // A transposition reaches back two rows, so stop only when both exceed.
    if (rowMin > limit && i > 1) {
      std::size_t before = prev2[0];
      for (std::size_t j = 1; j <= m; ++j) before = std::min(before, prev2[j]);
      if (before > limit) return limit + 1;
    }
  }
  return prev[m];
}

}  // namespace

std::size_t editDistance(std::string_view a, std::string_view b) {
  return boundedDistance(a, b, static_cast<std::size_t>(-1) - 1);
}

std::string closestName(std::string_view word, const std::vector<std::string_view>& candidates) {
  return closestName(word, candidates, std::max<std::size_t>(1, (word.size() + 1) / 3));
}

std::string closestName(std::string_view word, const std::vector<std::string_view>& candidates, std::size_t limit) {
  // Long unknown words are not typos of anything; skip the quadratic work.
  if (word.empty() || word.size() > 64) return {};
  std::size_t best = limit + 1;
  std::string_view found;
  for (std::string_view c : candidates) {
    std::size_t lenDiff = c.size() > word.size() ? c.size() - word.size() : word.size() - c.size();
    if (lenDiff > limit) continue;
    std::size_t d = boundedDistance(word, c, best - 1);
    if (d < best) {
      best = d;
      found = c;
    }
  }
  return std::string(found);
}

}  // namespace rscene
