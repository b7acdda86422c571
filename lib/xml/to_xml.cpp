// INTERIM (foundation): the export engineer replaces this file.
#include "xml/to_xml.hpp"

namespace rscene::xml {

ToXmlResult sceneToXml(const Document&, const Scene&, const ToXmlOptions&) {
  ToXmlResult r;
  Diagnostic d;
  d.code = "RS8130";
  d.message = "not exported yet";
  r.diagnostics.push_back(d);
  return r;
}

}  // namespace rscene::xml
