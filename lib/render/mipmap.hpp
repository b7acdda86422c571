// Mipmap levels of an RGBA8 texture, computed on the CPU.  glGenerateMipmap
// on llvmpipe rasterises every level through its thread pool: for ANYmal
// C's nineteen 2048x2048 textures it took 0.55 s of CPU and 2 s of wall
// time on a loaded machine, against about 0.1 s for this loop (issue 11).
#pragma once
#include <cstdint>
#include <vector>

namespace rscene::render {

// The next level of a w x h RGBA8 image (rows top to bottom, no padding):
// max(1, w/2) x max(1, h/2), each texel the mean of the 2x2 block it
// covers (of 2x1, 1x2 or 1x1 where a side is 1), rounded to nearest.
// The texels of an odd last row or column are left out, as a box filter of
// GL's power-of-two rule does.  Averages the stored values (gamma space),
// as glGenerateMipmap does for an RGBA8 texture.
void halveImage(const std::uint8_t* src, int w, int h, std::vector<std::uint8_t>& out);

}  // namespace rscene::render
