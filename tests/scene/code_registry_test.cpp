// One registry of diagnostic codes (core/code_table.inc): every code the
// sources emit is in it, every code the README and the man pages quote
// exists, and rscene-validate(1) lists exactly the registry.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "core/check.hpp"

namespace rscene {
namespace {

namespace fs = std::filesystem;
const fs::path kRoot = RSCENE_SOURCE_DIR;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Every RSnnnn in `text`, with the first line it is on.
std::map<std::string, int> quotedCodes(const std::string& text) {
  std::map<std::string, int> out;
  static const std::regex code("RS[0-9]{4}");
  int line = 1;
  std::size_t lineStart = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), code); it != std::sregex_iterator(); ++it) {
    auto at = static_cast<std::size_t>(it->position());
    for (; lineStart < at; ++lineStart) line += text[lineStart] == '\n';
    out.emplace(it->str(), line);
  }
  return out;
}

TEST(CodeRegistry, CodesAreUniqueAndInOrder) {
  std::string last;
  for (const CheckInfo& c : checkTable()) {
    EXPECT_LT(last, std::string(c.code)) << c.code;
    EXPECT_FALSE(c.tools.empty()) << c.code;
    EXPECT_FALSE(c.summary.empty()) << c.code;
    last = c.code;
  }
}

TEST(CodeRegistry, EveryCodeTheSourcesEmitIsRegistered) {
  std::size_t files = 0;
  for (const char* dir : {"lib", "cmd"})
    for (const auto& e : fs::recursive_directory_iterator(kRoot / dir)) {
      std::string ext = e.path().extension().string();
      if (ext != ".cpp" && ext != ".hpp") continue;
      ++files;
      for (const auto& [code, line] : quotedCodes(slurp(e.path())))
        EXPECT_NE(checkInfo(code), nullptr) << e.path().string() << ":" << line << ": " << code << " is not registered";
    }
  EXPECT_GT(files, 50u);
}

TEST(CodeRegistry, DocumentsQuoteOnlyCodesThatExist) {
  std::vector<fs::path> docs{kRoot / "README.md"};
  for (const auto& e : fs::directory_iterator(kRoot / "man")) docs.push_back(e.path());
  for (const fs::path& doc : docs) {
    for (const auto& [code, line] : quotedCodes(slurp(doc))) {
      if (code == "RS0000") continue;  // mdoc's `.Bl -tag -width RS0000`, a width, not a code
      EXPECT_NE(checkInfo(code), nullptr) << doc.string() << ":" << line << ": " << code << " does not exist";
    }
  }
}

TEST(CodeRegistry, ValidateManPageListsTheRegistry) {
  // `.It Sy RS1001 Pq error` items of rscene-validate(1)'s CHECKS section.
  std::string man = slurp(kRoot / "man/rscene-validate.1");
  static const std::regex item(R"(\.It Sy (RS[0-9]{4}) Pq (error|warning)\n([^\n]*))");
  std::vector<std::string> listed, registry;
  for (auto it = std::sregex_iterator(man.begin(), man.end(), item); it != std::sregex_iterator(); ++it)
    listed.push_back((*it)[1].str() + " " + (*it)[2].str() + " " + (*it)[3].str());
  for (const CheckInfo& c : checkTable())
    registry.push_back(std::string(c.code) + (c.severity == Severity::Error ? " error " : " warning ") +
                       std::string(c.tools) + ": " + std::string(c.summary));
  EXPECT_EQ(listed, registry) << "regenerate with scripts/man-checks.sh";
}

}  // namespace
}  // namespace rscene
