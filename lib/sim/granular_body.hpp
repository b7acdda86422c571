// One granular record simulated as RaiSim's GranularSystem does
// (../shared/spec/raisim/GranularMedia.rst): spherical grains with a
// discrete-element contact model (linear or Hertz normal force with
// damping, tangential springs with history capped by Coulomb friction,
// rolling friction, short-range cohesion), explicit integration in the
// record's substeps, contacts with the rigid world through a SurfaceQuery
// with the reaction applied back to dynamic bodies.  rscene-sim(1) has the
// key-by-key mapping.
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "scene/visual_records.hpp"
#include "sim/surface_query.hpp"

namespace rscene::sim {

class GranularBody {
 public:
  // Most particles one granular record may have whatever its maxParticles.
  static constexpr std::uint64_t kMaxParticles = 2'000'000;

  // Builds the particles (explicit positions/radii, else the box fill of
  // granularParticles(), refused past maxParticles before allocating),
  // placed by the record's world pose.  nullptr with `error` (and the key
  // at fault in `errorField`, "" for the record) when it cannot be simulated.
  static std::unique_ptr<GranularBody> create(const Granular& record, std::string& error, std::string& errorField);
  virtual ~GranularBody() = default;

  virtual void step(double dt, const Eigen::Vector3d& gravity, SurfaceQuery& surfaces) = 0;

  virtual const std::vector<Eigen::Vector3d>& positions() const = 0;  // world
  virtual const std::vector<double>& radii() const = 0;
  virtual double totalMass() const = 0;
  virtual double maxSpeed() const = 0;
  virtual bool finite() const = 0;
};

}  // namespace rscene::sim
