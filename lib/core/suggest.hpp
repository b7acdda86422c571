// "Did you mean" for misspelt record tags, keys, references and options.
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
// The same within distance `limit` (ties: the first candidate).
std::string closestName(std::string_view word, const std::vector<std::string_view>& candidates, std::size_t limit);

}  // namespace rscene
