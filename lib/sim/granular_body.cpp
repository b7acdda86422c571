// A granular record's solver, built from the scene model's setup
// (scene/granular.hpp); the solver is granular_dem.cpp.
#include "sim/granular_body.hpp"

#include "sim/granular_dem.hpp"

namespace rscene::sim {

std::unique_ptr<GranularBody> GranularBody::create(const Granular& g, double worldTimeStep,
                                                   std::vector<GranularFinding>& findings) {
  std::optional<GranularSetup> setup = granularSetup(g, worldTimeStep, findings);
  if (!setup) return nullptr;
  return makeGranularDem(std::move(*setup));
}

}  // namespace rscene::sim
