// What a scene must satisfy before a tool interprets its bodies: the one
// list of conditions that rscene-validate reports and rscene-sim and
// rscene-render refuse, so that the three cannot disagree about a body.
// Errors point at the record's field, with the validator's code where
// lib/core checks the same thing.
#pragma once
#include "core/assets.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "scene/scene.hpp"
#include "scene/triangle_surface.hpp"

namespace rscene {

struct SceneCheckOptions {
  // RS5001: mesh files bodies collide with must exist (sim; validate with
  // --check-files).  Off where missing assets are allowed or drawn
  // as placeholders.
  bool checkFiles = false;
  FileExists exists = fileExistsOnDisk;
  // When set, a deformable whose mesh file exists is judged with its mesh
  // too (scene/deformable_model.hpp: RS7080 when it is no usable surface,
  // RS7081 for a pinned vertex it lacks, an open mesh to fill, a fill or
  // constraint count past the bounds ...).  The tools pass lib/asset's
  // OBJ reader (asset::objSurfaceReader); validate only with --check-files.
  SurfaceReader readSurface;
  // When set, a mesh file that exists must read as a mesh (RS7007): a
  // body's collision mesh and compound child meshes, and with
  // visualAssets a foliage layer's and an instanced visual's mesh.  The tools pass lib/asset's
  // reader (asset::meshReader); validate only with --check-files.
  MeshReader readMesh;
  // Also judge the meshes only drawn (foliage): validate and rscene-render;
  // rscene-sim reads no visual asset.
  bool visualAssets = false;
  // Warnings about what stepping the scene costs (RS7086: granular
  // substeps raised): off in a tool that does not step it (rscene-render).
  bool stepWarnings = true;
};

// Appends the findings about `scene` (built from `doc`):
//   RS7008  time_step not positive
//   RS4008  dynamic object or compound with mass <= 0 (ground and
//           half_space are static, compat-notes.md "object record")
//   RS7003  body shape with a zero or negative physical size (box sides,
//           radius x scale.x, height x scale.z, mesh scale; compound
//           children in the compound's scale)
//   RS7004  mesh body without a mesh path
//   RS7009  compound child that is a plane (ground, half_space)
//   RS5001  collision mesh file missing (when options.checkFiles)
//   RS3012  enabled wire whose body names no node
//   RS7011  warning: wire to a node the simulator does not model, skipped
//   RS7020-RS7022  numbers no simulator can stand behind (scene/limits.hpp)
//   RS7080, RS7081  deformable records (scene/deformable_check.hpp; with
//           readSurface, scene/deformable_model.hpp with their mesh)
//   RS7082, RS7086-RS7089  granular records (scene/granular.hpp)
//   RS7064-RS7069, RS2007  sensor records and camera outputPath
//           (scene/sensor_check.hpp)
//   RS7013  warning (with stepWarnings): a dynamic primitive body that
//           starts more than 1 cm below a ground or half_space, or inside
//           another dynamic box, sphere or capsule (scene/start_pose.hpp)
//   RS7014  warning (with stepWarnings): dynamic box, sphere or capsule
//           objects starting in contact with masses more than 100 times
//           apart, at the heavier one's mass (scene/start_pose.hpp)
//   RS7015  error (with stepWarnings: a rule about stepping): a dynamic
//           object or compound starting more than 10 m under the lowest
//           ground or half_space (scene/start_pose.hpp)
// Returns false when it added an error.
bool checkScene(const Document& doc, const Scene& scene, const SceneCheckOptions& options, Diagnostics& diagnostics);

}  // namespace rscene
