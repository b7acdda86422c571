// The rules a deformable record's own values must meet before its mesh is
// read, decided once: checkScene() reports them (rscene-validate,
// rscene-render) and rscene-sim's model builder (sim/deformable_model.hpp)
// refuses by the same function, so the tools cannot disagree.  The
// enumerations (solverMode, particleMode) are the schema's: the reader
// refuses other names (RS2006) before this runs.
#pragma once
#include <string>

#include "scene/visual_records.hpp"

namespace rscene {

// Most iterations and substeps a deformable record may ask for.
inline constexpr long kMaxDeformableIterations = 10000;
inline constexpr long kMaxDeformableSubsteps = 1000;
// Physical ranges of the material (0 too: youngsModulus off, thickness unused).
inline constexpr double kMinThickness = 1e-6, kMaxThickness = 10;          // m
inline constexpr double kMinYoungsModulus = 1, kMaxYoungsModulus = 1e13;   // Pa (gels to past diamond)

// False with `error` and the record's key at fault in `field` (RS7081)
// when a value is out of range: the kind rscene-sim does not simulate,
// totalMass, compliance/stiffness/thickness/damping/radius/spacing ranges
// (thickness 0 or 1e-6 to 10 m, youngsModulus 0 or 1 to 1e13 Pa),
// poissonRatio, iterations, substeps, a scale that is not finite, a
// filled or fem body without a particle spacing.
bool checkDeformableRecord(const Deformable& record, std::string& error, std::string& field);

// Whether the record's particles are the mesh's vertices plus a fill of
// its inside (particleMode filled; fem fills unless its mode is surface).
inline bool deformableFilled(const Deformable& r) {
  return r.particleMode == "filled" || (r.kind == "fem" && r.particleMode == "skinned");
}

}  // namespace rscene
