#include "render/mipmap.hpp"

#include <algorithm>

namespace rscene::render {

void halveImage(const std::uint8_t* src, int w, int h, std::vector<std::uint8_t>& out) {
  int ow = std::max(1, w / 2), oh = std::max(1, h / 2);
  int dx = w > 1 ? 1 : 0, dy = h > 1 ? 1 : 0;  // a side of 1 is not halved
  int n = (1 + dx) * (1 + dy);
  out.resize(std::size_t(ow) * std::size_t(oh) * 4);
  std::size_t stride = std::size_t(w) * 4;
  if (dx && dy) {  // the common case, without the branches of the general loop
    for (int y = 0; y < oh; ++y) {
      const std::uint8_t* r0 = src + std::size_t(2 * y) * stride;
      const std::uint8_t* r1 = r0 + stride;
      std::uint8_t* o = &out[std::size_t(y) * std::size_t(ow) * 4];
      for (std::size_t i = 0; i < std::size_t(ow) * 4; ++i) {
        std::size_t a = (i & ~std::size_t(3)) * 2 + (i & 3);
        o[i] = std::uint8_t((r0[a] + r0[a + 4] + r1[a] + r1[a + 4] + 2) >> 2);
      }
    }
    return;
  }
  for (int y = 0; y < oh; ++y) {
    const std::uint8_t* r0 = src + std::size_t(2 * y * dy + (dy ? 0 : y)) * stride;
    const std::uint8_t* r1 = r0 + (dy ? stride : 0);
    std::uint8_t* o = &out[std::size_t(y) * std::size_t(ow) * 4];
    for (int x = 0; x < ow; ++x) {
      std::size_t a = std::size_t(dx ? 2 * x : x) * 4, b = a + (dx ? 4 : 0);
      for (int c = 0; c < 4; ++c) {
        int sum = r0[a + c] + (dx ? r0[b + c] : 0) + (dy ? r1[a + c] : 0) + (dx && dy ? r1[b + c] : 0);
        o[std::size_t(x) * 4 + std::size_t(c)] = std::uint8_t((sum + n / 2) / n);
      }
    }
  }
}

}  // namespace rscene::render
