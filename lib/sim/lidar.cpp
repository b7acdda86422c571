#include "sim/lidar.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "sim/sensor_noise.hpp"

namespace rscene::sim {

std::vector<Eigen::Vector3d> lidarDirections(const SensorParams& p) {
  std::vector<Eigen::Vector3d> out;
  if (p.lidarChannels <= 0 || p.lidarSamples <= 0) return out;
  out.reserve(static_cast<std::size_t>(p.lidarChannels) * static_cast<std::size_t>(p.lidarSamples));
  constexpr double kDeg = M_PI / 180;
  for (int i = 0; i < p.lidarChannels; ++i) {
    double pitch = p.lidarChannels == 1
                       ? (p.lidarMinPitch + p.lidarMaxPitch) / 2
                       : p.lidarMinPitch + i * (p.lidarMaxPitch - p.lidarMinPitch) / (p.lidarChannels - 1);
    double cp = std::cos(pitch * kDeg), sp = std::sin(pitch * kDeg);
    for (int j = 0; j < p.lidarSamples; ++j) {
      double yaw = 2 * M_PI * j / p.lidarSamples * (p.lidarClockwise ? -1 : 1);
      out.emplace_back(cp * std::cos(yaw), cp * std::sin(yaw), sp);
    }
  }
  return out;
}

std::vector<Eigen::Vector3f> scanLidar(const RayGeometry& geometry, const Pose& pose, const SensorParams& p,
                                       const std::vector<Eigen::Vector3d>& directions,
                                       const LidarScanOptions& options) {
  const std::size_t n = directions.size();
  // Ranges per ray first (NaN: no return), split over threads by ray
  // index; noise depends on the ray index only, so the split changes nothing.
  std::vector<float> range(n);
  const Eigen::Matrix3d r = pose.orientation.toRotationMatrix();
  const Eigen::Vector3d origin = pose.position;
  const bool noisy = p.noiseStddev != 0 || p.noiseMean != 0;
  auto work = [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      double t = geometry.cast(origin, r * directions[k], p.lidarMaxRange, options.exclude);
      if (!(t >= p.lidarMinRange && t <= p.lidarMaxRange)) {
        range[k] = NAN;
        continue;
      }
      if (noisy) t += p.noiseMean + p.noiseStddev * gaussian(p.noiseSeed, options.scanIndex, k);
      // The range window holds for what the sensor reports: a noisy reading
      // outside it is no return, like a true range outside it.
      range[k] = t > 0 && t >= p.lidarMinRange && t <= p.lidarMaxRange ? static_cast<float>(t) : NAN;
    }
  };
  int threads = std::clamp(options.threads, 1, 64);
  if (n < 4096) threads = 1;  // not worth a thread
  // Chunks of rays handed out as threads ask: on a loaded machine a thread
  // that is not scheduled leaves its share to the others instead of
  // making the scan wait for it.
  constexpr std::size_t kChunk = 1024;
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t begin; (begin = next.fetch_add(kChunk)) < n;) work(begin, std::min(n, begin + kChunk));
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  std::vector<Eigen::Vector3f> points;
  points.reserve(n);
  for (std::size_t k = 0; k < n; ++k)
    if (!std::isnan(range[k])) points.push_back((directions[k] * double(range[k])).cast<float>());
  return points;
}

}  // namespace rscene::sim
