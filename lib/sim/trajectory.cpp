#include "sim/trajectory.hpp"

#include <nlohmann/json.hpp>

#include "core/text.hpp"

namespace rscene::sim {
namespace {

void csvField(std::string& out, const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) {
    out += s;
    return;
  }
  out += '"';
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
}

void numbers(std::string& out, std::initializer_list<double> values, char sep) {
  for (double v : values) {
    out += sep;
    appendNumber(out, v == 0 ? 0.0 : v);
  }
}

}  // namespace

std::string trajectoryHeader(TrajectoryFormat format) {
  if (format == TrajectoryFormat::Jsonl) return {};
  return "time,path,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
}

void appendTrajectory(std::string& out, TrajectoryFormat format, double time, const std::vector<BodyState>& states) {
  for (const BodyState& b : states) {
    const Eigen::Vector3d &p = b.position, &v = b.linearVelocity, &w = b.angularVelocity;
    const Eigen::Quaterniond& q = b.orientation;
    if (format == TrajectoryFormat::Csv) {
      appendNumber(out, time);
      out += ',';
      csvField(out, b.path);
      numbers(out, {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z()}, ',');
      out += '\n';
      continue;
    }
    out += "{\"time\":";
    appendNumber(out, time);
    out += ",\"path\":" + nlohmann::json(b.path).dump();
    auto vec = [&](const char* name, std::initializer_list<double> xs) {
      out += ",\"";
      out += name;
      out += "\":[";
      std::string inner;
      numbers(inner, xs, ',');
      out += inner.substr(1);
      out += ']';
    };
    vec("position", {p.x(), p.y(), p.z()});
    vec("quaternion", {q.w(), q.x(), q.y(), q.z()});
    vec("linearVelocity", {v.x(), v.y(), v.z()});
    vec("angularVelocity", {w.x(), w.y(), w.z()});
    out += "}\n";
  }
}

}  // namespace rscene::sim
