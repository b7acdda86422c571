// Helpers shared by the core unit tests.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "core/io.hpp"
#include "core/loader.hpp"
#include "core/writer.hpp"

namespace rscene::test {

inline LoadResult load(std::string text) { return parse(std::move(text)); }

// Canonical text of `text`; fails the test if it does not load.
inline std::string fmt(const std::string& text) {
  LoadResult r = parse(text);
  EXPECT_TRUE(r.ok()) << (r.diagnostics.empty() ? "" : r.diagnostics[0].message);
  return canonicalText(r.document);
}

inline std::string firstCode(const LoadResult& r) { return r.diagnostics.empty() ? "" : r.diagnostics[0].code; }

inline std::string readAll(const std::filesystem::path& p) {
  std::string text, err;
  EXPECT_TRUE(readFile(p.string(), text, &err)) << p << ": " << err;
  return text;
}

// Every *.rscene under `dir` (sorted), or none when it does not exist.
inline std::vector<std::filesystem::path> scenesIn(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return out;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".rscene") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace rscene::test
