// Private to rscene-from-xml's mapping (from_xml*.cpp): the state of one
// conversion, the typed attribute readers that report a bad value at its
// attribute, and the builder of one record line.  Every reader returns
// nothing after an error diagnostic, so a caller only has to stop.
#pragma once
#include <array>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/codes.hpp"
#include "robot/load.hpp"
#include "xml/from_xml.hpp"

namespace rscene::xml::detail {

// Codes of the mapping (registry: core/check_codes.cpp).
namespace code {
inline constexpr const char* kBadValue = rs::RS8110;      // value that cannot become a field
inline constexpr const char* kNotConverted = rs::RS8111;  // unknown element or attribute (warning)
inline constexpr const char* kMissing = rs::RS8112;       // required child or attribute missing
inline constexpr const char* kApproximate = rs::RS8113;   // renamed, left flat, robot not read, mesh not found (warning)
inline constexpr const char* kBadAsset = rs::RS8114;      // heightmap PNG or text unreadable
inline constexpr const char* kRefused = rs::RS8125;       // a record the scene checks refuse (their code in the message)
}  // namespace code

// One record line, tokens separated by single spaces.
class Line {
 public:
  explicit Line(std::string_view tag) : s_(tag) {}
  Line& text(std::string_view value);  // percent-encoded, "" as "-"
  Line& raw(std::string_view token);   // already a token (true, dynamic ...)
  Line& num(double v);
  template <std::size_t N>
  Line& nums(const std::array<double, N>& v) {
    for (double x : v) num(x);
    return *this;
  }
  Line& u64(std::uint64_t v);
  Line& key(std::string_view name, std::string_view rawValue);
  Line& keyText(std::string_view name, std::string_view value);  // percent-encoded
  Line& keyNum(std::string_view name, double v);
  Line& keyNums(std::string_view name, const double* v, std::size_t n);  // CSV
  template <std::size_t N>
  Line& keyNums(std::string_view name, const std::array<double, N>& v) {
    return keyNums(name, v.data(), N);
  }
  Line& keyList(std::string_view name, const std::vector<std::string>& items);  // `;`-separated
  const std::string& str() const { return s_; }

 private:
  std::string s_;
};

using Vec3 = std::array<double, 3>;
using Quat = std::array<double, 4>;  // w x y z

struct Context {
  Context(const FromXmlOptions& o, FromXmlResult& r) : options(o), result(r) {}
  const FromXmlOptions& options;
  FromXmlResult& result;
  std::string records;                         // the record lines, LF-terminated
  // The element each line of `records` came from, in order, so a finding
  // of the scene checks on a record line is reported at its element.
  std::vector<const Element*> origins;
  std::set<std::string> paths;                 // every record path taken
  // Renames of repeated paths, by the path wanted, in order.
  std::vector<std::pair<std::string, std::vector<std::string>>> renamed;
  // Per path wanted: its entry in `renamed` and the next suffix to try, so
  // 10^6 bodies of one name are renamed in linear time.
  std::map<std::string, std::pair<std::size_t, int>> renames;
  std::map<std::string, std::string> bodies;   // XML name -> record path (first wins)
  // An articulated system wires can name: its record path and its model
  // (nullptr when the robot file did not load).
  struct Robot {
    std::string path;
    std::shared_ptr<const robot::Model> model;
  };
  std::map<std::string, Robot> robots;            // XML name -> robot (first wins)
  std::map<std::string, std::string> resourceOf;  // robot file as written -> articulated_resource id
  std::set<std::string> resourceIds;
  robot::ModelCache models;
  std::set<std::string> notConverted;          // dedup of result.notConverted

  // Appends one record line made from element `from`.
  void add(const Line& line, const Element& from) { add(line.str(), from); }
  void add(const std::string& line, const Element& from) {
    records += line;
    records += '\n';
    origins.push_back(&from);
  }
  void error(const char* code, const Element& e, std::string message);
  void error(const char* code, const Element& e, const Attribute& a, std::string message);
  void warning(const char* code, const Element& e, std::string message);
  // Lists what the XML says that the scene cannot hold (the one warning line).
  void lost(std::string what);
  // appearance="hidden" (RaiSim's way to keep a body out of the picture):
  // the record's visible field, false.  Any other appearance (a colour or
  // material name) has no field and is listed as not converted.
  bool visible(const Element& e, const std::string& label);

  // --- attribute readers: nullopt after an error at the attribute ---
  // A finite number; absent: nullopt without an error.
  std::optional<double> number(const Element& e, const Attribute* a);
  // Whitespace- or comma-separated finite numbers (RaiSim writes both).
  bool numbers(const Element& e, const Attribute& a, std::vector<double>& out);
  template <std::size_t N>
  std::optional<std::array<double, N>> vec(const Element& e, const Attribute* a) {
    if (!a) return std::nullopt;
    std::vector<double> v;
    if (!numbers(e, *a, v)) return std::nullopt;
    if (v.size() != N) {
      error(code::kBadValue, e, *a, "expected " + std::to_string(N) + " numbers, found " + std::to_string(v.size()));
      return std::nullopt;
    }
    std::array<double, N> out{};
    for (std::size_t i = 0; i < N; ++i) out[i] = v[i];
    return out;
  }
  // A whole number in [min, max].
  std::optional<std::int64_t> integer(const Element& e, const Attribute* a, std::int64_t min, std::int64_t max);
  // A collision group or mask: a decimal uint64, -1 (all bits), or
  // collision[i|j|...] (0 <= i < 64, -1 = all bits).
  std::optional<std::uint64_t> group(const Element& e, const Attribute* a);
  // A required attribute (RS8112 at the element when absent).
  const Attribute* require(const Element& e, std::string_view name, std::string_view alias = {});
  // A required path: present (RS8112) and not empty (RS8110).
  const Attribute* requirePath(const Element& e, std::string_view name, std::string_view alias = {});
  const Element* requireChild(const Element& e, std::string_view name, std::string_view alias = {});

  // Reports attributes and children outside `known`: those in `lostNames`
  // (known to RaiSim, no .rscene field) only in the not-converted line,
  // anything else also as an RS8111 warning.  `label` names the element
  // in that line ("sphere 'ball'").
  void checkAttributes(const Element& e, const std::string& label, std::initializer_list<std::string_view> known,
                       std::initializer_list<std::string_view> lostNames = {});
  void checkChildren(const Element& e, const std::string& label, std::initializer_list<std::string_view> known,
                     std::initializer_list<std::string_view> lostNames = {});

  // The record path of an XML name ('/'-rooted as is, else /World/NAME,
  // absent /World/TAG), made unique with _2, _3 ...
  std::string takePath(const Element& e);
  // An asset path (mesh, robot, resource directory) as the scene writes it:
  // relative to options.outputDir, or absolute.
  std::string assetPath(const std::string& written) const;
};

// "sphere 'ball'" or "sphere" for messages and the not-converted line.
std::string labelOf(const Element& e);
// The name a wire uses for a body: its `name`, or its tag when it has none.
inline std::string xmlName(const Element& e) {
  const Attribute* name = e.attribute("name");
  return name ? name->value : e.name;
}

// Element handlers (from_xml_bodies.cpp, from_xml_terrain.cpp, from_xml_robots.cpp).
void convertSingleBody(Context& ctx, const Element& e);  // sphere capsule cylinder box mesh
void convertGround(Context& ctx, const Element& e);
void convertCompound(Context& ctx, const Element& e);
void convertHeightmap(Context& ctx, const Element& e);
void convertArticulated(Context& ctx, const Element& e);
void convertWire(Context& ctx, const Element& e);

// Runs the checks rscene-validate, rscene-sim and rscene-to-xml run on the
// scene `text` (from_xml_check.cpp) and adds each error as an RS8125 error
// at the element line L of `text` came from (lineOrigins[L - 1]; `root`
// when none), at the attribute of the field when there is one.  `doc` is
// left holding the loaded scene, so the caller writes it without parsing
// the text a second time.
void checkConverted(Context& ctx, std::string text, const Element& root,
                    const std::vector<const Element*>& lineOrigins, Document& doc);

}  // namespace rscene::xml::detail
