// Feeds arbitrary bytes to rscene-from-json's reader (issue 10: every entry
// point that takes a scene into memory has a fuzz target).  Beyond not
// crashing, leaking or running past libFuzzer's time and memory limits,
// whatever the reader accepts must be a scene the rest of the toolchain
// stands behind:
// - its canonical text loads with the .rscene loader, and
// - the JSON written from that scene reads back to the same canonical text
//   (the lossless round trip rscene-to-json | rscene-from-json promises).
// A refusal must say where: one error with a line and column inside the input.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "core/io.hpp"
#include "core/json.hpp"
#include "core/loader.hpp"
#include "core/writer.hpp"

namespace {

[[noreturn]] void fail(const char* invariant, const std::string& detail) {
  std::fprintf(stderr, "fuzz_from_json: invariant broken: %s\n%s\n", invariant, detail.substr(0, 4000).c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view json(reinterpret_cast<const char*>(data), size);
  rscene::JsonLoadResult read = rscene::fromJson(json);
  if (!read.ok()) {
    if (read.diagnostics.empty()) fail("a refusal carries a diagnostic", "");
    const rscene::Diagnostic& d = read.diagnostics.front();
    std::size_t lines = 1;
    for (char c : json) lines += c == '\n';
    if (d.line == 0 || d.line > lines || d.column == 0)
      fail("a refusal points into the input", d.message + " at " + std::to_string(d.line) + ":" +
                                                  std::to_string(d.column));
    return 0;
  }
  std::string text = rscene::canonicalText(read.document);
  rscene::LoadResult loaded = rscene::parse(text);
  if (!loaded.ok()) fail("the canonical text of what from-json accepts loads", rscene::firstError(loaded.diagnostics) + "\n" + text);
  rscene::JsonLoadResult again = rscene::fromJson(rscene::toJson(loaded.document));
  if (!again.ok()) fail("to-json of the scene reads back", again.diagnostics.front().message);
  std::string back = rscene::canonicalText(again.document);
  if (back != text) fail("from-json(to-json(scene)) == scene", "first:\n" + text + "\nthen:\n" + back);
  return 0;
}
