// Which record of one scene is "the same" record in another.
//
//   singletons          by tag
//   nodes               by tag and id (explicit, or the default id of
//                       compat-notes.md), else by tag and path
//   material            by id, else name
//   contact_material    by the unordered (materialA, materialB) pair
//   terrain_texture     by slot
//   asset               by id, else label
//   articulated_resource, prefab_override (path + property)
//   children            by their parent's identity plus their own key:
//                       splat layer slot, foliage layer id or name, IK
//                       frame, compound child position among its siblings
//   unknown tags        by their whole text
//
// A key that occurs twice in one scene gets `#2`, `#3`, ... in file order.
#pragma once
#include <string>
#include <vector>

#include "core/document.hpp"

namespace rscene {

struct IdentityRule {
  const char* tag;
  const char* fields;  // space-separated; `a|b` = a, or b when a is empty
  bool unordered = false;  // the fields form a set (contact pairs)
};
// The rules for kinds that are neither singletons nor nodes.  Field names
// are the schema table's; a unit test checks that each one exists there.
const std::vector<IdentityRule>& identityRules();

// One key per record of `doc` (records[0], the header, included).
std::vector<std::string> identityKeys(const Document& doc);

// How people read a child record's identity: its parent's path and its
// place among its siblings, `/World/Cart[1]` (0-based), or its own key,
// `/World/Terrain[slot=2]`.  `key` is the record's from identityKeys().
std::string childPath(const Document& doc, const Record& r, std::string_view key);

// Text of field `name` of `r`: a width-1 positional field or a key, decoded.
std::string fieldText(const Document& doc, const Record& r, std::string_view name);

}  // namespace rscene
