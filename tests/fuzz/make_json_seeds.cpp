// make_json_seeds OUT_DIR SCENE...: writes the JSON form of each scene that
// loads to OUT_DIR/seed_NAME.json, the seed corpus of fuzz_from_json.  Not
// a fuzz target: run.sh calls it before fuzzing.
#include <cstdio>
#include <string>

#include "core/io.hpp"
#include "core/json.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: make_json_seeds OUT_DIR SCENE...\n");
    return 2;
  }
  int written = 0;
  for (int i = 2; i < argc; ++i) {
    rscene::Document doc;
    if (!rscene::loadFile(argv[i], doc)) continue;
    std::string name = argv[i];
    name = name.substr(name.rfind('/') + 1);
    if (rscene::writeFileAtomic(std::string(argv[1]) + "/seed_" + name + ".json",
                                [&](rscene::Sink& s) { rscene::writeJson(doc, s); return true; }, nullptr))
      ++written;
  }
  std::printf("%d JSON seeds\n", written);
  return 0;
}
