// RS4xxx: sizes and values that parse but cannot be right.  Per-sample
// lists are measured by counting separators, never by allocating what a
// record claims.
#include <cmath>

#include "core/codes.hpp"
#include "core/check_context.hpp"
#include "core/text.hpp"

namespace rscene::checks {
namespace {

constexpr std::int64_t kMinSamples = 2;
constexpr std::int64_t kMaxSamples = 16384;
constexpr std::int64_t kMaxTotalSamples = 64ll * 1024 * 1024;
constexpr double kUnitTolerance = 1e-3;
constexpr double kMinFov = 1, kMaxFov = 175;

// Items of a number list, by its separators (0 for an empty list).
std::size_t itemCount(std::string_view s, bool semicolonsOnly = false) {
  if (s.empty()) return 0;
  std::size_t n = 1;
  for (char c : s) n += c == ';' || (!semicolonsOnly && c == ',');
  return n;
}

// Every per-sample list of a terrain or terrain layer has `samples` entries
// (or none).  Which keys are per-sample comes from their types.
void perSampleLists(Context& ctx, const Record& r, std::int64_t samples) {
  const Document& doc = ctx.doc;
  for (std::uint32_t j = r.positionalCount; j < r.fieldCount; ++j) {
    const Field& f = doc.field(r, j);
    if (!f.isKey()) continue;
    const FieldDef* def = ctx.isCurrent(r) ? ctx.defOf(j) : r.kind->key(doc.text(f.key));
    if (!def) continue;
    std::string_view v = doc.text(f.value);
    bool colors = def->type == ValueType::ColorList;
    if (!colors && def->type != ValueType::NumberList && def->type != ValueType::IntegerList) continue;
    std::size_t n = itemCount(v, colors);
    if (n == 0 || static_cast<std::int64_t>(n) == samples) continue;
    ctx.report(colors ? rs::RS4006 : rs::RS4003, r, f.value, def->name,
               def->name + " has " + std::to_string(n) + (colors ? " colors" : " values") + " for " +
                   std::to_string(samples) + " samples",
               "give one entry per sample (xSamples * ySamples), or none");
  }
}

void terrain(Context& ctx, const Record& r) {
  auto xs = ctx.integer(r, "xSamples"), ys = ctx.integer(r, "ySamples");
  bool countsOk = xs && ys;
  for (auto [name, v] : {std::pair{"xSamples", xs}, std::pair{"ySamples", ys}}) {
    if (v && (*v < kMinSamples || *v > kMaxSamples)) {
      ctx.report(rs::RS4001, r, ctx.spanOf(r, ctx.get(r, name)), name,
                 std::string(name) + " is " + std::to_string(*v) + ", outside 2..16384");
      countsOk = false;
    }
  }
  for (const char* name : {"xSize", "ySize"}) {
    if (auto v = ctx.number(r, name); v && !(*v > 0))
      ctx.report(rs::RS4014, r, ctx.spanOf(r, ctx.get(r, name)), name, std::string(name) + " is " + numberText(*v) + ", not positive");
  }
  if (!countsOk) return;
  std::int64_t total = *xs * *ys;
  if (total > kMaxTotalSamples) {
    ctx.report(rs::RS4002, r, ctx.spanOf(r, ctx.get(r, "xSamples")), "xSamples",
               "terrain has " + std::to_string(total) + " samples, more than 64 Mi");
    return;
  }
  perSampleLists(ctx, r, total);
}

void terrainLayer(Context& ctx, const Record& r) {
  std::string name = ctx.text(r, "terrain");
  const Record* found = ctx.terrain(name);
  if (!found) return;  // RS3013 says so
  const Record& t = *found;
  auto xs = ctx.integer(t, "xSamples"), ys = ctx.integer(t, "ySamples");
  if (!xs || !ys || *xs < kMinSamples || *ys < kMinSamples || *xs > kMaxSamples || *ys > kMaxSamples) return;
  if (*xs * *ys <= kMaxTotalSamples) perSampleLists(ctx, r, *xs * *ys);
}

void instances(Context& ctx, const Record& r) {
  FieldRef inst = ctx.get(r, "instances"), weights = ctx.get(r, "colorWeights");
  if (!weights) return;
  std::size_t numbers = inst ? itemCount(ctx.doc.text(inst.first->value)) : 0;
  std::size_t w = itemCount(ctx.doc.text(weights.first->value));
  if (numbers % 10 != 0 || w == 0 || w == numbers / 10) return;
  ctx.report(rs::RS4005, r, weights.first->value, "colorWeights",
             "colorWeights has " + std::to_string(w) + " weights for " + std::to_string(numbers / 10) + " instances",
             "give one weight per instance");
}

void articulated(Context& ctx, const Record& r) {
  FieldRef gc = ctx.get(r, "generalizedCoordinate"), gv = ctx.get(r, "generalizedVelocity");
  if (!gc || !gv) return;
  std::size_t q = itemCount(ctx.doc.text(gc.first->value)), u = itemCount(ctx.doc.text(gv.first->value));
  // Each quaternion (the floating base's, a spherical joint's) is one
  // coordinate more than its velocities (6 and 3 of them): q = u + k with
  // 3k <= u.  The robot model gives the exact lengths (RS7040, RS7041).
  if (q == 0 || u == 0 || (q >= u && 3 * (q - u) <= u)) return;
  ctx.report(rs::RS4007, r, gv.first->value, "generalizedVelocity",
             "generalizedVelocity has " + std::to_string(u) + " values for " + std::to_string(q) + " coordinates",
             "each quaternion (a floating base, a spherical joint) is one coordinate more than its velocities; "
             "no robot has these lengths");
}

// Sizes that are lengths by their meaning; negative values draw and
// collide as nothing sensible.
constexpr std::string_view kLengthFields[] = {"radius", "length", "thickness", "collisionRadius", "range",
                                              "pointSize", "size", "halfExtents", "areaSize"};

// Whether `name` is a size of a body's shape.  The scene model checks those
// at physical size, scale included (lib/scene/check.cpp, RS7003), with the
// same verdict in validate, sim and render; a second check here would name
// the same problem twice.
bool bodySize(const std::string& tag, std::string_view name) {
  return (tag == "object" || tag == "compound_child") && (name == "radius" || name == "size");
}

void negativeSizes(Context& ctx, const Record& r) {
  for (std::string_view name : kLengthFields) {
    if (bodySize(r.kind->tag, name)) continue;
    FieldRef f = ctx.get(r, name);
    if (!f) continue;
    int n = f.def->type == ValueType::Number ? 1 : componentCount(f.def->type);
    if (n == 0) continue;
    double v[4] = {0, 0, 0, 0};
    if (!ctx.vector(r, f, v, n)) continue;
    for (int c = 0; c < n; ++c) {
      if (v[c] >= 0) continue;
      ctx.report(rs::RS4011, r, f.first->value, name, std::string(name) + " is negative (" + numberText(v[c]) + ")");
      break;
    }
  }
}

void camera(Context& ctx, const Record& r) {
  auto nearPlane = ctx.number(r, "nearPlane"), farPlane = ctx.number(r, "farPlane");
  if (nearPlane && !(*nearPlane > 0))
    ctx.report(rs::RS4012, r, ctx.spanOf(r, ctx.get(r, "nearPlane")), "nearPlane",
               "near plane " + numberText(*nearPlane) + " is not positive");
  else if (nearPlane && farPlane && *nearPlane >= *farPlane)
    ctx.report(rs::RS4012, r, ctx.spanOf(r, ctx.get(r, "farPlane")), "farPlane",
               "far plane " + numberText(*farPlane) + " is not beyond the near plane " + numberText(*nearPlane));
  if (r.kind->tag != "camera") return;
  if (auto fov = ctx.number(r, "verticalFov"); fov && (*fov < kMinFov || *fov > kMaxFov))
    ctx.report(rs::RS4013, r, ctx.spanOf(r, ctx.get(r, "verticalFov")), "verticalFov",
               "vertical field of view " + numberText(*fov) + " is outside 1..175 degrees", "it is clamped to that range");
  if (auto fov = ctx.number(r, "horizontalFov"); fov && (*fov < 0 || *fov >= 180))
    ctx.report(rs::RS4013, r, ctx.spanOf(r, ctx.get(r, "horizontalFov")), "horizontalFov",
               "horizontal field of view " + numberText(*fov) + " is outside 0..180 degrees",
               "0 means the vertical field of view decides");
}

}  // namespace

void checkQuaternion(Context& ctx, const Record& r, Span at, std::string_view field, const double q[4]) {
  double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  // Below 1e-12 the direction of a quaternion is rounding noise: the scene
  // model (sim, render) refuses it as zero, and so does the validator.
  if (!(norm >= 1e-12))
    ctx.report(rs::RS4009, r, at, field, std::string(field) + " is the zero quaternion",
               "the identity rotation is 1,0,0,0 (w,x,y,z)");
  else if (std::fabs(norm - 1) > kUnitTolerance)
    ctx.report(rs::RS4010, r, at, field, std::string(field) + " has length " + numberText(norm) + ", not 1",
               "readers normalise it; write a unit quaternion (w,x,y,z)");
}

void checkSizes(Context& ctx, const Record& r) {
  const std::string& tag = r.kind->tag;
  if (tag == "terrain_region") terrain(ctx, r);
  else if (tag == "terrain_splat_layer" || tag == "terrain_foliage_layer") terrainLayer(ctx, r);
  else if (tag == "instanced_visual") instances(ctx, r);
  else if (tag == "articulated") articulated(ctx, r);
  else if (tag == "camera" || tag == "sensor") camera(ctx, r);
  negativeSizes(ctx, r);
}

}  // namespace rscene::checks
