#include "sim/imu.hpp"

#include <algorithm>
#include <charconv>

#include "sim/sensor_noise.hpp"

namespace rscene::sim {

ImuReading imuReading(double time, const Pose& pose, const Eigen::Vector3d& previousVelocity,
                      const Eigen::Vector3d& velocity, const Eigen::Vector3d& omega, const Eigen::Vector3d& gravity,
                      double dt, const SensorParams& p, std::uint64_t sample) {
  ImuReading r;
  r.time = time;
  Eigen::Matrix3d toSensor = pose.orientation.toRotationMatrix().transpose();
  Eigen::Vector3d a = dt > 0 ? Eigen::Vector3d((velocity - previousVelocity) / dt) : Eigen::Vector3d::Zero();
  r.specificForce = toSensor * (a - gravity);
  r.angularVelocity = toSensor * omega;
  if (p.noiseStddev != 0 || p.noiseMean != 0)
    for (int k = 0; k < 3; ++k) {
      r.specificForce[k] += p.noiseMean + p.noiseStddev * gaussian(p.noiseSeed, sample, std::uint64_t(k));
      r.angularVelocity[k] += p.noiseMean + p.noiseStddev * gaussian(p.noiseSeed, sample, std::uint64_t(k + 3));
    }
  auto saturate = [](Eigen::Vector3d& v, double limit) {
    if (limit > 0) v = v.cwiseMax(-limit).cwiseMin(limit);
  };
  saturate(r.specificForce, p.accelerationLimit);
  saturate(r.angularVelocity, p.angularVelocityLimit);
  return r;
}

std::string imuHeader(ImuFormat format) { return format == ImuFormat::Csv ? "time,ax,ay,az,wx,wy,wz\n" : ""; }

void appendImu(std::string& out, ImuFormat format, const ImuReading& r) {
  auto number = [&](double v) {
    char buf[32];
    auto e = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, e.ptr);
  };
  const Eigen::Vector3d &f = r.specificForce, &w = r.angularVelocity;
  if (format == ImuFormat::Csv) {
    number(r.time);
    for (double v : {f.x(), f.y(), f.z(), w.x(), w.y(), w.z()}) out += ',', number(v);
    out += '\n';
    return;
  }
  out += "{\"time\":", number(r.time);
  out += ",\"acceleration\":[", number(f.x()), out += ',', number(f.y()), out += ',', number(f.z());
  out += "],\"angularVelocity\":[", number(w.x()), out += ',', number(w.y()), out += ',', number(w.z());
  out += "]}\n";
}

}  // namespace rscene::sim
