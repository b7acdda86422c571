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

// The solver for a checked record (scene/granular.hpp: grains in world,
// material, substeps per world step at least; more when a world step is
// longer than substeps x maxSubstep, a time step other than the setup's).
std::unique_ptr<GranularBody> makeGranularDem(GranularSetup setup);

}  // namespace rscene::sim
