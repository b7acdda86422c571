// Typed access to one record's fields by the schema's field names, for the
// scene view.  A field is looked up among the positional fields of the
// record's layout, then among its keys; an absent field falls back to the
// schema default, then to the caller's fallback.  A value that does not
// parse adds an error with the validator's code for it (RS2xxx, at the
// value's line and column) and yields the fallback.
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostic.hpp"
#include "core/document.hpp"

namespace rscene {

class RecordReader {
 public:
  RecordReader(const Document& doc, std::size_t recordIndex, Diagnostics& diagnostics);

  // Whether the record wrote the field (positional, or key present).
  bool has(std::string_view name) const;
  // Decoded text of the field: components of a positional vector joined by
  // `,`; the schema default when absent; nullopt when neither.
  std::optional<std::string> text(std::string_view name) const;
  std::string str(std::string_view name, std::string fallback = {}) const;
  double number(std::string_view name, double fallback) const;
  std::int64_t integer(std::string_view name, std::int64_t fallback) const;
  bool flag(std::string_view name, bool fallback) const;
  std::uint64_t group(std::string_view name, std::uint64_t fallback) const;
  // Canonical enumeration name; an unknown name of an open enum is kept
  // lower-case as written; of a closed one reported and `fallback`.
  std::string name(std::string_view name, std::string fallback) const;
  // Numbers of a vector field; `n` components (color: 3 or 4, alpha 1).
  Eigen::Vector3d vec3(std::string_view name, const Eigen::Vector3d& fallback) const;
  Eigen::Vector4d color(std::string_view name, const Eigen::Vector4d& fallback) const;
  Eigen::Vector4d quat(std::string_view name) const;  // w,x,y,z; identity default
  // Any numeric list; false (after a diagnostic) when malformed.
  bool numbers(std::string_view name, std::vector<double>& out) const;
  // Positional token index where field `name` starts, or -1.
  int positionalToken(std::string_view name) const;

  void error(std::string_view name, const char* code, const std::string& message, std::string hint = {},
             Severity severity = Severity::Error) const;
  const Record& record() const { return rec_; }
  std::uint32_t line() const { return rec_.line; }

 private:
  struct Located {
    const FieldDef* def = nullptr;
    int firstToken = -1;             // positional
    const Field* key = nullptr;      // key=value
  };
  Located locate(std::string_view name) const;
  std::uint32_t columnOf(std::string_view name) const;
  void bad(std::string_view name, std::string_view value, std::string_view expected, const char* code) const;
  static const char* numberCode(std::string_view s);
  bool components(std::string_view name, std::vector<double>& out) const;

  const Document& doc_;
  const Record& rec_;
  const Layout* layout_ = nullptr;
  Diagnostics& diags_;
};

}  // namespace rscene
