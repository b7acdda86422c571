// Typed, by-name access to one record's fields, positional or key=value,
// through the schema table (so this file knows no field names itself).
// Values that are absent or do not parse give the schema default, then the
// caller's fallback.
#pragma once
#include <Eigen/Geometry>
#include <string>
#include <string_view>
#include <vector>

#include "core/document.hpp"

namespace rscene::render {

class RecordView {
 public:
  RecordView(const Document& doc, const Record& r) : doc_(doc), r_(r) {}

  bool has(std::string_view name) const;
  // Raw (still encoded) text; several tokens of a positional vec3/quat/color
  // are joined with `,`.
  std::string raw(std::string_view name) const;
  std::string text(std::string_view name) const;  // decoded
  // Canonical enumeration name (aliases resolved), lower-case input accepted.
  std::string name(std::string_view field, std::string_view fallback = {}) const;
  double number(std::string_view name, double fallback = 0) const;
  bool flag(std::string_view name, bool fallback = false) const;
  Eigen::Vector3d vec3(std::string_view name, const Eigen::Vector3d& fallback = Eigen::Vector3d::Zero()) const;
  Eigen::Vector2d vec2(std::string_view name, const Eigen::Vector2d& fallback = Eigen::Vector2d::Zero()) const;
  // r,g,b[,a]; alpha defaults to 1.
  Eigen::Vector4d color(std::string_view name, const Eigen::Vector4d& fallback = Eigen::Vector4d(1, 1, 1, 1)) const;
  // w,x,y,z, normalised; identity when absent or degenerate.
  Eigen::Quaterniond quat(std::string_view name) const;
  std::vector<double> numbers(std::string_view name) const;
  std::uint32_t line() const { return r_.line; }
  const Record& record() const { return r_; }

 private:
  std::string schemaDefault(std::string_view name) const;
  const Document& doc_;
  const Record& r_;
};

}  // namespace rscene::render
