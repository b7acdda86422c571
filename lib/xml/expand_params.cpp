#include "xml/expand_params.hpp"

#include <algorithm>
#include <cctype>

namespace rscene::xml {
namespace {
bool isNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
}  // namespace

bool isParameterName(std::string_view name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), isNameChar);
}

void Parameters::setFromCommandLine(const std::string& name, const std::string& value) {
  globals_[name] = value;
  longestName_ = std::max(longestName_, name.size());
}

bool Parameters::define(const std::string& name, const std::string& value) {
  if (globals_.count(name)) return false;
  globals_[name] = value;
  longestName_ = std::max(longestName_, name.size());
  return true;
}

void Parameters::pushLoop(std::string name, std::string value) {
  longestName_ = std::max(longestName_, name.size());
  loops_.emplace_back(std::move(name), std::move(value));
}

const std::string* Parameters::lookup(std::string_view name, bool* isLoop) {
  for (auto it = loops_.rbegin(); it != loops_.rend(); ++it)
    if (it->first == name) {
      *isLoop = true;
      return &it->second;
    }
  auto g = globals_.find(name);
  if (g == globals_.end()) return nullptr;
  *isLoop = false;
  return &g->second;
}

bool Parameters::substitute(std::string_view in, std::string& out, std::string* error, std::size_t maxBytes) {
  out.clear();
  if (in.find("@@") == std::string_view::npos) {
    out.assign(in);
    return true;
  }
  std::vector<std::string> chain;
  steps_ = 0;
  return expandInto(in, out, chain, error, maxBytes);
}

std::vector<std::string> Parameters::unsetNames(std::string_view in, const std::vector<std::string>& loopNames) const {
  std::vector<std::string> out;
  for (std::size_t at = in.find("@@"); at != std::string_view::npos; at = in.find("@@", at + 2)) {
    std::size_t start = at + 2, end = start;
    while (end < in.size() && isNameChar(in[end])) ++end;
    std::string_view run = in.substr(start, end - start);
    if (run.empty()) continue;  // substitute() says what is wrong
    bool set = false;
    for (std::size_t len = std::min(run.size(), longestName_); len > 0 && !set; --len)
      set = globals_.find(run.substr(0, len)) != globals_.end();
    for (const std::string& loop : loopNames) set = set || run.substr(0, loop.size()) == loop;
    std::string name(run.substr(0, 64));
    if (!set && std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
  }
  return out;
}

bool Parameters::expandInto(std::string_view in, std::string& out, std::vector<std::string>& chain,
                            std::string* error, std::size_t maxBytes) {
  std::size_t i = 0;
  while (i < in.size()) {
    std::size_t at = in.find("@@", i);
    if (at == std::string_view::npos) at = in.size();
    out.append(in.substr(i, at - i));
    if (out.size() > maxBytes) {
      if (error) *error = "value longer than " + std::to_string(maxBytes) + " bytes after substituting parameters";
      return false;
    }
    if (at == in.size()) break;
    std::size_t start = at + 2, end = start;
    while (end < in.size() && isNameChar(in[end])) ++end;
    if (end == start) {
      if (error) *error = "'@@' without a parameter name";
      return false;
    }
    // Longest set name first; no name is longer than longestName_, so a
    // long run of letters costs at most that many lookups.
    const std::string* value = nullptr;
    bool isLoop = false;
    std::size_t len = std::min(end - start, longestName_);
    for (; len > 0; --len)
      if ((value = lookup(in.substr(start, len), &isLoop))) break;
    if (!value) {
      std::string name(in.substr(start, std::min<std::size_t>(end - start, 64)));
      if (error)
        *error = "@@" + name + " is not set: define it in <params> or give --param " + name + "=VALUE";
      return false;
    }
    std::string name(in.substr(start, len));
    i = start + len;
    // Values that are all references to references ("@@b@@b" down to an
    // empty one) grow no output but double the work per level.
    if (++steps_ > kMaxSubstitutions) {
      if (error) *error = "more than " + std::to_string(kMaxSubstitutions) + " parameter substitutions in one value";
      return false;
    }
    if (isLoop) {
      out.append(*value);
      continue;
    }
    if (std::find(chain.begin(), chain.end(), name) != chain.end()) {
      std::string path;
      for (const std::string& n : chain) path += n + " -> ";
      if (error) *error = "@@" + name + " is defined from itself (" + path + name + ")";
      return false;
    }
    if (static_cast<int>(chain.size()) >= kMaxParameterNesting) {
      if (error)
        *error = "parameters refer to parameters more than " + std::to_string(kMaxParameterNesting) + " deep";
      return false;
    }
    chain.push_back(name);
    if (!expandInto(*value, out, chain, error, maxBytes)) return false;
    chain.pop_back();
  }
  return true;
}

}  // namespace rscene::xml
