#include "sim/pcd.hpp"

#include <charconv>
#include <cstring>

namespace rscene::sim {
namespace {

void appendNumber(std::string& s, double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, r.ptr);
}

void appendNumber(std::string& s, float v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, r.ptr);
}

}  // namespace

void writePcd(Sink& out, const std::vector<Eigen::Vector3f>& points, const Pose& viewpoint, double time,
              PcdEncoding encoding) {
  std::string h = "# .PCD v0.7 - Point Cloud Data file format\n# time ";
  appendNumber(h, time);
  h += "\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH ";
  h += std::to_string(points.size());
  h += "\nHEIGHT 1\nVIEWPOINT";
  const Eigen::Quaterniond& q = viewpoint.orientation;
  for (double v : {viewpoint.position.x(), viewpoint.position.y(), viewpoint.position.z(), q.w(), q.x(), q.y(), q.z()})
    h += ' ', appendNumber(h, v);
  h += "\nPOINTS " + std::to_string(points.size());
  h += encoding == PcdEncoding::Binary ? "\nDATA binary\n" : "\nDATA ascii\n";
  out.write(h);
  constexpr std::size_t kChunk = 1 << 16;
  std::string body;
  body.reserve(kChunk + 64);
  for (const Eigen::Vector3f& p : points) {
    if (encoding == PcdEncoding::Binary) {
      static_assert(sizeof(float) == 4);
      char raw[12];  // little-endian hosts: PCD's binary is the host's float layout
      std::memcpy(raw, p.data(), 12);
      body.append(raw, 12);
    } else {
      appendNumber(body, p.x()), body += ' ', appendNumber(body, p.y()), body += ' ', appendNumber(body, p.z());
      body += '\n';
    }
    if (body.size() >= kChunk) out.write(body), body.clear();
  }
  out.write(body);
}

}  // namespace rscene::sim
