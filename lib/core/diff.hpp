// Semantic diff of two scenes (rscene-diff): records are matched by their
// identity (diff_identity.hpp), not by line; reordered records and keys
// are no change; every value is compared as a value of its schema type
// (diff_value.hpp), with optional tolerances; long lists name their
// changed entries.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/document.hpp"

namespace rscene {

struct DiffOptions {
  double tolerance = 0;     // |a - b| <= tolerance is no change, for every number (vector, list item)
  double relTolerance = 0;  // |a - b| <= relTolerance * max(|a|, |b|) is no change
  bool ignoreEditorState = false;  // snapping, editor_ux, render_bake, locked, expanded, selection*
  std::vector<std::string> ignore;  // field names, or tag.field
  std::size_t summarizeAbove = 16;  // lists with more values are summarised
  std::size_t listEntries = 10;     // changed entries of a summarised list named one by one
  // Names of the entries of a number list that a layer above lib/core
  // understands: rscene-diff names generalizedCoordinate's and
  // generalizedVelocity's entries by joint from the robot model (lib/robot).
  // Called with a side's document, the record's index and the field; empty
  // when the entries have no names.  When both sides name every entry of
  // their list, the list is compared by name (a reordered jointOrder is no
  // change) and a changed entry shows as `field[NAME]`; otherwise by index.
  std::function<std::vector<std::string>(const Document&, std::size_t record, std::string_view field)> entryNames =
      nullptr;
};

enum class Change { Added, Removed, Changed };
const char* changeName(Change c);

struct FieldDiff {
  // The schema name; an entry of a long list is `instances[3].position`,
  // `heights[7]`.  0-based like JSON arrays.
  std::string name;
  Change change = Change::Changed;
  ValueType type = ValueType::Text;  // of oldValue/newValue
  // A key=value whose kind also has a positional field of this name (the
  // two are different fields: `deformable` scale vec3 and scale=).
  bool keyForm = false;
  bool entry = false;  // an entry of the summarised list before it
  std::string oldValue, newValue;  // canonical text
  bool oldDefault = false, newDefault = false;  // not written: the schema default
  // Long lists: counts of entries (values for number lists); the changed
  // entries follow as FieldDiffs of their own, the first `listedCount`.
  bool summarized = false;
  std::size_t oldCount = 0, newCount = 0, changedCount = 0, listedCount = 0;
  double maxDelta = 0;  // largest |a - b| over numbers of the common entries
};

struct RecordDiff {
  Change change = Change::Changed;
  std::string tag;
  std::string key;       // identity, as people read it
  // Node path (new side, or old side when removed); a child record's is its
  // parent's path and its place: `/World/Cart[1]`, `/World/T[slot=2]`.
  std::string path;
  std::string oldPath;   // when a node kept its id but changed its path
  std::uint32_t oldLine = 0, newLine = 0;
  // What changed; for an added record every field it writes (added), for a
  // removed one every field it wrote (removed), long lists as a count.
  std::vector<FieldDiff> fields;
  bool renamed() const { return !oldPath.empty(); }
};

struct DiffResult {
  std::vector<RecordDiff> records;  // writer order of the kinds
  std::size_t oldRecords = 0, newRecords = 0;
  bool same() const { return records.empty(); }
  std::size_t count(Change c) const;
};

DiffResult diff(const Document& oldDoc, const Document& newDoc, const DiffOptions& options = {});

// Checks one --ignore entry (NAME or TAG.NAME) against the schema and the
// keys the two documents use: nullopt when it names a field, else a message
// with a suggestion ("no field 'colr'; did you mean 'color'?").
std::optional<std::string> checkIgnoreName(std::string_view entry, const Document& oldDoc, const Document& newDoc);

// The result as JSON ({"same":..., "stat":{...}, "records":[...]}), values
// typed like rscene-to-json's (numbers, booleans, arrays, strings).
std::string diffToJson(const DiffResult& result);

}  // namespace rscene
