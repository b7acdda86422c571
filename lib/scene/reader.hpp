// Typed access to one record's fields by the schema's field names, for the
// scene model.  A field is looked up among the positional fields of the
// record's layout, then among its keys.  An absent field (or one written
// `-`) has the schema table's default (FieldDef::defaultValue), the one
// place defaults are written: the accessors without a fallback read it, and
// reading a field the schema gives no default is a programming error
// (std::logic_error, found by tests/scene/defaults_test.cpp).  The forms
// with a fallback are for values the schema cannot hold: derived ones (a
// contact pair's friction is the solver's default friction) and ones that
// are unused when absent.  A value that does not parse adds an error with
// the validator's code for it (RS2xxx, at the value's line and column) and
// yields the default.
//
// A reader of an absent record (a scene without a `solver` record ...)
// yields every field's default, so absent records need no second copy of
// the defaults either.
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
  // An absent record of `kind`: every field is its default.
  RecordReader(const Document& doc, const KindDef& kind, Diagnostics& diagnostics);

  // Whether the record wrote the field (positional, or key present).
  bool has(std::string_view name) const;
  // Decoded text of the field: components of a positional vector joined by
  // `,`; the schema default when absent; nullopt when neither.
  std::optional<std::string> text(std::string_view name) const;
  std::string str(std::string_view name, std::string fallback = {}) const;
  // Value, or the schema default.
  double number(std::string_view name) const;
  std::int64_t integer(std::string_view name) const;
  bool flag(std::string_view name) const;
  std::uint64_t group(std::string_view name) const;
  std::string name(std::string_view name) const;
  Eigen::Vector3d vec3(std::string_view name) const;
  Eigen::Vector4d color(std::string_view name) const;
  // Value, or the schema default, or `fallback` where the schema has none.
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
  // 1-based column of the field's value (where diagnostics point), or 0.
  std::uint32_t columnOf(std::string_view name) const;

  void error(std::string_view name, const char* code, const std::string& message, std::string hint = {},
             Severity severity = Severity::Error) const;
  const Record& record() const { return *rec_; }  // a present record only
  bool present() const { return rec_ != nullptr; }
  std::uint32_t line() const { return rec_ ? rec_->line : 0; }

 private:
  struct Located {
    const FieldDef* def = nullptr;
    int firstToken = -1;             // positional
    const Field* key = nullptr;      // key=value
  };
  Located locate(std::string_view name) const;
  void bad(std::string_view name, std::string_view value, std::string_view expected, const char* code) const;
  static const char* numberCode(std::string_view s);
  bool components(std::string_view name, std::vector<double>& out) const;
  // The schema default of `name`, or nullopt when the record wrote it;
  // throws std::logic_error when it is absent and has no default.
  std::optional<std::string> defaultText(std::string_view name, std::string_view expected, const char* code) const;

  const Document& doc_;
  const Record* rec_ = nullptr;  // nullptr: an absent record
  const KindDef* kind_ = nullptr;
  const Layout* layout_ = nullptr;
  Diagnostics& diags_;
};

// The one way a finding about a record is reported outside the readers:
// at `field` of record `recordIndex` of `doc` (line:col; the record's
// first column when the field is not written), or bare, with no position,
// when there is no document or no such record (a world built without one,
// by a test or a library caller).
void reportAt(const Document* doc, int recordIndex, std::string_view field, const char* code,
              const std::string& message, Diagnostics& diagnostics, Severity severity = Severity::Error,
              std::string hint = {});

}  // namespace rscene
