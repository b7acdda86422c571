// Feeds arbitrary bytes to the loader.  Whatever loads must satisfy the two
// invariants of the canonical form (DESIGN.md): formatting is a fixed
// point, and the formatted text parses back to the same scene record for
// record.  A violation aborts with the input's first difference, so that
// libFuzzer saves the input as a crash artifact.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "core/io.hpp"
#include "core/loader.hpp"
#include "core/writer.hpp"

namespace {

[[noreturn]] void fail(const char* invariant, const std::string& detail) {
  std::fprintf(stderr, "fuzz_loader: invariant broken: %s\n%s\n", invariant, detail.c_str());
  std::abort();
}

// The first line where two texts differ, quoted from both.
std::string firstDifference(std::string_view a, std::string_view b) {
  std::size_t i = 0, line = 1, start = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) {
    if (a[i] == '\n') {
      ++line;
      start = i + 1;
    }
    ++i;
  }
  auto lineAt = [&](std::string_view s) {
    std::string_view rest = s.substr(std::min(start, s.size()));
    return std::string(rest.substr(0, std::min(rest.find('\n'), std::size_t{200})));
  };
  return "line " + std::to_string(line) + ":\n  fmt(x):      " + lineAt(a) + "\n  fmt(fmt(x)): " + lineAt(b);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rscene::LoadResult first = rscene::parse(std::string(reinterpret_cast<const char*>(data), size));
  if (!first.ok()) return 0;  // refused input: the loader's only duty was not to crash
  std::string once = rscene::canonicalText(first.document);
  rscene::LoadResult second = rscene::parse(once);
  if (!second.ok())
    fail("parse(fmt(x)) succeeds", rscene::firstError(second.diagnostics) + "\nfmt(x):\n" + once.substr(0, 2000));
  std::string twice = rscene::canonicalText(second.document);
  if (twice != once) fail("fmt(fmt(x)) == fmt(x)", firstDifference(once, twice));
  std::string why;
  if (!rscene::sameDocument(first.document, second.document, &why))
    fail("sameDocument(parse(x), parse(fmt(x)))", why);
  return 0;
}
