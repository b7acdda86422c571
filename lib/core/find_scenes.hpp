// The scenes under a folder, for tools given a directory operand
// (`rscene-fmt --check .`, `rscene-validate scenes/`), the way black and
// prettier walk theirs.  File-system access only: nothing here prints or
// reads the environment.
#pragma once
#include <string>
#include <vector>

namespace rscene {

struct SceneSearch {
  std::vector<std::string> files;   // `dir` joined with the relative path of each scene
  std::vector<std::string> errors;  // "cannot read directory 'x': Permission denied"
};

// Every regular file (or link to one) named *.rscene under `dir`, in a
// fixed order: entries sorted by name (bytewise) in each folder, a folder's
// scenes where its name sorts.  Names starting with `.` are skipped (hidden
// folders such as .git, editor backups); links to folders are not followed,
// so a link loop cannot make the walk endless.  An unreadable folder is an
// error; the walk goes on with the rest.
SceneSearch findScenes(const std::string& dir);

}  // namespace rscene
