// Deterministic Gaussian noise for sensor readings: a counter-based
// generator (SplitMix64 over seed, stream and index, then Box-Muller), so
// that a value depends only on (seed, stream, index): the same seed gives
// the same noisy outputs whatever the thread split of a scan, the platform
// or the standard library (std::normal_distribution is not specified
// bit for bit).
#pragma once
#include <cmath>
#include <cstdint>

namespace rscene::sim {

inline std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// A uniform double in (0, 1): 53 random bits, never 0.
inline double unitOpen(std::uint64_t bits) { return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53; }

// A standard normal value for (seed, stream, index): a sensor's seed, its
// sample (scan) number, and the reading within the sample.
inline double gaussian(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  std::uint64_t key = splitMix64(splitMix64(seed ^ 0x5EED5EED5EED5EEDull) ^ stream);
  std::uint64_t a = splitMix64(key ^ (2 * index)), b = splitMix64(key ^ (2 * index + 1));
  double u1 = unitOpen(a), u2 = unitOpen(b);
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
}

}  // namespace rscene::sim
