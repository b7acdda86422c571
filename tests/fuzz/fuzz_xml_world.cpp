// libFuzzer target (tests/fuzz/run.sh): rscene-from-xml's front end on
// arbitrary bytes: reading, includes, parameters, arrays, expressions,
// exist, object_class.  Besides crashes, leaks and timeouts it checks what
// a successful expansion promises: no template element, no `exist`, no
// `@@` and no brace is left in the tree.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "xml/xml_tree.hpp"

namespace {

void check(const rscene::xml::Element& e) {
  if (e.name == "array" || e.name == "include" || e.name == "params" || e.name == "object_class") std::abort();
  for (const rscene::xml::Attribute& a : e.attributes)
    if (a.name == "exist" || a.value.find("@@") != std::string::npos ||
        a.value.find_first_of("{}") != std::string::npos)
      std::abort();
  for (const rscene::xml::Element& c : e.children) check(c);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rscene::xml::LoadOptions options;
  // Small limits keep each input fast; the limits themselves are what is tested.
  options.limits.maxElements = 20000;
  options.limits.maxLoopIterations = 20000;
  options.limits.maxFileBytes = 1 << 20;
  options.limits.maxExpandedBytes = 4 << 20;
  options.params = {{"n", "3"}, {"on", "true"}};
  rscene::xml::LoadResult r = rscene::xml::loadWorldText(
      std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.xml", "/nonexistent/fuzz", options);
  if (r.ok()) check(*r.root);
  return 0;
}
