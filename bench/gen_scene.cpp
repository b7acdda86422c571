// rscene-bench-gen: writes a deterministic synthetic scene of about
// --size bytes to stdout, shaped like the real files in ../shared/corpus:
// Engine 2's editor records, materials carrying every key the schema knows
// (~230, like rayrai_forest_head.rscene), a terrain whose per-sample lists
// reach about a million samples at 128 MB, thousands of objects under zone
// folders, lights, cameras and instanced_visual batches with long
// `instances=` lists.  About one record in 150 is written the way a hand
// edit or another generator would (`0.50`, `yes`, `%3d`, a record out of
// the writer's order) so that the formatter has real work to do.
//
// Key names come from the schema: the generator refuses to run if one it
// writes is not in the table, so a renamed key cannot silently turn the
// benchmark into a benchmark of unknown keys.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/schema.hpp"
#include "rng.hpp"

namespace {

using rscene::FieldDef;
using rscene::KindDef;
using rscene::Schema;
using rscene::ValueType;

constexpr double kNoiseRate = 1.0 / 150.0;  // records written non-canonically

class Out {
 public:
  ~Out() { flush(); }
  void flush() {
    if (!buf_.empty() && std::fwrite(buf_.data(), 1, buf_.size(), stdout) != buf_.size())
      throw std::runtime_error("cannot write to standard output");
    buf_.clear();
  }
  void put(std::string_view s) {
    buf_.append(s);
    total_ += s.size();
    if (buf_.size() >= (1u << 20)) flush();
  }
  std::uint64_t total() const { return total_; }

 private:
  std::string buf_;
  std::uint64_t total_ = 0;
};

// One record line under construction.
class Line {
 public:
  Line(const char* tag, Rng& rng) : kind_(Schema::get().kind(tag)), rng_(rng) {
    if (!kind_) throw std::logic_error(std::string("schema has no record kind ") + tag);
    s_ = tag;
    noisy_ = rng.chance(kNoiseRate);
  }
  // A positional token.
  Line& pos(std::string_view v) {
    s_ += ' ';
    s_ += v;
    return *this;
  }
  Line& pos(double v, int decimals = 4) { return pos(number(v, decimals)); }
  // key=value; the key must be one the schema knows for this kind.
  Line& key(std::string_view name, std::string_view v) {
    if (!kind_->key(name))
      throw std::logic_error("schema has no key " + std::string(name) + " on " + kind_->tag);
    s_ += ' ';
    s_ += name;
    s_ += '=';
    s_ += v;
    return *this;
  }
  Line& key(std::string_view name, double v, int decimals = 4) { return key(name, number(v, decimals)); }
  Line& flag(std::string_view name, bool v) { return key(name, flagText(v)); }
  bool noisy() const { return noisy_; }
  const KindDef& kind() const { return *kind_; }
  std::string& text() { return s_; }

  // Shortest round-trip text of `v` rounded to `decimals` places: what
  // Engine 2 writes.  A noisy record spells one number the long way.
  std::string number(double v, int decimals) {
    std::string t = canonicalNumber(v, decimals);
    if (noisy_ && !spent_ && t.find('e') == std::string::npos) {
      spent_ = true;
      t += t.find('.') == std::string::npos ? ".0" : "0";
    }
    return t;
  }
  std::string flagText(bool v) {
    if (noisy_ && !spent_) {
      spent_ = true;
      return v ? "yes" : "off";
    }
    return v ? "true" : "false";
  }
  static std::string canonicalNumber(double v, int decimals) {
    double scale = std::pow(10.0, decimals);
    double k = std::nearbyint(v * scale);
    if (k == 0) return "0";
    char buf[32];
    auto [p, ec] = std::to_chars(buf, buf + sizeof buf, k / scale);
    return std::string(buf, p);
  }

 private:
  const KindDef* kind_;
  Rng& rng_;
  std::string s_;
  bool noisy_ = false;
  bool spent_ = false;
};

// A plausible value for a key the generator has no opinion about: the
// schema's default, else something of the right type.
std::string plainValue(const FieldDef& f) {
  if (f.defaultValue) return *f.defaultValue;
  switch (f.type) {
    case ValueType::Number: return "1";
    case ValueType::Integer: return "0";
    case ValueType::Group: return "1";
    case ValueType::Flag: return "false";
    case ValueType::Name:
      return f.enumDef && !f.enumDef->values.empty() ? f.enumDef->values[0].name : std::string("default");
    case ValueType::Vec2: return "1,1";
    case ValueType::Vec3: return "0,0,0";
    case ValueType::Quat: return "1,0,0,0";
    case ValueType::Color: return "1,1,1,1";
    case ValueType::Text:
    case ValueType::Path:
    case ValueType::Id:
    case ValueType::Ref: return "-";
    default: return "";  // lists: empty, written as `key=` like Engine 2
  }
}

// Every key of the kind in schema order, with `id` set and the rest plain.
void allKeys(Line& l, std::string_view id) {
  for (const FieldDef& f : l.kind().keys) l.key(f.name, f.type == ValueType::Id ? std::string(id) : plainValue(f));
}

class Generator {
 public:
  Generator(std::uint64_t target, std::uint64_t seed, int version) : target_(target), rng_(seed), version_(version) {}

  void run() {
    header();
    resources();
    folders();
    terrain();
    lights(1 + static_cast<int>(target_ >> 21));
    cameras();
    // Objects fill what is left after a share kept for instanced batches.
    std::uint64_t instancedShare = target_ / 7;
    objects(target_ > instancedShare ? target_ - instancedShare : 0);
    while (out_.total() < target_) instancedBatch(target_ - out_.total());
    out_.flush();
  }

 private:
  void emit(Line& l) {
    l.text() += '\n';
    out_.put(l.text());
  }

  void header() {
    out_.put("raisim_engine_scene " + std::to_string(version_) + "\n");
    out_.put("# synthetic benchmark scene (rscene-bench-gen), seed and size on the command line\n");
    { Line l("time_step", rng_); l.pos("0.002"); emit(l); }
    { Line l("gravity", rng_); l.pos("0").pos("0").pos("-9.81"); emit(l); }
    {
      Line l("solver", rng_);
      l.pos("150").pos("1e-08").pos("1.5").pos("accurate");
      allKeys(l, "");
      emit(l);
    }
    {
      Line l("snapping", rng_);
      l.pos("true").pos("true");
      for (int i = 0; i < 6; ++i) l.pos("false");
      l.pos("0.1").pos("15").pos("0.1").pos("0").key("surfaceNormal", "0,0,1");
      emit(l);
    }
    { Line l("asset_root", rng_); l.pos("."); emit(l); }
    for (const char* tag : {"scene_graph", "editor_ux", "render_bake"}) {
      Line l(tag, rng_);
      allKeys(l, "");
      emit(l);
    }
    {
      Line l("environment", rng_);
      for (const char* v : {"0.38", "0.38", "0.38", "0.54", "0.54", "0.54", "0.004", "true", "true", "10", "-"}) l.pos(v);
      allKeys(l, "");
      emit(l);
    }
    {
      Line l("weather", rng_);
      l.pos("true");
      allKeys(l, "");
      emit(l);
    }
    { Line l("rayrai_render", rng_); allKeys(l, ""); emit(l); }
  }

  void resources() {
    // Six named materials like the forest file, then one more per 2 MB.
    static const char* names[] = {"engine_default", "forest_blue", "forest_coral", "forest_gold", "forest_cyan",
                                  "forest_violet"};
    int count = 6 + static_cast<int>(target_ >> 21);
    for (int i = 0; i < count; ++i) {
      std::string name = i < 6 ? names[i] : "mat_" + std::to_string(i);
      materials_.push_back(name);
      Line l("material", rng_);
      l.pos(name);
      for (int c = 0; c < 3; ++c) l.pos(rng_.uniform(0.05, 0.95), 2);
      l.pos("1").pos("0").pos(l.number(rng_.uniform(0.2, 0.9), 2));
      for (int c = 0; c < 4; ++c) l.pos("0");
      l.pos("false");
      for (int c = 0; c < 6; ++c) l.pos("-");
      allKeys(l, name);
      emit(l);
    }
    {
      Line l("contact_material", rng_);
      for (const char* v : {"default", "rubber", "0.95", "0.03", "0.001", "0.8", "0.001", "0.01", "0.01"}) l.pos(v);
      l.key("id", "default_rubber");
      emit(l);
    }
    static const char* textures[] = {"forest_mud", "forest_grass", "rock", "sand"};
    for (int i = 0; i < 4; ++i) {
      Line l("terrain_texture", rng_);
      l.pos(std::to_string(i)).pos(textures[i]).pos(std::string("Texture%20") + std::to_string(i));
      l.key("color", "0.4117647058823529,0.4666666666666667,0.3058823529411765,1");
      l.key("albedo", std::string("ground/") + textures[i] + "_diff_1k.jpg");
      l.key("normal", std::string("ground/") + textures[i] + "_nor_gl_1k.jpg");
      l.key("uvScale", "4").key("normalDepth", "1").key("aoStrength", "1").key("roughness", "0.98");
      l.key("detile", "0,0").key("displacement", "0,1");
      emit(l);
    }
    for (int i = 0; i < 8; ++i) {
      Line l("asset", rng_);
      std::string id = "carton_" + std::to_string(i);
      l.pos(id).pos("mesh").pos("cartons/" + id + ".gltf");
      l.key("id", "asset_" + id).key("defaultMaterial", materials_[i % materials_.size()]);
      l.key("contactMaterial", "default").key("bodyMode", "dynamic").key("mass", 2.0, 2);
      l.key("scale", "1,1,1").key("quat", "1,0,0,0").flag("collidable", true);
      l.key("collisionMode", "convex_hull").key("materialRemaps", "").key("importWarnings", "");
      emit(l);
    }
  }

  void group(const std::string& path, const std::string& id, const std::string& parent) {
    Line l("group", rng_);
    l.pos(path).key("id", id).key("parentId", parent);
    l.flag("visible", true).flag("locked", false).flag("expanded", true);
    emit(l);
  }

  void folders() {
    group("/World", "folder_world", "-");
    for (const char* f : {"Physics", "Props", "Lights", "Cameras", "Terrain", "Foliage", "Building"}) {
      std::string lower = f;
      for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      group(std::string("/World/") + f, "folder_" + lower, "folder_world");
    }
  }

  // One region of about size/128 samples: a million at 128 MB.
  void terrain() {
    auto side = static_cast<std::uint64_t>(std::sqrt(static_cast<double>(target_) / 128.0));
    if (side < 17) side = 17;
    if (side > 16384) side = 16384;
    const std::uint64_t n = side * side;
    const std::string path = "/World/Terrain/Field";
    double size = static_cast<double>(side) * 0.25;
    Line l("terrain_region", rng_);
    l.pos(path).pos(std::to_string(side)).pos(std::to_string(side)).pos(size, 2).pos(size, 2);
    l.pos("0").pos("0").pos("0");
    l.key("id", "terrain_field").key("parentGroupId", "folder_terrain").key("location", "0,0");
    l.key("material", materials_[0]).key("contactMaterial", "default").key("baseTexture", "0");
    l.flag("visible", true).flag("collidable", true).flag("castShadow", true).flag("receiveShadow", true);
    l.key("sourceKind", "samples").key("sourcePath", "-").key("cloneSource", "-");
    l.key("lodLevels", "7").key("collisionShapeSize", "64").flag("textureSplattingEnabled", true);
    std::vector<double> h(n);
    double p1 = rng_.uniform(0, 6.28), p2 = rng_.uniform(0, 6.28);
    for (std::uint64_t y = 0; y < side; ++y)
      for (std::uint64_t x = 0; x < side; ++x)
        h[y * side + x] = 1.5 * std::sin(0.031 * static_cast<double>(x) + p1) * std::cos(0.027 * static_cast<double>(y) + p2) +
                          0.3 * std::sin(0.17 * static_cast<double>(x + 2 * y)) + rng_.uniform(-0.02, 0.02);
    std::string& s = l.text();
    s.reserve(s.size() + n * 48);
    auto list = [&](const char* key, auto item, char sep = ',') {
      if (!l.kind().key(key)) throw std::logic_error(std::string("schema has no terrain key ") + key);
      s += ' ';
      s += key;
      s += '=';
      for (std::uint64_t i = 0; i < n; ++i) {
        if (i) s += sep;
        item(i);
      }
    };
    list("heights", [&](std::uint64_t i) { s += l.number(h[i], 4); });
    list("texturePrimary", [&](std::uint64_t i) { s += h[i] > 0.8 ? '2' : h[i] > -0.5 ? '1' : '0'; });
    list("textureSecondary", [&](std::uint64_t i) { s += h[i] > 0.3 ? '2' : '1'; });
    list("textureBlend", [&](std::uint64_t i) { s += Line::canonicalNumber(std::fabs(std::sin(h[i] * 3)), 2); });
    list(
        "vertexColors",
        [&](std::uint64_t i) {
          double g = 0.75 + 0.2 * std::sin(h[i]);
          s += Line::canonicalNumber(g, 2);
          s += ',';
          s += Line::canonicalNumber(g * 0.95, 2);
          s += ',';
          s += Line::canonicalNumber(g * 0.85, 2);
          s += ",1";
        },
        ';');
    emit(l);
    Line splat("terrain_splat_layer", rng_);
    splat.pos(path).key("slot", "2").flag("enabled", true).key("strength", "1");
    std::string& w = splat.text();
    w += " weights=";
    for (std::uint64_t i = 0; i < n; ++i) {
      if (i) w += ',';
      w += Line::canonicalNumber(std::clamp(h[i] - 0.2, 0.0, 1.0), 2);
    }
    emit(splat);
    Line foliage("terrain_foliage_layer", rng_);
    foliage.pos(path).key("id", "foliage_grass").key("name", "Grass").flag("enabled", true);
    foliage.key("primitive", "grass_blade").key("meshPath", "meshes/grass.obj").key("size", "0.06,0.06,0.3");
    foliage.key("densityPerSquareMeter", "120").key("maxInstances", "200000").key("seed", "1234");
    emit(foliage);
  }

  void light(int i) {
    Line l("light", rng_);
    static const char* types[] = {"point", "spot", "area"};
    const char* type = i == 0 ? "directional" : types[i % 3];
    l.pos("/World/Lights/" + std::string(i == 0 ? "Sun" : "Light_" + std::to_string(i)));
    l.pos(-0.53786, 5).pos(0.35197, 5).pos(-0.76604, 5).pos(rng_.uniform(0.5, 4), 2);
    l.key("id", "light_" + std::to_string(i)).key("parentGroupId", "folder_lights").key("type", type);
    l.key("position", coords(3, -30, 30, 3)).key("color", "1,0.97,0.92").flag("shadows", i == 0);
    if (std::strcmp(type, "area") == 0) l.key("areaSize", "31.57,1.2,0").key("areaRight", "1,0,0").key("areaUp", "0,1,0");
    l.key("attenuationLinear", "0.02").key("attenuationQuadratic", "0.008").key("shadowResolution", "4096");
    emit(l);
  }

  void lights(int count) {
    for (int i = 0; i < count; ++i) light(i);
    lightCount_ = count;
  }

  void cameras() {
    for (int i = 0; i < 3; ++i) {
      Line l("camera", rng_);
      l.pos("/World/Cameras/Cam" + std::to_string(i));
      l.pos(9.6, 2).pos(-1 - i, 2).pos(1.3, 2).pos("-0.02617").pos("-0.01745").pos("-0.00046").pos("0.99951");
      l.pos("55").pos("0.05").pos("400").pos("1280").pos("800").pos("rgb").pos("true");
      l.key("id", "camera_" + std::to_string(i)).key("parentGroupId", "folder_cameras").key("projection", "perspective");
      emit(l);
    }
  }

  std::string coords(int n, double lo, double hi, int decimals) {
    std::string s;
    for (int i = 0; i < n; ++i) {
      if (i) s += ',';
      s += Line::canonicalNumber(rng_.uniform(lo, hi), decimals);
    }
    return s;
  }

  void object(std::uint64_t i, const std::string& folder) {
    Line l("object", rng_);
    std::uint64_t kind = rng_.below(100);
    const char* prim = kind < 60 ? "box" : kind < 85 ? "mesh" : kind < 92 ? "sphere" : kind < 97 ? "cylinder" : "capsule";
    bool mesh = prim[0] == 'm';
    std::string name = std::string(mesh ? "Visual_" : "Collider_") + std::to_string(i);
    l.pos("/World/Props/" + folder + "/" + name).pos(prim);
    for (int c = 0; c < 3; ++c) l.pos(rng_.uniform(-40, 40), 5);
    double yaw = rng_.uniform(-3.14159, 3.14159);
    l.pos(std::cos(yaw / 2), 5).pos("0").pos("0").pos(std::sin(yaw / 2), 5);
    for (int c = 0; c < 3; ++c) l.pos(rng_.uniform(0.2, 3), 3);
    l.pos("0.5").pos("1").pos(mesh ? 1.0 : rng_.uniform(0.5, 30), 2);
    l.pos("default").pos(materials_[rng_.below(materials_.size())]);
    bool dynamic = !mesh && rng_.chance(0.2);
    l.pos(l.flagText(mesh)).pos("true").pos(l.flagText(!dynamic && !mesh));
    l.pos(mesh ? "building/prop_" + std::to_string(i % 40) + ".gltf" : std::string("-"));
    l.pos(mesh ? "visual_only" : dynamic ? "dynamic" : "static").pos(mesh ? "false" : "true");
    l.pos("1").pos("18446744073709551615");
    l.key("id", "object_" + std::to_string(i)).key("parentGroupId", "folder_" + folder);
    if (mesh) {
      l.key("renderMeshPath", "building/prop_" + std::to_string(i % 40) + ".gltf");
      l.flag("visualUseMeshColor", false).key("visualShadowCasting", i % 2 ? "off" : "double_sided");
    } else {
      std::string cls = l.noisy() && rng_.chance(0.5) ? "crate%3dstack" : "crate";
      l.key("semanticClass", cls).key("instanceId", std::to_string(i)).key("segmentationColor", coords(3, 0, 1, 2));
      l.flag("castShadow", true);
    }
    emit(l);
  }

  // Objects under zone folders of 500; now and then a zone's group or an
  // extra light comes in the middle of the objects, out of writer order.
  void objects(std::uint64_t until) {
    std::uint64_t i = 0;
    std::string folder;
    while (out_.total() < until) {
      if (i % 500 == 0) {
        folder = "zone_" + std::to_string(i / 500);
        std::string path = "/World/Props/" + folder;
        if (i == 0 || !rng_.chance(0.3)) zones_.push_back(folder);
        else group(path, "folder_" + folder, "folder_props");  // late: out of order
      }
      if (i % 5000 == 4999) light(lightCount_++);
      object(i++, folder);
    }
    // Zones not declared in the middle are declared here, after their
    // objects: a group after objects is out of the writer's order too.
    for (const std::string& z : zones_) group("/World/Props/" + z, "folder_" + z, "folder_props");
  }

  void instancedBatch(std::uint64_t budget) {
    // ~75 bytes per instance; real batches hold a few thousand.
    std::uint64_t count = std::min<std::uint64_t>(budget / 80 + 1, 1000 + rng_.below(4000));
    std::string n = std::to_string(batch_++);
    Line l("instanced_visual", rng_);
    l.pos("/World/Foliage/Batch_" + n).pos("mesh");
    l.key("id", "instanced_" + n).key("parentGroupId", "folder_foliage").key("meshPath", "cartons/carton_" + n + ".gltf");
    l.key("size", "1,1,1").key("colorA", "1,1,1,1").key("colorB", "0.68,0.6,0.5,1");
    std::string& s = l.text();
    s += " instances=";
    double scale = rng_.uniform(0.5, 1.5);
    std::string sc = Line::canonicalNumber(scale, 5);
    for (std::uint64_t k = 0; k < count; ++k) {
      if (k) s += ';';
      s += coords(3, -30, 30, 5);
      double yaw = rng_.uniform(-3.14159, 3.14159);
      s += ',' + Line::canonicalNumber(std::cos(yaw / 2), 5) + ",0,0," + Line::canonicalNumber(std::sin(yaw / 2), 5);
      s += ',' + sc + ',' + sc + ',' + sc;
    }
    s += " colorWeights=";
    for (std::uint64_t k = 0; k < count; ++k) {
      if (k) s += ',';
      s += Line::canonicalNumber(rng_.uniform(0, 1), 2);
    }
    l.flag("castShadows", true).flag("detectable", false).key("maxRenderedInstances", "20000");
    l.flag("grassPatch", false).key("terrainBinding", "-").key("terrainFoliageLayer", "-1").flag("enabled", true);
    emit(l);
  }

  std::uint64_t target_;
  Rng rng_;
  int version_;
  Out out_;
  std::vector<std::string> materials_;
  std::vector<std::string> zones_;
  int lightCount_ = 0;
  int batch_ = 0;
};

int usage(const char* msg) {
  if (msg) std::fprintf(stderr, "rscene-bench-gen: error: %s\n", msg);
  std::fprintf(msg ? stderr : stdout,
               "usage: rscene-bench-gen --size BYTES [--seed N] [--version 1|2]\n"
               "Writes a deterministic synthetic .rscene of about BYTES bytes to standard output.\n"
               "BYTES may end in K, M or G (powers of 1024).\n");
  return msg ? 2 : 0;
}

bool parseSize(std::string_view s, std::uint64_t& out) {
  std::uint64_t v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p == s.data()) return false;
  std::string_view suffix(p, static_cast<std::size_t>(s.data() + s.size() - p));
  int shift = suffix.empty() ? 0 : suffix == "K" ? 10 : suffix == "M" ? 20 : suffix == "G" ? 30 : -1;
  if (shift < 0 || v > (std::uint64_t{1} << 40) >> shift) return false;
  out = v << shift;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t size = 0, seed = 1;
  int version = 1;
  bool haveSize = false;
  for (int i = 1; i < argc; ++i) {
    std::string_view a = argv[i];
    if (a == "--help" || a == "-h") return usage(nullptr);
    if (i + 1 >= argc) return usage(("missing value for " + std::string(a)).c_str());
    std::string_view v = argv[++i];
    if (a == "--size") {
      if (!parseSize(v, size)) return usage("--size wants a byte count such as 1048576 or 16M");
      haveSize = true;
    } else if (a == "--seed") {
      if (!parseSize(v, seed)) return usage("--seed wants a non-negative integer");
    } else if (a == "--version") {
      if (v != "1" && v != "2") return usage("--version is 1 or 2");
      version = v[0] - '0';
    } else {
      return usage(("unknown option " + std::string(a)).c_str());
    }
  }
  if (!haveSize) return usage("--size is required");
  try {
    Generator(size, seed, version).run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rscene-bench-gen: error: %s\n", e.what());
    return 2;
  }
  return std::fflush(stdout) == 0 ? 0 : 2;
}
