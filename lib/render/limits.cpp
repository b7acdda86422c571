#include "render/limits.hpp"

#include "core/codes.hpp"
#include "render/renderer.hpp"
#include "scene/reader.hpp"

namespace rscene::render {

ImageSize cameraImageSize(const Camera& camera, int width, int height) {
  ImageSize s;
  s.width = width > 0 ? width : camera.width > 0 ? camera.width : kDefaultImageWidth;
  s.height = height > 0 ? height : camera.height > 0 ? camera.height : kDefaultImageHeight;
  return s;
}

std::string imageSizeProblem(std::int64_t width, std::int64_t height, std::uint64_t maxPixels) {
  std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
    return size + " is outside 1.." + std::to_string(kMaxImageSide) + " on a side";
  std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);  // both <= 16384: no overflow
  if (pixels > maxPixels)
    return size + " is " + std::to_string(pixels) + " pixels, more than --max-pixels " + std::to_string(maxPixels);
  return {};
}

bool checkCameraImageSize(const Document& doc, const Camera& camera, std::int64_t width, std::int64_t height,
                          std::uint64_t maxPixels, Diagnostics& diags) {
  std::string problem = imageSizeProblem(width, height, maxPixels);
  if (problem.empty()) return true;
  if (camera.recordIndex > 0 && std::size_t(camera.recordIndex) < doc.records.size()) {
    RecordReader r(doc, std::size_t(camera.recordIndex), diags);
    r.error("width", rs::RS9013, "camera image " + problem, "give --width and --height, or raise --max-pixels");
  } else {
    Diagnostic d;
    d.severity = Severity::Error;
    d.code = rs::RS9013;
    d.message = "camera image " + problem;
    diags.push_back(std::move(d));
  }
  return false;
}

}  // namespace rscene::render
