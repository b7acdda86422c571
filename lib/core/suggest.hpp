// "Did you mean" for misspelt record tags and keys.
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace rscene {

// Optimal-string-alignment distance (adjacent swaps count once), compared
// case-insensitively.
std::size_t editDistance(std::string_view a, std::string_view b);

// The closest candidate within a distance that still reads as a typo of
// `word` (about a third of its length), or empty.
std::string closestName(std::string_view word, const std::vector<std::string_view>& candidates);

}  // namespace rscene
