// Radiance .hdr (RGBE, flat or new-style run-length encoded) reader for
// equirectangular backgrounds.  Debian 12 has no small packaged reader.
#pragma once
#include <string>

#include "render/image.hpp"

namespace rscene::render {

bool decodeHdr(const std::string& bytes, FloatImage& out, std::string* error, std::uint64_t maxPixels = 1ull << 26);

}  // namespace rscene::render
