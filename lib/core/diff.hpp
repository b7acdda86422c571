// Semantic diff of two scenes (rscene-diff): records are matched by their
// identity (diff_identity.hpp), not by line; reordered records and keys
// are no change; fields are compared as values of their schema type, with
// optional tolerances; long lists are summarised.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/document.hpp"

namespace rscene {

struct DiffOptions {
  double tolerance = 0;     // |a - b| <= tolerance is no change
  double relTolerance = 0;  // |a - b| <= relTolerance * max(|a|, |b|) is no change
  bool ignoreEditorState = false;  // snapping, editor_ux, render_bake, locked, expanded, selection*
  std::vector<std::string> ignore;  // field names, or tag.field
  std::size_t summarizeAbove = 16;  // lists with more values are summarised
};

enum class Change { Added, Removed, Changed };
const char* changeName(Change c);

struct FieldDiff {
  std::string name;
  Change change = Change::Changed;
  std::string oldValue, newValue;  // canonical text; "(default)" appended for a schema default
  // Long lists: counts instead of values.
  bool summarized = false;
  std::size_t oldCount = 0, newCount = 0, changedCount = 0;
  double maxDelta = 0;  // largest |a - b| over numeric items (same count only)
};

struct RecordDiff {
  Change change = Change::Changed;
  std::string tag;
  std::string key;       // identity, as people read it
  std::string path;      // node path (new side, or old side when removed)
  std::string oldPath;   // when a node kept its id but changed its path
  std::uint32_t oldLine = 0, newLine = 0;
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

// The result as JSON ({"same":..., "stat":{...}, "records":[...]}).
std::string diffToJson(const DiffResult& result);

}  // namespace rscene
