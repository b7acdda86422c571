// The image-size check of rscene-render (README, "Resource limits:
// rscene-render"): done before any framebuffer is allocated.
#pragma once
#include <cstdint>
#include <string>

#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "scene/scene.hpp"

namespace rscene::render {

struct ImageSize {
  int width = 0, height = 0;
};

// The size a camera record's view (or the automatic view) is drawn at,
// each side on its own: `width`/`height` when > 0 (--width/--height), else
// the camera's when > 0, else kDefaultImageWidth x kDefaultImageHeight
// (renderer.hpp).  The one place the default is decided; a sensor keeps
// its own size (its intrinsics are written for it).
ImageSize cameraImageSize(const Camera& camera, int width = 0, int height = 0);

// Empty when a `width` x `height` image fits in `maxPixels` and each side
// in kMaxImageSide (renderer.hpp), else the reason ("16384x16384 is
// 268435456 pixels, more than --max-pixels 16777216").
std::string imageSizeProblem(std::int64_t width, std::int64_t height, std::uint64_t maxPixels);

// The same check for a size the camera record asks for: an RS9013 error at
// the camera's width field (file:line:col), false when it does not fit.
bool checkCameraImageSize(const Document& doc, const Camera& camera, std::int64_t width, std::int64_t height,
                          std::uint64_t maxPixels, Diagnostics& diags);

}  // namespace rscene::render
