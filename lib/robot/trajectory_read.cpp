#include "robot/trajectory_read.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "core/text.hpp"

namespace rscene::robot {
namespace {


bool finiteBounded(double v) { return std::isfinite(v) && std::fabs(v) <= kMaxTrajectoryValue; }


// The column of `"key"` in a JSON line, for messages (1 when absent).
std::uint32_t keyColumn(const std::string& line, const char* key) {
  std::size_t at = line.find('"' + std::string(key) + '"');
  return at == std::string::npos ? 1 : static_cast<std::uint32_t>(at + 1);
}

// The column of the `nth` (from 0) `"key"` followed by ':' in a JSON line
// (a key, not a string value); 1 when not found (a key written with escapes).
std::uint32_t nthKeyColumn(const std::string& line, const std::string& key, int nth) {
  std::string quoted = '"' + key + '"';
  for (std::size_t at = line.find(quoted); at != std::string::npos; at = line.find(quoted, at + 1)) {
    std::size_t after = line.find_first_not_of(" \t", at + quoted.size());
    if (after == std::string::npos || line[after] != ':') continue;
    if (nth-- == 0) return static_cast<std::uint32_t>(at + 1);
  }
  return 1;
}

// nlohmann's parse error without its "[json.exception...] parse error at
// line 1, column N: " prefix (the diagnostic gives the column).
std::string parseErrorReason(const std::string& what) {
  std::size_t at = what.find("syntax error while parsing ");
  return at == std::string::npos ? "malformed JSON" : "malformed JSON: " + what.substr(at + 27);
}

// The column of element `index` (from 0) of the array that is the value of
// the top-level key `key` (for messages about one point of "points"); the
// key's column when it cannot be told.
std::uint32_t elementColumn(const std::string& line, const char* key, std::size_t index) {
  std::uint32_t keyAt = nthKeyColumn(line, key, 0);
  std::size_t i = line.find('[', keyAt);
  if (i == std::string::npos) return keyAt;
  int depth = 0;
  std::size_t element = 0;
  bool atStart = true;  // the next non-blank byte opens an element
  for (++i; i < line.size(); ++i) {
    char c = line[i];
    if (c == ' ' || c == '\t') continue;
    if (atStart && depth == 0) {
      if (c == ']') break;
      if (element == index) return static_cast<std::uint32_t>(i + 1);
      atStart = false;
    }
    if (c == '"') {  // a string: skip it, escapes included
      for (++i; i < line.size() && line[i] != '"'; ++i)
        if (line[i] == '\\') ++i;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      if (depth-- == 0) break;
    } else if (c == ',' && depth == 0) {
      ++element;
      atStart = true;
    }
  }
  return keyAt;
}

// The top-level "points" array of a particle line, gathered while it is
// parsed: each [x,y,z] becomes a point and leaves the JSON tree at once,
// so a line of many points costs 24 bytes each, and counting stops (an
// exception out of the parse) at the first bad point or past `max`.
struct PointSink {
  std::size_t max = 0;
  std::vector<Eigen::Vector3d> points;
  std::size_t badIndex = 0;  // with `bad`: which element, from 0
  std::string bad;           // why the parse stopped at a point; empty: it did not
};
struct StopAtPoint {};

// A parse that records the first key an object repeats: nlohmann keeps
// one of the values silently, which would hide a file's mistake.
struct JsonLine {
  nlohmann::json value;
  std::string duplicateKey;  // empty: none
  int duplicateOccurrence = 0;  // of that key name in the line, from 0
  std::size_t errorByte = 0;    // parse error: 1-based byte, else 0
  std::string error;
};

JsonLine parseJsonLine(const std::string& text, PointSink& sink) {
  JsonLine out;
  std::vector<std::vector<std::string>> open;  // keys of each object being read
  std::map<std::string, int> seen;              // key name -> times read so far, any object
  std::vector<char> nesting;                    // 'o' object, 'a' array, outermost first
  std::string topKey;                           // the key of the outermost object being read
  std::size_t pointsDepth = 0;                  // nesting size inside the "points" array; 0: not in it
  // One element of "points" ended: keep it as a point, never in the tree.
  auto point = [&](const nlohmann::json& v) {
    std::size_t index = sink.points.size();
    auto stop = [&](std::string why) {
      sink.badIndex = index;
      sink.bad = std::move(why);
      throw StopAtPoint{};
    };
    if (index >= sink.max)
      stop("more than " + std::to_string(sink.max) + " points (the scene's largest deformable or granular record has " +
           std::to_string(sink.max) + ")");
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
      stop("point " + std::to_string(index) + " is not an [x,y,z] triple of numbers");
    Eigen::Vector3d p(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
    if (!finiteBounded(p.x()) || !finiteBounded(p.y()) || !finiteBounded(p.z()))
      stop("point " + std::to_string(index) + " out of range (|value| at most 1e12)");
    sink.points.push_back(p);
  };
  auto callback = [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    if (event == E::object_start || event == E::array_start) {
      if (event == E::array_start && nesting.size() == 1 && nesting[0] == 'o' && topKey == "points")
        pointsDepth = 2;
      nesting.push_back(event == E::object_start ? 'o' : 'a');
    }
    if (event == E::object_end || event == E::array_end) {
      if (!nesting.empty()) nesting.pop_back();
      if (pointsDepth && nesting.size() == pointsDepth) {  // an element of "points" closed
        point(parsed);
        if (event == E::object_end && !open.empty()) open.pop_back();
        return false;
      }
      if (pointsDepth && nesting.size() < pointsDepth) pointsDepth = 0;  // "points" itself closed
    }
    if (event == E::value && pointsDepth && nesting.size() == pointsDepth) {  // a bare number in "points"
      point(parsed);
      return false;
    }
    if (event == E::key && nesting.size() == 1 && parsed.is_string()) topKey = parsed.get<std::string>();
    if (event == E::object_start) open.emplace_back();
    if (event == E::object_end && !open.empty()) open.pop_back();
    if (event == E::key && parsed.is_string() && !open.empty()) {
      const std::string& key = parsed.get_ref<const std::string&>();
      int occurrence = seen[key]++;
      std::vector<std::string>& keys = open.back();
      if (out.duplicateKey.empty() && std::find(keys.begin(), keys.end(), key) != keys.end()) {
        out.duplicateKey = key;
        out.duplicateOccurrence = occurrence;
      }
      keys.push_back(key);
    }
    return true;
  };
  try {
    out.value = nlohmann::json::parse(text, callback, true);
  } catch (const StopAtPoint&) {
    // sink.bad says why; the caller reports it at the point.
  } catch (const nlohmann::json::parse_error& e) {
    out.errorByte = e.byte == 0 ? 1 : e.byte;
    out.error = parseErrorReason(e.what());
    // nlohmann names the last byte read: for a string where none belongs,
    // the caret goes to its opening quote instead of its closing one.
    if (out.error.find("unexpected string literal") != std::string::npos && out.errorByte <= text.size() &&
        text[out.errorByte - 1] == '"') {
      for (std::size_t i = out.errorByte - 1; i-- > 0;)
        if (text[i] == '"' && (i == 0 || text[i - 1] != '\\')) {
          out.errorByte = i + 1;
          break;
        }
    }
  } catch (const std::exception& e) {
    out.errorByte = 1;
    out.error = std::string("malformed JSON: ") + e.what();
  }
  return out;
}

}  // namespace

TrajectoryReader::TrajectoryReader(std::istream& in, std::string file, TrajectoryLimits limits)
    : in_(in), file_(std::move(file)), limits_(limits) {}

TrajectoryReader::~TrajectoryReader() = default;

bool TrajectoryReader::fail(Diagnostics& d, std::uint32_t column, std::string message) {
  Diagnostic x;
  x.code = code::kTrajectorySyntax;
  x.file = file_;
  x.line = lineNumber_;
  x.column = column;
  x.message = std::move(message);
  d.push_back(std::move(x));
  failed_ = true;
  return false;
}

// Reads one line without its end (LF or CRLF) into `out`, never holding
// more than maxLineBytes of it.  False at the end of the input (or on an
// over-long line: failed_ then set).
bool TrajectoryReader::readLine(std::string& out, Diagnostics& d) {
  out.clear();
  lineNumber_ += continuedLines_;  // the lines the last record went on over
  continuedLines_ = 0;
  std::streambuf* sb = in_.rdbuf();
  if (!sb) return false;
  bool any = false, quoted = false;
  std::uint32_t continued = 0;
  for (;;) {
    int c = 0;
    // libstdc++'s filebuf throws on a read error (a directory, EIO): an
    // error at this line, never an escaping exception.
    try {
      c = sb->sbumpc();
    } catch (const std::exception& e) {
      ++lineNumber_;
      return fail(d, 0, std::string("cannot read the trajectory: ") + e.what());
    }
    if (c == std::char_traits<char>::eof()) break;
    any = true;
    // A quoted CSV field may hold a newline (appendCsvField's rule): the
    // record goes on on the next line, which counts as a line of the file.
    if (c == '"' && format_ == TrajectoryFileFormat::Csv) quoted = !quoted;
    if (c == '\n' && !quoted) break;
    if (c == '\n') ++continued;
    if (out.size() >= limits_.maxLineBytes) {
      ++lineNumber_;
      return fail(d, 1,
                  "trajectory line longer than " + std::to_string(limits_.maxLineBytes) +
                      " bytes (is this a trajectory file?)");
    }
    out += static_cast<char>(c);
  }
  if (!any) return false;
  ++lineNumber_;  // a record is reported at its first line
  continuedLines_ = continued;
  if (!out.empty() && out.back() == '\r') out.pop_back();
  return true;
}

bool TrajectoryReader::parseJson(const std::string& text, double& time, TrajectoryEntry& e, Diagnostics& d) {
  PointSink sink;
  sink.max = limits_.maxPoints;
  JsonLine parsed = parseJsonLine(text, sink);
  if (!sink.bad.empty()) return fail(d, elementColumn(text, "points", sink.badIndex), sink.bad);
  if (parsed.errorByte)
    return fail(d, static_cast<std::uint32_t>(std::min<std::size_t>(parsed.errorByte, text.size() + 1)),
                parsed.error + " (rscene-sim --trajectory writes one JSON object per line)");
  const nlohmann::json& j = parsed.value;
  if (!j.is_object()) return fail(d, 1, "a trajectory line is a JSON object");
  if (!parsed.duplicateKey.empty())
    return fail(d, nthKeyColumn(text, parsed.duplicateKey, parsed.duplicateOccurrence),
                "\"" + parsed.duplicateKey + "\" twice in one object (which one is meant?)");
  auto number = [&](const nlohmann::json& v, const char* key, double& out) {
    if (!v.is_number()) return fail(d, keyColumn(text, key), std::string(key) + " is not a number");
    out = v.get<double>();
    if (!finiteBounded(out))
      return fail(d, keyColumn(text, key), std::string(key) + " out of range (|value| at most 1e12)");
    return true;
  };
  auto vec = [&](const char* key, double* out, std::size_t n) {
    auto it = j.find(key);
    if (it == j.end()) return fail(d, 1, std::string("no \"") + key + "\" in the line");
    if (!it->is_array() || it->size() != n)
      return fail(d, keyColumn(text, key), std::string(key) + " is not an array of " + std::to_string(n) + " numbers");
    for (std::size_t i = 0; i < n; ++i)
      if (!number((*it)[i], key, out[i])) return false;
    return true;
  };
  auto t = j.find("time");
  if (t == j.end()) return fail(d, 1, "no \"time\" in the line");
  if (!number(*t, "time", time)) return false;
  auto p = j.find("path");
  if (p == j.end() || !p->is_string()) return fail(d, keyColumn(text, "path"), "no \"path\" string in the line");
  e.path = p->get<std::string>();
  // At the path's value: the opening quote after "path":.
  std::size_t value = text.find('"', text.find(':', keyColumn(text, "path") + 5));
  e.pathColumn = value == std::string::npos ? 1 : static_cast<std::uint32_t>(value + 1);
  if (auto pts = j.find("points"); pts != j.end()) {
    e.pointsColumn = nthKeyColumn(text, "points", 0);
    if (!pts->is_array()) return fail(d, e.pointsColumn, "points is not an array of [x,y,z] triples");
    for (const char* pose : {"position", "quaternion", "jointPositions"})
      if (j.contains(pose))
        return fail(d, keyColumn(text, pose),
                    std::string("a line with points is a deformable's or granular record's: it has no ") + pose);
    e.particles = true;
    e.points = std::move(sink.points);
    return true;
  }
  double pos[3], quat[4];
  if (!vec("position", pos, 3) || !vec("quaternion", quat, 4)) return false;
  Eigen::Quaterniond q(quat[0], quat[1], quat[2], quat[3]);
  if (q.norm() < 1e-12) return fail(d, keyColumn(text, "quaternion"), "quaternion of zero length");
  e.pose = {{pos[0], pos[1], pos[2]}, q.normalized()};
  if (auto jp = j.find("jointPositions"); jp != j.end()) {
    std::uint32_t column = keyColumn(text, "jointPositions");
    if (!jp->is_object()) return fail(d, column, "jointPositions is not an object of joint names and numbers");
    for (auto it = jp->begin(); it != jp->end(); ++it) {
      TrajectoryEntry::Joint joint;
      joint.name = it.key();
      joint.column = column;
      if (!it->is_number()) return fail(d, column, "joint '" + joint.name + "' is not a number");
      joint.value = it->get<double>();
      if (!finiteBounded(joint.value)) return fail(d, column, "joint '" + joint.name + "' out of range");
      e.joints.push_back(std::move(joint));
    }
  }
  return true;
}

bool TrajectoryReader::parseCsvHeader(const std::string& text, Diagnostics& d) {
  std::vector<CsvField> fields;
  std::uint32_t bad = 0;
  if (!splitCsv(text, fields, bad)) return fail(d, bad, "malformed CSV header (unclosed quote)");
  for (std::size_t i = 0; i < kTrajectoryBodyColumns.size(); ++i)
    if (i >= fields.size() || fields[i].text != kTrajectoryBodyColumns[i])
      return fail(d, i < fields.size() ? fields[i].column : static_cast<std::uint32_t>(text.size() + 1),
                  std::string("CSV header column ") + std::to_string(i + 1) + " is not '" + std::string(kTrajectoryBodyColumns[i]) +
                      "' (rscene-sim --trajectory-format csv writes time,path,px,...,wz)");
  for (std::size_t i = kTrajectoryBodyColumns.size(); i < fields.size(); ++i) {
    const std::string& name = fields[i].text;
    if (name == kTrajectoryPointsColumn && i + 1 == fields.size())  // particles of deformables and granular media (last)
      csvPoints_ = true;
    else if (name.rfind(kJointPositionPrefix, 0) == 0 && name.size() > kJointPositionPrefix.size())
      csvJoints_.push_back(name.substr(kJointPositionPrefix.size()));
    else if (name.rfind(kJointVelocityPrefix, 0) == 0 && name.size() > kJointVelocityPrefix.size())
      csvJoints_.emplace_back();
    else
      return fail(d, fields[i].column, "CSV header column '" + name + "' is neither q.JOINT nor u.JOINT");
  }
  return true;
}

bool TrajectoryReader::parseCsv(const std::string& text, double& time, TrajectoryEntry& e, Diagnostics& d) {
  std::vector<CsvField> f;
  std::uint32_t bad = 0;
  if (!splitCsv(text, f, bad)) return fail(d, bad, "malformed CSV field (unclosed quote)");
  std::size_t want = kTrajectoryBodyColumns.size() + csvJoints_.size() + (csvPoints_ ? 1 : 0);
  if (f.size() != want)
    return fail(d, f.size() > want ? f[want].column : static_cast<std::uint32_t>(text.size() + 1),
                std::to_string(f.size()) + " fields where the header has " + std::to_string(want));
  // A particle row: time, path and points, every pose and joint cell empty.
  if (csvPoints_ && f[2].text.empty()) {
    for (std::size_t i = 2; i + 1 < f.size(); ++i)
      if (!f[i].text.empty())
        return fail(d, f[i].column, "a row with points has no pose or joint values (px is empty)");
    std::optional<double> t = parseNumber(f[0].text);
    if (!t || !finiteBounded(*t)) return fail(d, f[0].column, "time '" + f[0].text + "' is not a number in range");
    time = *t;
    e.path = f[1].text;
    e.pathColumn = f[1].column;
    e.particles = true;
    // A quoted cell's text starts one byte after its column.
    const CsvField& cell = f.back();
    std::uint32_t start = cell.column + (cell.column <= text.size() && text[cell.column - 1] == '"' ? 1 : 0);
    e.pointsColumn = cell.column;
    return parseCsvPoints(cell.text, start, e.points, d);
  }
  double v[kTrajectoryBodyColumns.size()];
  for (std::size_t i = 0; i < kTrajectoryBodyColumns.size(); ++i) {
    if (i == 1) continue;
    std::optional<double> n = parseNumber(f[i].text);
    if (!n || !finiteBounded(*n))
      return fail(d, f[i].column, std::string(kTrajectoryBodyColumns[i]) + " '" + f[i].text + "' is not a number in range");
    v[i] = *n;
  }
  time = v[0];
  e.path = f[1].text;
  e.pathColumn = f[1].column;
  if (csvPoints_ && !f.back().text.empty()) return fail(d, f.back().column, "a body's or robot's row has no points");
  Eigen::Quaterniond q(v[5], v[6], v[7], v[8]);
  if (q.norm() < 1e-12) return fail(d, f[5].column, "quaternion of zero length");
  e.pose = {{v[2], v[3], v[4]}, q.normalized()};
  for (std::size_t k = 0; k < csvJoints_.size(); ++k) {
    const CsvField& cell = f[kTrajectoryBodyColumns.size() + k];
    if (csvJoints_[k].empty() || cell.text.empty()) continue;  // a velocity, or another robot's joint
    std::optional<double> n = parseNumber(cell.text);
    if (!n || !finiteBounded(*n))
      return fail(d, cell.column, std::string(kJointPositionPrefix) + csvJoints_[k] + " '" + cell.text + "' is not a number in range");
    e.joints.push_back({csvJoints_[k], *n, cell.column});
  }
  return true;
}

// "x y z;x y z;...": each point three numbers split by blanks, points by
// ';' (an empty cell: no points).  `column` is where `cell` starts.
bool TrajectoryReader::parseCsvPoints(const std::string& cell, std::uint32_t column, std::vector<Eigen::Vector3d>& out,
                                      Diagnostics& d) {
  out.clear();
  if (cell.empty()) return true;
  std::size_t begin = 0;
  for (std::size_t index = 0;; ++index) {
    std::size_t end = cell.find(';', begin);
    if (end == std::string::npos) end = cell.size();
    auto at = static_cast<std::uint32_t>(column + begin);
    if (index >= limits_.maxPoints)
      return fail(d, at,
                  "more than " + std::to_string(limits_.maxPoints) +
                      " points (the scene's largest deformable or granular record has " +
                      std::to_string(limits_.maxPoints) + ")");
    double xyz[3];
    int n = 0;
    std::size_t i = begin;
    while (i < end) {
      while (i < end && (cell[i] == ' ' || cell[i] == '\t')) ++i;
      if (i == end) break;
      std::size_t j = i;
      while (j < end && cell[j] != ' ' && cell[j] != '\t') ++j;
      std::optional<double> v = n < 3 ? parseNumber(std::string_view(cell).substr(i, j - i)) : std::nullopt;
      if (!v)
        return fail(d, at, "point " + std::to_string(index) + " '" + cell.substr(begin, end - begin) +
                               "' is not three numbers 'x y z'");
      if (!finiteBounded(*v))
        return fail(d, at, "point " + std::to_string(index) + " out of range (|value| at most 1e12)");
      xyz[n++] = *v;
      i = j;
    }
    if (n != 3)
      return fail(d, at, "point " + std::to_string(index) + " '" + cell.substr(begin, end - begin) +
                             "' is not three numbers 'x y z'");
    out.emplace_back(xyz[0], xyz[1], xyz[2]);
    if (end == cell.size()) return true;
    begin = end + 1;
  }
}

bool TrajectoryReader::parseLine(const std::string& text, double& time, TrajectoryEntry& e, Diagnostics& d) {
  e = {};
  e.line = lineNumber_;
  return format_ == TrajectoryFileFormat::Csv ? parseCsv(text, time, e, d) : parseJson(text, time, e, d);
}

bool TrajectoryReader::next(TrajectoryFrame& frame, Diagnostics& d) {
  frame.entries.clear();
  if (failed_ || ended_) return false;
  std::string line;
  if (format_ == TrajectoryFileFormat::Unknown) {
    // The first line that is not blank tells the format.
    do {
      if (!readLine(line, d)) {
        if (failed_) return false;
        ended_ = true;
        return fail(d, 0, "empty trajectory: no line to render");
      }
    } while (line.find_first_not_of(" \t") == std::string::npos);
    if (line.front() == '{')
      format_ = TrajectoryFileFormat::Jsonl;
    else if (line.rfind("time,", 0) == 0) {
      format_ = TrajectoryFileFormat::Csv;
      if (!parseCsvHeader(line, d) || !readLine(line, d)) {
        if (!failed_) fail(d, 0, "CSV trajectory with a header and no line");
        return false;
      }
    } else {
      return fail(d, 1, "not a trajectory: neither JSON Lines nor CSV with a 'time,path,...' header");
    }
    if (!parseLine(line, pendingTime_, pending_, d)) return false;
    havePending_ = true;
  }
  if (!havePending_) {
    ended_ = true;
    return false;
  }
  frame.time = pendingTime_;
  frame.index = frames_++;
  frame.entries.push_back(std::move(pending_));
  havePending_ = false;
  lastTime_ = frame.time;
  while (readLine(line, d)) {
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    double time = 0;
    TrajectoryEntry e;
    if (!parseLine(line, time, e, d)) return false;
    if (time < lastTime_)
      return fail(d, 1,
                  "time " + numberText(time) + " is before the previous frame's " + numberText(lastTime_) +
                      " (times must not decrease)");
    if (time != frame.time) {
      pendingTime_ = time;
      pending_ = std::move(e);
      havePending_ = true;
      return true;
    }
    for (const TrajectoryEntry& other : frame.entries)
      if (other.path == e.path)
        return fail(d, e.pathColumn,
                    "'" + e.path + "' twice at time " + numberText(time) + " (first on line " +
                        std::to_string(other.line) + ")");
    if (frame.entries.size() >= limits_.maxEntriesPerFrame)
      return fail(d, 1, "more than " + std::to_string(limits_.maxEntriesPerFrame) + " lines at one time");
    frame.entries.push_back(std::move(e));
  }
  if (failed_) return false;
  ended_ = true;
  return true;
}

TrajectoryPoser::TrajectoryPoser(const Scene& scene, const std::vector<std::shared_ptr<const Model>>& models,
                                 ParticleCounts counts)
    : counts_(std::move(counts)), deformables_(scene.deformables.size()), granulars_(scene.granulars.size()) {
  addTargets(scene, models);
}

void TrajectoryPoser::addTargets(const Scene& scene, const std::vector<std::shared_ptr<const Model>>& models) {
  for (std::size_t i = 0; i < scene.deformables.size(); ++i)
    targets_.emplace(scene.deformables[i].path,
                     Target{Mount::Kind::World, static_cast<int>(i), Particles::Deformable});
  for (std::size_t i = 0; i < scene.granulars.size(); ++i)
    targets_.emplace(scene.granulars[i].path, Target{Mount::Kind::World, static_cast<int>(i), Particles::Granular});
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    targets_.emplace(scene.objects[i].path, Target{Mount::Kind::Object, static_cast<int>(i)});
  for (std::size_t i = 0; i < scene.compounds.size(); ++i)
    targets_.emplace(scene.compounds[i].path, Target{Mount::Kind::Compound, static_cast<int>(i)});
  robots_.resize(scene.articulated.size());
  for (std::size_t i = 0; i < scene.articulated.size(); ++i) {
    targets_.emplace(scene.articulated[i].path, Target{Mount::Kind::Articulated, static_cast<int>(i)});
    if (i >= models.size() || !models[i]) continue;
    Robot& r = robots_[i];
    r.model = models[i];
    makeCoordinates(*r.model, scene.articulated[i].jointOrder, r.coordinates);
    std::vector<std::string> names = coordinateNames(*r.model, r.coordinates, false);
    for (std::size_t k = static_cast<std::size_t>(r.coordinates.baseCoordinates); k < names.size(); ++k) {
      r.coordinate.emplace(names[k], static_cast<int>(k));
      r.names.push_back(names[k]);
    }
  }
  // A JSON line holds a path that is not UTF-8 in its JSON-safe form
  // (jsonSafeText); a CSV line as written.  Both find the body.
  std::vector<std::pair<std::string, Target>> safe;
  for (const auto& [path, target] : targets_)
    if (std::string s = jsonSafeText(path); s != path) safe.emplace_back(std::move(s), target);
  for (auto& [path, target] : safe) targets_.emplace(std::move(path), target);
}

bool TrajectoryPoser::apply(const TrajectoryFrame& frame, const std::string& file, BodyPoses& poses,
                            Diagnostics& d, ParticlePositions* particles) const {
  auto error = [&](const TrajectoryEntry& e, std::uint32_t column, std::string message) {
    Diagnostic x;
    x.code = code::kTrajectoryTarget;
    x.file = file;
    x.line = e.line;
    x.column = column;
    x.message = std::move(message);
    d.push_back(std::move(x));
    return false;
  };
  for (const TrajectoryEntry& e : frame.entries) {
    auto it = targets_.find(e.path);
    if (it == targets_.end())
      return error(e, e.pathColumn,
                   "'" + e.path +
                       (e.particles ? "' is no deformable or granular record of the scene"
                                    : "' is no object, compound or articulated system of the scene"));
    const Target& t = it->second;
    if (t.particles != Particles::None || e.particles) {
      const bool deformable = t.particles == Particles::Deformable;
      if (t.particles == Particles::None)
        return error(e, e.pointsColumn,
                     "'" + e.path + "' is a body or robot, not a deformable or granular record: it has no points");
      if (!e.particles)
        return error(e, e.pathColumn,
                     "'" + e.path + "' is a " + (deformable ? "deformable" : "granular") +
                         " record: its line gives points, not a pose");
      const auto index = static_cast<std::size_t>(t.index);
      const std::vector<std::int64_t>& counts = deformable ? counts_.deformables : counts_.granulars;
      std::int64_t want = index < counts.size() ? counts[index] : -1;
      // A deformable's fill particles (fem) follow its OBJ's vertices.
      if (want >= 0 && (deformable ? e.points.size() < static_cast<std::uint64_t>(want)
                                   : e.points.size() != static_cast<std::uint64_t>(want)))
        return error(e, e.pointsColumn,
                     "'" + e.path + "' has " + std::to_string(want) +
                         (deformable ? " vertices (its OBJ's v lines)" : " particles") + ", the line gives " +
                         std::to_string(e.points.size()) + " points");
      if (particles) {
        std::vector<ParticlePositions::Record>& list = deformable ? particles->deformables : particles->granulars;
        if (list.size() < (deformable ? deformables_ : granulars_)) list.resize(deformable ? deformables_ : granulars_);
        ParticlePositions::Record& r = list[index];
        r.given = true;
        ++r.version;
        r.points = e.points;
      }
      continue;
    }
    auto set = [&](std::vector<Pose>& list) {
      if (static_cast<std::size_t>(t.index) < list.size()) list[static_cast<std::size_t>(t.index)] = e.pose;
    };
    if (t.kind == Mount::Kind::Object)
      set(poses.objects);
    else if (t.kind == Mount::Kind::Compound)
      set(poses.compounds);
    if (t.kind != Mount::Kind::Articulated) {
      if (!e.joints.empty())
        return error(e, e.joints.front().column, "'" + e.path + "' is a body, not a robot: it has no joints");
      continue;
    }
    const Robot& r = robots_[static_cast<std::size_t>(t.index)];
    if (!r.model) continue;
    Eigen::VectorXd q = neutralCoordinate(*r.model, r.coordinates, e.pose);
    std::vector<bool> given(r.names.size(), false);
    const int base = r.coordinates.baseCoordinates;
    for (const TrajectoryEntry::Joint& j : e.joints) {
      auto at = r.coordinate.find(j.name);
      if (at == r.coordinate.end())
        return error(
            e, j.column,
            "joint '" + j.name + "' is no movable joint of robot '" + e.path + "' (model '" + r.model->name + "')");
      q[at->second] = j.value;
      given[static_cast<std::size_t>(at->second - base)] = true;
    }
    // rscene-sim writes every joint: a line without one is cut or edited,
    // and silently drawing that joint at zero would hide it.
    for (std::size_t k = 0; k < given.size(); ++k) {
      if (given[k]) continue;
      std::uint32_t column = e.joints.empty() ? e.pathColumn : e.joints.front().column;
      return error(e, column,
                   "robot '" + e.path + "' (model '" + r.model->name + "'): the line leaves out joint '" + r.names[k] +
                       "' (every movable joint needs a position)");
    }
    // Spherical joints' quaternions as the simulator reads them: unit.
    for (int ji : r.coordinates.joints) {
      if (r.model->joints[static_cast<std::size_t>(ji)].type != JointType::Spherical) continue;
      int k = r.coordinates.coordinateIndex[static_cast<std::size_t>(ji)];
      double n = q.segment<4>(k).norm();
      q.segment<4>(k) = n > 1e-12 ? Eigen::Vector4d(q.segment<4>(k) / n) : Eigen::Vector4d(1, 0, 0, 0);
    }
    if (poses.robotLinks.size() <= static_cast<std::size_t>(t.index))
      poses.robotLinks.resize(static_cast<std::size_t>(t.index) + 1);
    poses.robotLinks[static_cast<std::size_t>(t.index)] = linkPoses(*r.model, r.coordinates, e.pose, q);
  }
  return true;
}

}  // namespace rscene::robot
