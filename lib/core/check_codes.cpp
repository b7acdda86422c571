// The registry of every diagnostic code any tool emits, built from the one
// table core/code_table.inc.  --list-checks, the man pages and the tests
// read it; tests/scene/code_registry_test.cpp fails when lib/ or cmd/ emits a
// code that is not here, or when README.md or a man page quotes one that
// does not exist.
#include <algorithm>

#include "core/check.hpp"

namespace rscene {
namespace {

constexpr Severity E = Severity::Error;
constexpr Severity W = Severity::Warning;
constexpr CheckLayer Core = CheckLayer::Core, Scene = CheckLayer::Scene, Sim = CheckLayer::Sim,
                     Json = CheckLayer::Json, Render = CheckLayer::Render, Robot = CheckLayer::Robot,
                     Xml = CheckLayer::Xml;
// Who reports a code: the validator alone, or also sim and render, whose
// scene model (lib/scene/reader.cpp) reads values with the validator's codes.
// The loader's codes (RS1001-RS1010) stop every tool that reads a scene.
constexpr std::string_view V = "validate", VSR = "validate sim render", All = "every tool";

constexpr CheckInfo kChecks[] = {
#define RSCENE_CODE(code, severity, layer, tools, summary) {#code, severity, layer, tools, summary},
#include "core/code_table.inc"
#undef RSCENE_CODE

};

}  // namespace

std::span<const CheckInfo> checkTable() { return kChecks; }

const CheckInfo* checkInfo(std::string_view code) {
  auto it = std::find_if(std::begin(kChecks), std::end(kChecks), [&](const CheckInfo& c) { return c.code == code; });
  return it == std::end(kChecks) ? nullptr : it;
}

}  // namespace rscene
