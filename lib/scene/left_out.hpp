// What rscene-sim and rscene-render leave out under --allow-missing-assets
// (a body whose collision mesh, a robot whose file is missing), and what
// hangs on it: decided once here so both tools say the same.
#pragma once
#include <set>
#include <string>

#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "scene/scene.hpp"

namespace rscene {

// Disables every enabled wire with an end on one of `records` (the record
// indices of what was left out; the ends as the model resolved them,
// Wire::recordA/B) and, with `sensors`, every enabled sensor and camera
// mounted on one (Sensor::mount, Camera::mount), and every enabled IK
// target of a robot left out, each with a warning (RS5001) at the field
// naming it: "wire ... is not attached" / "sensor ... is not used" /
// "IK target ... is not solved: <name> was left out <why>".
void detachFromLeftOut(const Document& doc, Scene& scene, const std::set<int>& records, bool sensors,
                       const std::string& why, Diagnostics& diagnostics);

}  // namespace rscene
