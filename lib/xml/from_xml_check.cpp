// rscene-from-xml's last step: the converted records go through the same
// checks rscene-validate, rscene-sim and rscene-to-xml run (lib/scene's
// validateScene, with lib/robot's robot checks), so the tool never writes
// a scene those tools refuse.  Each error is reported again at the XML
// element (and attribute, where the record field has one) that made the
// record, with the check's own code in the message.
#include <cstdint>
#include <string_view>

#include "core/check.hpp"
#include "robot/check.hpp"
#include "scene/validate.hpp"
#include "xml/from_xml_context.hpp"

namespace rscene::xml::detail {
namespace {

// Where a record field is written in the XML: the attribute `names` of the
// element itself (child empty) or of its child element `child`.
struct FieldSource {
  std::string_view field;
  std::string_view child;
  std::string_view name = {}, alias = {};  // both empty: the child element itself
};

// The record fields the mapping writes from an attribute (rscene-from-xml(1),
// the mapping table).  A field not listed is reported at the element.
const FieldSource kFieldSources[] = {
    {"radius", "dim", "radius"},
    {"height", "dim", "height"},
    {"height", "", "height"},  // ground
    {"scale", "", "scale"},    // mesh
    {"scale", "dim"},        // box: dim x y z
    {"size", "dim"},         // compound child box
    {"mass", "", "mass"},
    {"position", "state", "pos"},
    {"orientation", "state", "quat"},
    {"position", "state", "qpos"},  // articulated: qpos[0..2] of a floating base
    {"orientation", "state", "qpos"},  // and qpos[3..6]
    {"generalizedCoordinate", "state", "qpos"},
    {"generalizedVelocity", "state", "qvel"},
    {"meshPath", "", "file_name", "fileName"},
    {"centerOfMass", "", "com"},
    {"inertiaDiagonal", "inertia"},
    {"contactMaterial", "", "material"},
    {"collisionGroup", "", "collision_group", "collisionGroup"},
    {"collisionMask", "", "collision_mask", "collisionMask"},
    {"bodyMode", "", "body_type", "bodyType"},
    {"length", "", "length"},
    {"stiffness", "", "stiffness"},
    {"dt", "", "value"},
    {"gravity", "", "value"},
    {"value", "", "value"},
    {"erp", "", "erp"},
    {"erp2", "", "erp2"},
    {"friction", "", "friction"},
    {"restitution", "", "restitution"},
    {"defaultFriction", "default", "friction"},
    {"defaultRestitution", "default", "restitution"},
    {"defaultRestitutionThreshold", "default", "restitution_threshold"},
};

// The diagnostic `d` (a finding on a record line) as an error at `from`.
Diagnostic atElement(const Diagnostic& d, const Element& from) {
  std::string message = d.message + " (" + d.code + " in the converted scene)";
  for (const FieldSource& s : kFieldSources) {
    if (d.field != s.field) continue;
    const Element* e = s.child.empty() ? &from : from.child(s.child);
    if (!e) continue;
    if (s.name.empty()) return elementDiagnostic(Severity::Error, code::kRefused, *e, message);
    if (const Attribute* a = e->attribute(s.name, s.alias))
      return attributeDiagnostic(Severity::Error, code::kRefused, *e, *a, message);
  }
  return elementDiagnostic(Severity::Error, code::kRefused, from, message);
}

// Keeps the errors only: the warnings of the scene checks (a material no
// pair names, a path outside /World) are rscene-validate's to say.
struct Collect : DiagnosticSink {
  Diagnostics errors;
  void add(Diagnostic d) override {
    if (d.severity == Severity::Error) errors.push_back(std::move(d));
  }
};

}  // namespace

void checkConverted(Context& ctx, std::string text, const Element& root,
                    const std::vector<const Element*>& lineOrigins, Document& doc) {
  CheckOptions co;
  // Asset paths are written relative to the output's folder, where the
  // other tools will resolve them; missing files are not an error here
  // (a missing mesh is a warning at its element, see convertSingleBody).
  co.sceneDir = ctx.options.absolutePaths ? "." : ctx.options.outputDir;
  co.checkFiles = false;
  Collect sink;
  robot::RobotCheckOptions ro;
  validateScene(std::move(text), co, doc, sink, [&](const Document& d, const Scene& s, std::vector<SceneFinding>& out) {
    robot::checkRobots(d, s, ro, ctx.models, out);
  });
  for (const Diagnostic& d : sink.errors) {
    // A finding inside another file (a robot's URDF: none without
    // checkFiles, but a robot check may add one) names its place there.
    if (!d.file.empty()) {
      Diagnostic inFile = d;
      inFile.message = d.file + ":" + std::to_string(d.line) + ": " + d.message;
      ctx.result.diagnostics.push_back(atElement(inFile, root));
      continue;
    }
    const Element* from = d.line >= 1 && d.line <= lineOrigins.size() ? lineOrigins[d.line - 1] : nullptr;
    ctx.result.diagnostics.push_back(atElement(d, from ? *from : root));
  }
}

}  // namespace rscene::xml::detail
