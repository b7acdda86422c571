// How rscene-diff compares one value of a record: by its schema type.
// Numbers inside scalars, vectors, colors, quaternions and lists all go
// through the same tolerance; names through their enumeration; text after
// decoding.  Long lists are compared entry by entry (a transform list's
// entry has a position, an orientation and a scale), so a diff can name
// `instances[3].position` instead of printing 10 000 numbers.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "core/diff.hpp"

namespace rscene {

// One named value of a record: a positional field (one token, or one per
// component of a vector written over several) or a key.
struct DiffValue {
  std::string_view name;
  ValueType type = ValueType::Text;  // the schema type; Text for unknown keys
  bool positional = false;
  bool unknownTokens = false;  // the positional text of an unknown record kind
  const FieldDef* def = nullptr;  // nullptr for unknown keys
  std::vector<std::string_view> tokens;  // raw (encoded) text
};

class ValueComparer {
 public:
  ValueComparer(const DiffOptions& options, int oldVersion, int newVersion)
      : opt_(options), oldVersion_(oldVersion), newVersion_(newVersion) {}

  // Appends what changed from `a` to `b` (both present) to `out`: nothing
  // when they hold the same value; one FieldDiff; or, for a long list, a
  // summary followed by its changed entries.
  void compare(const DiffValue& a, const DiffValue& b, std::vector<FieldDiff>& out) const;

  // A number list whose entries have names on both sides (`namesA` for a,
  // `namesB` for b): compared by name, a changed entry shown as
  // `field[NAME]`.  False, with nothing appended, when a side's list does
  // not have one entry per name (then compare() by index is the answer).
  bool compareNamed(const DiffValue& a, const DiffValue& b, const std::vector<std::string>& namesA,
                    const std::vector<std::string>& namesB, std::vector<FieldDiff>& out) const;

  // A value only one side has (`isOld`: the old side): one FieldDiff,
  // added or removed, with its canonical text, or, for a long list, a
  // summary that counts its entries.
  void whole(const DiffValue& v, bool isOld, std::vector<FieldDiff>& out) const;

  // Canonical text of a value, written for a file of `version`.
  static std::string display(const DiffValue& v, int version);

  bool closeEnough(double x, double y) const;

 private:
  bool sameToken(std::string_view x, std::string_view y, ValueType type, const FieldDef* def) const;
  bool sameNumbers(std::string_view x, std::string_view y, ValueType type) const;
  bool sameItems(std::vector<std::string_view> x, std::vector<std::string_view> y, ValueType type) const;
  FieldDiff wholeChange(const DiffValue& a, const DiffValue& b) const;
  void compareList(const DiffValue& a, const DiffValue& b, std::vector<FieldDiff>& out) const;

  const DiffOptions& opt_;
  int oldVersion_, newVersion_;
};

}  // namespace rscene
