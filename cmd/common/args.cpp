// Command-line parsing every tool shares: CLI11's errors in our message
// style, "did you mean" for a mistyped option, and validators whose
// messages say what a value should look like (CLI11's own print the range
// 0 to DBL_MAX in 300 digits).
#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <iostream>

#include "common/cli.hpp"
#include "core/suggest.hpp"
#include "core/text.hpp"

namespace rscene::cli {
namespace {

// The long options of `app` without their dashes (help and version too).
std::vector<std::string> longOptionNames(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options())
    for (const std::string& l : o->get_lnames()) names.push_back(l);
  return names;
}

// "unknown option '--chek'; did you mean '--check'?" for the first
// left-over argument that looks like an option; empty when none does
// (extra operands keep CLI11's message).
std::string unknownOptionMessage(const CLI::App& app) {
  for (const std::string& arg : app.remaining()) {
    if (arg.size() < 2 || arg[0] != '-') continue;
    const std::string name = arg.substr(0, arg.find('='));
    std::string msg = "unknown option '" + name + "'";
    // "--chek" and "-chek" are both a long option mistyped; "-x" is only a
    // letter and suggests nothing.
    std::string word = name.substr(name[1] == '-' ? 2 : 1);
    if (name[1] != '-' && word.size() < 2) return msg;
    const std::vector<std::string> names = longOptionNames(app);
    std::vector<std::string_view> candidates(names.begin(), names.end());
    std::string best = closestName(word, candidates);
    if (best.empty() && name[1] != '-')  // -check: one dash short
      for (const std::string& n : names)
        if (n == word) best = n;
    if (!best.empty()) msg += "; did you mean '--" + best + "'?";
    return msg;
  }
  return {};
}

std::string lowerFirst(std::string msg) {
  // CLI11 starts its messages with a capital; ours are lower-case (but
  // not an acronym's first letter).
  if (!msg.empty() && msg[0] >= 'A' && msg[0] <= 'Z' && !(msg.size() > 1 && msg[1] >= 'A' && msg[1] <= 'Z'))
    msg[0] = static_cast<char>(msg[0] - 'A' + 'a');
  return msg;
}

// A whole number within [min, LLONG_MAX], written as plain digits.
std::string checkCount(const std::string& s, long long min) {
  long long v = 0;
  const char* end = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), end, v);
  if (s.empty() || ec != std::errc() || p != end || v < min)
    return "expected a whole number >= " + std::to_string(min) + ", not '" + s + "'";
  return {};
}

}  // namespace

CLI::Validator seconds() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        std::optional<double> v = parseNumber(s);
        if (!v || !(*v >= 0)) return "expected seconds as a plain number >= 0 (e.g. 2 or 0.5), not '" + s + "'";
        return {};
      },
      "", "seconds");
}

CLI::Validator nonNegative() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        std::optional<double> v = parseNumber(s);
        if (!v || !(*v >= 0) || !std::isfinite(*v)) return "expected a plain number >= 0 (e.g. 0.001 or 1e-6), not '" + s + "'";
        return {};
      },
      "", "nonNegative");
}

CLI::Validator fraction() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        std::optional<double> v = parseNumber(s);
        if (!v || !(*v >= 0 && *v <= 1)) return "expected a fraction from 0 to 1 (e.g. 0.01), not '" + s + "'";
        return {};
      },
      "", "fraction");
}

CLI::Validator count(long long min) {
  return CLI::Validator([min](std::string& s) { return checkCount(s, min); }, "", "count");
}

CLI::Validator range(long long min, long long max) {
  return CLI::Range(min, max).description("");
}

int parseArgs(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return kSuccess;
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << '\n';
    return kSuccess;
  } catch (const CLI::ParseError& e) {
    std::string msg = dynamic_cast<const CLI::ExtrasError*>(&e) ? unknownOptionMessage(app) : std::string();
    error(msg.empty() ? lowerFirst(e.what()) : msg);
    std::cerr << "Try '" << toolName() << " --help' for more information.\n";
    return kTrouble;
  }
  return -1;
}

}  // namespace rscene::cli
