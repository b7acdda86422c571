// Which record of one scene is "the same" record in another.
//
//   singletons          by tag
//   nodes               by tag and id (explicit, or the default id of
//                       compat-notes.md), else by tag and path; between
//                       two scenes (matchedIdentityKeys), a node left
//                       unmatched with an explicit id on one side and none
//                       on the other, of the same tag and path, is the same
//                       node (rscene-to-xml and back drops ids)
//   material            by id, else name
//   contact_material    by the unordered (materialA, materialB) pair
//   terrain_texture     by slot
//   asset               by id, else label
//   articulated_resource by id, else name
//   prefab_override     by path + property
//   children            by their parent's identity plus their own key:
//                       splat layer slot, foliage layer id or name, IK
//                       frame, compound child position among its siblings
//   unknown tags        by their whole text
//
// A key that occurs twice in one scene gets `#2`, `#3`, ... in file order.
// With ids ignored (rscene-diff --ignore id, or TAG.id), nodes of those
// kinds are keyed by tag and path only, and `id|name` rules by name.
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

struct IdentityOptions {
  // Kinds whose ids take no part in identity; "*" stands for every kind.
  std::vector<std::string> ignoreIdTags;
  bool ignoresId(std::string_view tag) const;
};

// One key per record of `doc` (records[0], the header, included).
std::vector<std::string> identityKeys(const Document& doc, const IdentityOptions& options = {});

// Keys of both sides of a diff: identityKeys() of each, and then a node
// that found no partner, with an explicit `id=` on one side and none on the
// other, takes the key of the node of the same tag and path on the other
// side that found none either (in file order when a path repeats); its
// children follow it.  Ids on both sides still decide alone.
struct SideKeys {
  std::vector<std::string> oldKeys, newKeys;
};
SideKeys matchedIdentityKeys(const Document& oldDoc, const Document& newDoc, const IdentityOptions& options = {});

// How people read a child record's identity: its parent's path and its
// place among its siblings, `/World/Cart[1]` (0-based), or its own key,
// `/World/Terrain[slot=2]`.  `key` is the record's from identityKeys().
std::string childPath(const Document& doc, const Record& r, std::string_view key,
                      const IdentityOptions& options = {});

// Text of field `name` of `r`: a width-1 positional field or a key, decoded.
std::string fieldText(const Document& doc, const Record& r, std::string_view name);

}  // namespace rscene
