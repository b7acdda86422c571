// Raw rows of the schema table (schema_table.cpp).  Only schema.cpp reads
// these; everything else uses the parsed form in schema.hpp.
#pragma once
#include <cstddef>

namespace rscene {

// How a record kind behaves in a scene.
enum class Role {
  Singleton,  // one per scene; a repeat replaces the earlier one
  Plain,      // resources and other records that accumulate
  Node,       // scene-tree node with a path and an id
  Child,      // belongs to the parent record before it (parentTag)
};

namespace table {

struct KindRow {
  const char* tag;
  int rank;              // writer's section order
  Role role;
  const char* idPrefix;  // default id = prefix + path (nodes)
  const char* parentTag; // for children
  const char* positional;
  const char* keys;
};
struct LayoutRow {
  const char* tag;
  const char* positional;
};
struct EnumRow {
  const char* name;
  const char* values;  // "canon=alias,alias canon2 ..."; "..." = open
};

extern const KindRow kKinds[];
extern const std::size_t kKindCount;
extern const LayoutRow kAltLayouts[];
extern const std::size_t kAltLayoutCount;
extern const EnumRow kEnums[];
extern const std::size_t kEnumCount;

}  // namespace table
}  // namespace rscene
