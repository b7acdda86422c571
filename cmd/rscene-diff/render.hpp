// Output of rscene-diff for people: change blocks and --stat counts.
#pragma once
#include <string>

#include "core/diff.hpp"

namespace rscene::diffout {

// One block per changed record: `~ object /World/Box`, then its fields as
// `name: old -> new` (long lists summarised).
std::string blocks(const DiffResult& result, bool color);

// Counts per record kind and a total line.
std::string stat(const DiffResult& result);

}  // namespace rscene::diffout
