// What a view's images become as files, in memory (the caller writes
// them): depth as a 16-bit PNG in millimetres and as a NumPy .npy float32
// array in metres, and the segmentation legend as JSON.
//
// Why .npy for float depth: `numpy.load` opens it with no extra package,
// a C++ reader is a header parse and one read, and it keeps NaN for "no
// return" (PFM has no standard orientation or NaN rule across tools and
// OpenEXR needs a library on both sides).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "render/render_scene.hpp"

namespace rscene::render {

// Depth in metres to millimetres for 16-bit images: round to nearest;
// NaN or infinite (no return) -> 0; a return is never 0, so a finite depth
// below 0.5 mm (noise can push one there or below 0) -> 1; beyond
// 65.535 m -> 65535 (saturated: check the .npy for far ranges).
std::uint16_t depthMillimetres(float metres);
// The depth image as a 16-bit grayscale PNG of depthMillimetres(); empty
// when depth.size() != width*height.
std::string encodeDepthPng16(const std::vector<float>& depth, int width, int height);

// NPY 1.0: magic "\x93NUMPY", version 1.0, a little-endian uint16 header
// length, the header dict {'descr': '<f4', 'fortran_order': False,
// 'shape': (height, width), } padded with spaces and a final '\n' so the
// data starts at a multiple of 64 bytes, then the floats little-endian,
// rows top to bottom; NaN = no return.  Empty when depth.size() !=
// width*height.
std::string encodeDepthNpy(const std::vector<float>& depth, int width, int height);

// The segmentation legend: {"background": {"color": [0,0,0], "hex":
// "#000000"}, "segments": [{"color": [r,g,b], "hex": "#rrggbb", "kind",
// "path", "id", "semanticClass", "instanceId"}, ...]} in the order of
// RenderScene::segments, one entry per record.  id, semanticClass and
// instanceId are null where the record has none.  Text is escaped for JSON;
// a name that is not UTF-8 is written with its bytes >= 0x80 and '%'
// percent-encoded (%XX, the scene file's own escape).  Ends with a newline.
std::string segmentationLegendJson(const RenderScene& scene);

}  // namespace rscene::render
