// <heightmap> as a terrain_region, in its four forms: a `height` list, a
// PNG (decoded here, bounded by the terrain sample limit), a text file of
// numbers (bounded read) and terrain_properties (RaiSim's noise generator
// is not reproduced: the record keeps the parameters, the samples stay
// flat, one warning says so).
#include <algorithm>
#include <tuple>

#include "asset/image.hpp"
#include "core/filesystem.hpp"
#include "core/text.hpp"
#include "scene/scene.hpp"
#include "xml/from_xml_context.hpp"

namespace rscene::xml::detail {
namespace {

constexpr std::int64_t kMaxSamplesPerAxis = 16384;  // lib/scene's bound (RS4001)

struct Grid {
  std::int64_t xs = 0, ys = 0;
  double xSize = 0, ySize = 0;
  std::vector<double> heights;
};

bool readCounts(Context& ctx, const Element& e, Grid& g) {
  auto xs = ctx.integer(e, ctx.require(e, "x_sample", "xSample"), 2, kMaxSamplesPerAxis);
  auto ys = ctx.integer(e, ctx.require(e, "y_sample", "ySample"), 2, kMaxSamplesPerAxis);
  if (!xs || !ys) return false;
  if (static_cast<std::uint64_t>(*xs) * static_cast<std::uint64_t>(*ys) > kMaxTerrainSamples) {
    ctx.error(code::kBadValue, e, "x_sample * y_sample is more than 64 Mi samples");
    return false;
  }
  g.xs = *xs;
  g.ys = *ys;
  return true;
}

bool readSizes(Context& ctx, const Element& e, Grid& g) {
  auto xSize = ctx.number(e, ctx.require(e, "x_size", "xSize"));
  auto ySize = ctx.number(e, ctx.require(e, "y_size", "ySize"));
  if (!xSize || !ySize) return false;
  for (auto [v, name] : {std::pair{*xSize, "x_size"}, std::pair{*ySize, "y_size"}})
    if (!(v > 0)) {
      ctx.error(code::kBadValue, e, *e.attribute(name, name[0] == 'x' ? "xSize" : "ySize"), "is not positive");
      return false;
    }
  g.xSize = *xSize;
  g.ySize = *ySize;
  return true;
}

// The first of `names` present (RS8112 naming the first when none is).
const Attribute* requireOneOf(Context& ctx, const Element& e, std::initializer_list<std::string_view> names) {
  for (std::string_view n : names)
    if (const Attribute* a = e.attribute(n)) return a;
  return ctx.require(e, *names.begin());
}

std::size_t byteLimit() { return static_cast<std::size_t>(kMaxTerrainSamples) * 32; }

// Option 2: the PNG's pixels are the samples (width x height); a sample is
// the red channel / 255 * z_scale + z_offset.  The image's top row is the
// +y edge (north up, as the picture is seen), so sample (x, y) reads row
// height-1-y.
bool readPng(Context& ctx, const Element& e, const Attribute& png, double scale, double offset, Grid& g) {
  std::string bytes, why;
  if (!ctx.options.fileSystem().read(png.value, bytes, &why, byteLimit())) {
    ctx.error(code::kBadAsset, e, png, "cannot read '" + png.value + "': " + why);
    return false;
  }
  asset::Image image;
  asset::ImageLimits limits;
  limits.maxPixels = kMaxTerrainSamples;
  if (!asset::decodeImage(bytes, image, &why, limits)) {
    ctx.error(code::kBadAsset, e, png, "cannot decode '" + png.value + "': " + why);
    return false;
  }
  if (image.width < 2 || image.height < 2 || image.width > kMaxSamplesPerAxis || image.height > kMaxSamplesPerAxis) {
    ctx.error(code::kBadAsset, e, png,
              "'" + png.value + "' is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                  " pixels: each side must be 2 to 16384");
    return false;
  }
  g.xs = image.width;
  g.ys = image.height;
  g.heights.resize(static_cast<std::size_t>(g.xs * g.ys));
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      g.heights[static_cast<std::size_t>(y) * g.xs + x] =
          image.pixel(x, image.height - 1 - y)[0] / 255.0 * scale + offset;
  return true;
}

// Option 3: a text file `x_sample y_sample x_size y_size` then the
// x_sample * y_sample heights, x fastest, separated by spaces, commas or
// line breaks.
bool readText(Context& ctx, const Element& e, const Attribute& text, Grid& g) {
  std::string body, why;
  if (!ctx.options.fileSystem().read(text.value, body, &why, byteLimit())) {
    ctx.error(code::kBadAsset, e, text, "cannot read '" + text.value + "': " + why);
    return false;
  }
  std::vector<double> v;
  std::size_t i = 0;
  auto sep = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ','; };
  while (i < body.size()) {
    while (i < body.size() && sep(body[i])) ++i;
    std::size_t j = i;
    while (j < body.size() && !sep(body[j])) ++j;
    if (j == i) break;
    auto n = parseNumber(std::string_view(body).substr(i, j - i));
    if (!n) {
      ctx.error(code::kBadAsset, e, text,
                "'" + text.value + "': '" + body.substr(i, std::min<std::size_t>(j - i, 40)) + "' is not a number");
      return false;
    }
    v.push_back(*n);
    i = j;
  }
  auto whole = [](double d) { return d == static_cast<double>(static_cast<std::int64_t>(d)); };
  if (v.size() < 4 || !whole(v[0]) || !whole(v[1]) || v[0] < 2 || v[1] < 2 || v[0] > kMaxSamplesPerAxis ||
      v[1] > kMaxSamplesPerAxis || !(v[2] > 0) || !(v[3] > 0)) {
    ctx.error(code::kBadAsset, e, text,
              "'" + text.value + "' does not start with x_sample y_sample (2 to 16384) x_size y_size (positive)");
    return false;
  }
  g.xs = static_cast<std::int64_t>(v[0]);
  g.ys = static_cast<std::int64_t>(v[1]);
  g.xSize = v[2];
  g.ySize = v[3];
  std::size_t n = static_cast<std::size_t>(g.xs * g.ys);
  if (v.size() - 4 != n) {
    ctx.error(code::kBadAsset, e, text,
              "'" + text.value + "' has " + std::to_string(v.size() - 4) + " heights, expected " + std::to_string(n));
    return false;
  }
  g.heights.assign(v.begin() + 4, v.end());
  return true;
}

}  // namespace

void convertHeightmap(Context& ctx, const Element& e) {
  std::string label = labelOf(e);
  ctx.checkAttributes(e, label,
                      {"name", "material", "x_sample", "xSample", "y_sample", "ySample", "x_size", "xSize", "y_size",
                       "ySize", "center_x", "centerX", "center_y", "centerY", "height", "png", "z_scale", "zScale",
                       "z_offset", "zOffset", "heightScale", "height_scale", "heightOffset", "height_offset", "text",
                       "collision_mask", "collisionMask"},
                      {"appearance"});
  ctx.checkChildren(e, label, {"terrain_properties", "terrainProperties"});
  std::string path = ctx.takePath(e);
  auto cx = ctx.number(e, ctx.require(e, "center_x", "centerX"));
  auto cy = ctx.number(e, ctx.require(e, "center_y", "centerY"));
  // A terrain_region has no collision mask: one other than "all" is lost.
  if (auto mask = ctx.group(e, e.attribute("collision_mask", "collisionMask")); mask && *mask != ~std::uint64_t{0})
    ctx.lost(label + ": collision_mask");
  Grid g;
  Line keys("");
  const Attribute* material = e.attribute("material");
  keys.keyText("contactMaterial", material && !material->value.empty() ? material->value : "default");
  const Element* props = e.child("terrain_properties", "terrainProperties");
  if (const Attribute* png = e.attribute("png")) {
    // heightMapUsingPng.xml spells them heightScale / heightOffset.
    auto scale = ctx.number(e, requireOneOf(ctx, e, {"z_scale", "zScale", "heightScale", "height_scale"}));
    auto offset = ctx.number(e, requireOneOf(ctx, e, {"z_offset", "zOffset", "heightOffset", "height_offset"}));
    if (!readSizes(ctx, e, g) || !scale || !offset || !readPng(ctx, e, *png, *scale, *offset, g)) return;
    // The PNG's pixels are the samples (heightMapUsingPng.xml gives no
    // counts); counts that disagree are not resampled, and say so.
    for (auto [name, alias, have] : {std::tuple{"x_sample", "xSample", g.xs}, std::tuple{"y_sample", "ySample", g.ys}})
      if (const Attribute* a = e.attribute(name, alias))
        if (auto n = ctx.integer(e, a, 2, kMaxSamplesPerAxis); n && *n != have)
          ctx.warning(code::kApproximate, e,
                      std::string(name) + " " + std::to_string(*n) + " differs from the PNG's " +
                          std::to_string(have) + " pixels: the pixels are the samples, not resampled");
    keys.key("sourceKind", "png").keyText("sourcePath", ctx.assetPath(png->value));
    keys.keyNum("pngHeightScale", *scale).keyNum("pngHeightOffset", *offset);
    keys.keyNums("heights", g.heights.data(), g.heights.size());
  } else if (const Attribute* text = e.attribute("text")) {
    if (!readText(ctx, e, *text, g)) return;
    keys.key("sourceKind", "samples").keyNums("heights", g.heights.data(), g.heights.size());
  } else if (props) {
    if (!readCounts(ctx, e, g) || !readSizes(ctx, e, g)) return;
    std::string propsLabel = label + " <" + props->name + ">";
    ctx.checkAttributes(*props, propsLabel,
                        {"frequency", "z_scale", "zScale", "fractal_octaves", "fractalOctaves", "fractal_lacunarity",
                         "fractalLacunarity", "fractal_gain", "fractalGain", "step_size", "stepSize",
                         "height_offset", "heightOffset", "seed", "x_sample", "xSample", "y_sample", "ySample",
                         "x_size", "xSize", "y_size", "ySize"});
    keys.key("sourceKind", "procedural");
    struct Num {
      const char* xml;
      const char* alias;
      const char* key;
      bool integer;
    };
    const Num nums[] = {{"frequency", "frequency", "proceduralFrequency", false},
                        {"z_scale", "zScale", "proceduralZScale", false},
                        {"fractal_octaves", "fractalOctaves", "proceduralOctaves", true},
                        {"fractal_lacunarity", "fractalLacunarity", "proceduralLacunarity", false},
                        {"fractal_gain", "fractalGain", "proceduralGain", false},
                        {"step_size", "stepSize", "proceduralStepSize", false},
                        {"height_offset", "heightOffset", "proceduralHeightOffset", false},
                        {"seed", "seed", "proceduralSeed", true}};
    for (const Num& n : nums) {
      const Attribute* a = props->attribute(n.xml, n.alias);
      if (!a) continue;
      if (n.integer) {
        if (auto v = ctx.integer(*props, a, 0, 2147483647)) keys.key(n.key, std::to_string(*v));
      } else if (auto v = ctx.number(*props, a)) {
        keys.keyNum(n.key, *v);
      }
    }
    ctx.warning(code::kApproximate, e,
                "terrain_properties: rscene does not reproduce RaiSim's terrain generator, the samples are left flat");
  } else {
    const Attribute* height = ctx.require(e, "height");
    if (!readCounts(ctx, e, g) || !readSizes(ctx, e, g) || !height) return;
    if (!ctx.numbers(e, *height, g.heights)) return;
    std::size_t n = static_cast<std::size_t>(g.xs * g.ys);
    if (g.heights.size() != n) {
      ctx.error(code::kBadValue, e, *height,
                "has " + std::to_string(g.heights.size()) + " numbers, expected x_sample * y_sample = " +
                    std::to_string(n));
      return;
    }
    keys.key("sourceKind", "samples").keyNums("heights", g.heights.data(), g.heights.size());
  }
  if (!cx || !cy) return;
  // terrain_region PATH xSamples ySamples xSize ySize center
  Line l("terrain_region");
  l.text(path).raw(std::to_string(g.xs)).raw(std::to_string(g.ys)).num(g.xSize).num(g.ySize);
  l.nums(Vec3{*cx, *cy, 0});
  ctx.add(l.str() + keys.str(), e);
  ctx.bodies.emplace(xmlName(e), path);
}

}  // namespace rscene::xml::detail
