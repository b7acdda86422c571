// Private to lib/asset: the one size check of every image decoder.
#pragma once
#include <string>

#include "asset/image.hpp"

namespace rscene::asset {

// Empty when a `width` x `height` image may be decoded, else the reason.
std::string sizeProblem(const char* format, std::uint64_t width, std::uint64_t height, const ImageLimits& limits);

}  // namespace rscene::asset
