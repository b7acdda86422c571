// The DEM solver behind GranularBody: grains as a structure of arrays,
// forces from granular_contact.hpp over the pair list of
// granular_pairs.hpp and the rigid world's SurfaceQuery, semi-implicit
// Euler in substeps.  Single-threaded and deterministic: every sum runs in
// an order fixed by the data (pair list order, then grain index order).
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "sim/granular_body.hpp"
#include "sim/granular_material.hpp"

namespace rscene::sim {

struct GranularParticles {
  std::vector<Eigen::Vector3d> positions;  // world
  std::vector<double> radii;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero(), angularVelocity = Eigen::Vector3d::Zero();  // world, all grains
  bool fixed = false;
};

// `substeps` per world step at least; more when a world step is longer
// than substeps x maxSubstep (a time step other than the one create() saw).
std::unique_ptr<GranularBody> makeGranularDem(GranularParticles particles, const GranularMaterial& material,
                                              int substeps, double maxSubstep);

}  // namespace rscene::sim
