// One world XML file's text as an Element tree, before template expansion:
// tinyxml2 parses, and a linear scan of the same text adds what tinyxml2
// does not keep (the column of each element's '<' and of each attribute
// name) and refuses what tinyxml2 would let through silently: DOCTYPE
// entity declarations (tinyxml2 does not expand them; an "&lol;" would
// stay in a value as text) and references to entities other than XML's
// five and numeric ones.
#pragma once
#include <string>
#include <string_view>

#include "core/codes.hpp"
#include "core/diagnostic.hpp"
#include "xml/xml_tree.hpp"

namespace rscene::xml {

// Codes of the XML front end (reading and expanding; RS8101-RS8109).
namespace code {
inline constexpr const char* kXmlRead = rs::RS8101;     // not well-formed, not <raisim>, unreadable, too large
inline constexpr const char* kXmlEntity = rs::RS8102;   // DOCTYPE entities, unknown &name;
inline constexpr const char* kXmlInclude = rs::RS8103;  // include: no file, unreadable, cycle, depth, place
inline constexpr const char* kXmlParam = rs::RS8104;    // @@NAME unset, cyclic, bad <params> entry
inline constexpr const char* kXmlExpr = rs::RS8105;     // {...} that cannot be evaluated
inline constexpr const char* kXmlArray = rs::RS8106;    // array attributes
inline constexpr const char* kXmlLimit = rs::RS8107;    // expansion past a LoadLimits bound
inline constexpr const char* kXmlExist = rs::RS8108;    // exist neither true nor false
inline constexpr const char* kXmlClass = rs::RS8109;    // object_class that cannot be used
}  // namespace code

// `value` with every "[THIS_DIR]" replaced by `thisDir`.
std::string replaceThisDir(std::string_view value, const std::string& thisDir);

// Parses `text` (the file `file`) into `root`.  Every attribute value has
// "[THIS_DIR]" replaced by `thisDir`.  Elements nested deeper than
// `maxDepth` are refused while scanning, before tinyxml2 recurses.  False
// with diagnostics on error; the top element must be <raisim>.
bool parseWorldSource(std::string_view text, const std::string& file, const std::string& thisDir, int maxDepth,
                      Element& root, Diagnostics& diagnostics);

}  // namespace rscene::xml
