// rscene-sim --pd-gains: the text of the flag read into PdGains.
#include <cmath>
#include <optional>
#include <set>

#include "core/text.hpp"
#include "sim/world.hpp"

namespace rscene::sim {
namespace {

bool gain(std::string_view text, double& out) {
  std::optional<double> v = parseNumber(text);
  if (!v || !std::isfinite(*v) || *v < 0) return false;
  out = *v;
  return true;
}

}  // namespace

bool parsePdGains(const std::vector<std::string>& specs, PdGains& out, std::string& error) {
  out = PdGains{};
  for (const std::string& spec : specs) {
    std::string_view text = spec, name;
    bool named = false;
    if (std::size_t eq = text.find('='); eq != std::string_view::npos) {
      named = true;
      name = text.substr(0, eq);
      text = text.substr(eq + 1);
    }
    std::size_t comma = text.find(',');
    double kp = 0, kd = 0;
    if (comma == std::string_view::npos || !gain(text.substr(0, comma), kp) || !gain(text.substr(comma + 1), kd) ||
        (named && name.empty())) {
      error = "--pd-gains '" + spec + "': expected KP,KD or JOINT=KP,KD with finite gains >= 0";
      return false;
    }
    out.enabled = true;
    if (name.empty()) {
      out.kp = kp;
      out.kd = kd;
    } else {
      out.joints[std::string(name)] = {kp, kd};
    }
  }
  return true;
}

std::vector<std::string> unknownPdJoints(const PdGains& pd, const std::vector<robot::RobotInstance>& robots) {
  std::set<std::string> known;
  for (const robot::RobotInstance& r : robots)
    if (r.model)
      for (const robot::Joint& j : r.model->joints)
        if (j.type != robot::JointType::Fixed) known.insert(j.name);
  std::vector<std::string> unknown;
  for (const auto& [name, gains] : pd.joints)
    if (!known.count(name)) unknown.push_back(name);
  return unknown;
}

}  // namespace rscene::sim
