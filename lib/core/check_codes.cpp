// Every finding the validator (and the loader before it) can report: the
// code, its severity and one line of explanation.  --list-checks, the man
// page and the tests all read this one table.
#include <algorithm>

#include "core/check.hpp"

namespace rscene {
namespace {

constexpr Severity E = Severity::Error;
constexpr Severity W = Severity::Warning;

constexpr CheckInfo kChecks[] = {
    // RS1xxx syntax (RS1001..RS1010 come from the loader)
    {"RS1001", E, "missing raisim_engine_scene header"},
    {"RS1002", E, "unsupported rscene version (only 1 and 2 exist)"},
    {"RS1003", E, "invalid percent escape"},
    {"RS1004", E, "scene text contains a NUL byte"},
    {"RS1005", E, "invalid UTF-8"},
    {"RS1006", E, "control character in a token"},
    {"RS1007", E, "wrong number of positional fields for the record kind"},
    {"RS1008", E, "positional field after key=value fields"},
    {"RS1009", E, "key=value token without a key"},
    {"RS1010", E, "input too large"},
    {"RS1101", W, "key repeated in one record (the last one wins)"},
    // RS2xxx types
    {"RS2001", E, "value is not a number"},
    {"RS2002", E, "number is not finite (nan, inf or out of range)"},
    {"RS2003", E, "value is not an integer in range"},
    {"RS2004", E, "collision group or mask is not an unsigned 64-bit integer"},
    {"RS2005", E, "value is not a flag (true/false, 1/0, yes/no, on/off)"},
    {"RS2006", E, "unknown name for an enumeration"},
    {"RS2007", W, "name not known for an open enumeration (newer writers may add names)"},
    {"RS2008", E, "vector, quaternion or color with the wrong number of components"},
    {"RS2009", E, "number list with an empty entry or a trailing separator"},
    // RS3xxx names and references
    {"RS3001", W, "unknown record tag (kept and ignored)"},
    {"RS3002", W, "unknown key (kept and ignored)"},
    {"RS3003", E, "duplicate node path"},
    {"RS3004", E, "duplicate id (explicit or default)"},
    {"RS3005", W, "node path not rooted at /World"},
    {"RS3006", E, "parent (parentGroupId or parentId) names no node"},
    {"RS3007", W, "node parented to a non-group node inherits its transform"},
    {"RS3008", E, "material names no material record"},
    {"RS3009", W, "contact material named by no contact_material record"},
    {"RS3010", E, "articulated resource names no articulated_resource record"},
    {"RS3011", E, "terrain texture slot names no terrain_texture record"},
    {"RS3012", E, "body reference names no node"},
    {"RS3013", E, "terrain reference names no terrain_region"},
    {"RS3014", E, "node reference names no node of the right kind"},
    {"RS3015", E, "child record with no parent record before it"},
    {"RS3016", W, "repeated singleton record replaces the earlier one"},
    {"RS3017", E, "parent chain forms a cycle"},
    // RS4xxx sizes and values
    {"RS4001", E, "terrain sample count per axis outside 2..16384"},
    {"RS4002", E, "terrain has more than 64 Mi samples"},
    {"RS4003", E, "per-sample list length differs from the terrain's sample count"},
    {"RS4004", E, "instance list length is not a multiple of 10"},
    {"RS4005", E, "colorWeights count differs from the instance count"},
    {"RS4006", E, "vertexColors count differs from the terrain's sample count"},
    {"RS4007", E, "generalizedCoordinate and generalizedVelocity lengths disagree"},
    {"RS4008", E, "dynamic body without positive mass"},
    {"RS4009", E, "zero quaternion"},
    {"RS4010", W, "quaternion not of unit length (off by more than 1e-3)"},
    {"RS4011", E, "negative size, radius or length"},
    {"RS4012", E, "camera near plane not positive or not below the far plane"},
    {"RS4013", W, "field of view outside the range it is clamped to"},
    {"RS4014", E, "terrain size not positive"},
    // RS5xxx files (--check-files)
    {"RS5001", E, "asset file does not exist"},
    // RS6xxx what RaiSim 2.7.1 refuses (--profile raisim)
    {"RS6001", E, "record kind RaiSim does not load"},
    {"RS6002", E, "key repeated in one record"},
    {"RS6003", E, "version-1 asset_root other than . or an absolute path"},
    {"RS6004", E, "node parented to a non-group node while transforms are inherited"},
    {"RS6005", E, "terrain not sampled, hidden or not collidable"},
    {"RS6006", E, "terrain layer before its terrain"},
    {"RS6007", E, "enabled instanced visual that is a grass patch or a ground"},
    {"RS6008", E, "enabled wire with a negative length or body index"},
    {"RS6009", E, "name not known to RaiSim"},
};

}  // namespace

std::span<const CheckInfo> checkTable() { return kChecks; }

const CheckInfo* checkInfo(std::string_view code) {
  auto it = std::find_if(std::begin(kChecks), std::end(kChecks), [&](const CheckInfo& c) { return c.code == code; });
  return it == std::end(kChecks) ? nullptr : it;
}

}  // namespace rscene
