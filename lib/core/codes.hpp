// The diagnostic codes as constants, generated from the one table
// (core/code_table.inc): rs::RS5001 is "RS5001".  Every layer's named
// constants (scene_code::kMissingFile ...) are defined from these, so a
// code that is not in the registry is a compile error, not a test failure.
#pragma once

namespace rscene::rs {

#define RSCENE_CODE(code, severity, layer, tools, summary) inline constexpr const char* code = #code;
#include "core/code_table.inc"
#undef RSCENE_CODE

}  // namespace rscene::rs
