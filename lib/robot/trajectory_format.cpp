#include "robot/trajectory_format.hpp"

#include <nlohmann/json.hpp>
#include <unordered_map>

#include "core/text.hpp"
#include "robot/kinematics.hpp"

namespace rscene::robot {
namespace {

// The length of the valid UTF-8 sequence at text[i], 0 when there is none
// (no overlong forms, no surrogates, nothing past U+10FFFF).
std::size_t utf8Length(std::string_view text, std::size_t i) {
  auto byte = [&](std::size_t k) { return k < text.size() ? static_cast<unsigned char>(text[k]) : 0u; };
  auto cont = [&](std::size_t k) { return (byte(k) & 0xC0) == 0x80; };
  unsigned c = byte(i), c1 = byte(i + 1);
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) return cont(i + 1) ? 2 : 0;
  if (c >= 0xE0 && c <= 0xEF) {
    bool ok = cont(i + 1) && cont(i + 2) && !(c == 0xE0 && c1 < 0xA0) && !(c == 0xED && c1 >= 0xA0);
    return ok ? 3 : 0;
  }
  if (c >= 0xF0 && c <= 0xF4) {
    bool ok = cont(i + 1) && cont(i + 2) && cont(i + 3) && !(c == 0xF0 && c1 < 0x90) && !(c == 0xF4 && c1 >= 0x90);
    return ok ? 4 : 0;
  }
  return 0;
}

bool validUtf8(std::string_view text) {
  for (std::size_t i = 0, n = 0; i < text.size(); i += n)
    if ((n = utf8Length(text, i)) == 0) return false;
  return true;
}

// A JSON string for `text`; the copy only when it is not UTF-8 already.
std::string jsonString(const std::string& text) {
  return nlohmann::json(validUtf8(text) ? text : jsonSafeText(text)).dump();
}


void number(std::string& out, double v) { appendNumber(out, v == 0 ? 0.0 : v); }

void numbers(std::string& out, std::initializer_list<double> values, char sep) {
  for (double v : values) {
    out += sep;
    number(out, v);
  }
}

// One pose-and-velocity line (a body, or a robot's base) without its end.
void poseLine(std::string& out, TrajectoryFormat format, double time, const std::string& path,
              const Eigen::Vector3d& p, const Eigen::Quaterniond& q, const Eigen::Vector3d& v,
              const Eigen::Vector3d& w) {
  if (format == TrajectoryFormat::Csv) {
    number(out, time);
    out += ',';
    appendCsvField(out, path);
    numbers(out, {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z()}, ',');
    return;
  }
  out += "{\"time\":";
  number(out, time);
  out += ",\"path\":" + jsonString(path);
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
}

}  // namespace

std::string jsonSafeText(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    if (std::size_t n = utf8Length(text, i)) {
      out.append(text.substr(i, n));
      i += n;
    } else {
      out += "\xEF\xBF\xBD";  // U+FFFD
      ++i;
    }
  }
  return out;
}

void appendCsvField(std::string& out, std::string_view s) {
  if (s.find_first_of(",\"\n") == std::string_view::npos) {
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

bool splitCsv(const std::string& line, std::vector<CsvField>& out, std::uint32_t& bad) {
  out.clear();
  std::size_t i = 0;
  for (;;) {
    CsvField f;
    f.column = static_cast<std::uint32_t>(i + 1);
    if (i < line.size() && line[i] == '"') {
      ++i;
      for (;;) {
        if (i >= line.size()) {
          bad = f.column;
          return false;
        }
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            f.text += '"';
            i += 2;
            continue;
          }
          ++i;
          break;
        }
        f.text += line[i++];
      }
      if (i < line.size() && line[i] != ',') {
        bad = static_cast<std::uint32_t>(i + 1);
        return false;
      }
    } else {
      std::size_t end = line.find(',', i);
      if (end == std::string::npos) end = line.size();
      f.text = line.substr(i, end - i);
      i = end;
    }
    out.push_back(std::move(f));
    if (i >= line.size()) return true;
    ++i;  // the comma
  }
}

TrajectoryLimits TrajectoryLimits::forPoints(std::size_t points) {
  TrajectoryLimits l;
  l.maxPoints = points;
  l.maxLineBytes = (std::size_t{1} << 20) + kBytesPerPoint * std::min<std::size_t>(points, std::size_t{1} << 40);
  return l;
}

TrajectoryWriter::TrajectoryWriter(TrajectoryFormat format, const std::vector<RobotState>& robots) : format_(format) {
  std::unordered_map<std::string, int> index;
  auto column = [&](const std::string& name) {
    auto [it, added] = index.emplace(name, static_cast<int>(columns_.size()));
    if (added) columns_.push_back(name);
    return it->second;
  };
  for (const RobotState& r : robots) {
    const RobotInstance& in = *r.instance;
    std::vector<std::string> q = coordinateNames(*in.model, in.coordinates, false);
    std::vector<std::string> u = coordinateNames(*in.model, in.coordinates, true);
    qColumns_.emplace_back();
    uColumns_.emplace_back();
    for (std::size_t i = static_cast<std::size_t>(in.coordinates.baseCoordinates); i < q.size(); ++i)
      qColumns_.back().push_back(column(std::string(kJointPositionPrefix) + q[i]));
    for (std::size_t i = static_cast<std::size_t>(in.coordinates.baseVelocities); i < u.size(); ++i)
      uColumns_.back().push_back(column(std::string(kJointVelocityPrefix) + u[i]));
  }
}

std::string TrajectoryWriter::header() const {
  if (format_ == TrajectoryFormat::Jsonl) return {};
  std::string h;
  for (std::string_view c : kTrajectoryBodyColumns) {
    if (!h.empty()) h += ',';
    h += c;
  }
  for (const std::string& c : columns_) {
    h += ',';
    appendCsvField(h, c);
  }
  h += ',';
  h += kTrajectoryPointsColumn;
  return h + '\n';
}

void TrajectoryWriter::append(std::string& out, double time, const std::vector<BodyState>& bodies,
                        const std::vector<RobotState>& robots, const std::vector<ParticleState>& particles) const {
  const std::string empty(columns_.size() + 1, ',');  // the joint columns and points
  for (const BodyState& b : bodies) {
    poseLine(out, format_, time, b.path, b.position, b.orientation, b.linearVelocity, b.angularVelocity);
    out += format_ == TrajectoryFormat::Csv ? empty + '\n' : "}\n";
  }
  std::vector<const double*> cells(columns_.size());
  for (std::size_t k = 0; k < robots.size() && k < qColumns_.size(); ++k) {
    const RobotState& r = robots[k];
    const RobotInstance& in = *r.instance;
    poseLine(out, format_, time, r.path, r.base.position, r.base.orientation, r.baseLinearVelocity,
             r.baseAngularVelocity);
    const int q0 = in.coordinates.baseCoordinates, u0 = in.coordinates.baseVelocities;
    if (format_ == TrajectoryFormat::Csv) {
      std::fill(cells.begin(), cells.end(), nullptr);
      for (std::size_t i = 0; i < qColumns_[k].size(); ++i)
        cells[static_cast<std::size_t>(qColumns_[k][i])] = &r.q[q0 + static_cast<Eigen::Index>(i)];
      for (std::size_t i = 0; i < uColumns_[k].size(); ++i)
        cells[static_cast<std::size_t>(uColumns_[k][i])] = &r.u[u0 + static_cast<Eigen::Index>(i)];
      for (const double* c : cells) {
        out += ',';
        if (c) number(out, *c);
      }
      out += ",\n";
      continue;
    }
    auto object = [&](const char* name, const std::vector<int>& cols, const Eigen::VectorXd& v, int first) {
      out += ",\"";
      out += name;
      out += "\":{";
      for (std::size_t i = 0; i < cols.size(); ++i) {
        if (i) out += ',';
        out += jsonString(columns_[static_cast<std::size_t>(cols[i])].substr(2)) + ':';
        number(out, v[first + static_cast<Eigen::Index>(i)]);
      }
      out += '}';
    };
    object("jointPositions", qColumns_[k], r.q, q0);
    object("jointVelocities", uColumns_[k], r.u, u0);
    out += "}\n";
  }
  for (const ParticleState& p : particles) {
    const bool csv = format_ == TrajectoryFormat::Csv;
    if (csv) {
      number(out, time);
      out += ',';
      appendCsvField(out, p.path);
      out += std::string(kTrajectoryBodyColumns.size() - 2 + columns_.size() + 1, ',');
    } else {
      out += "{\"time\":";
      number(out, time);
      out += ",\"path\":" + jsonString(p.path) + ",\"points\":[";
    }
    for (std::size_t i = 0; i < p.points->size(); ++i) {
      const Eigen::Vector3d& x = (*p.points)[i];
      if (i) out += csv ? ';' : ',';
      if (!csv) out += '[';
      for (int k = 0; k < 3; ++k) {
        if (k) out += csv ? ' ' : ',';
        number(out, x[k]);
      }
      if (!csv) out += ']';
    }
    out += csv ? "\n" : "]}\n";
  }
}

}  // namespace rscene::robot
