// INTERIM (foundation): the mapping engineer replaces this file.
#include "xml/from_xml.hpp"

namespace rscene::xml {

FromXmlResult worldToScene(const Element& raisim, const FromXmlOptions&) {
  FromXmlResult r;
  r.diagnostics.push_back(elementDiagnostic(Severity::Error, "RS8110", raisim, "not converted yet"));
  return r;
}

}  // namespace rscene::xml
