// Output patterns of a batch (`rscene-sim -o 'out/{stem}.rscene' scenes/`,
// `rscene-render -o 'thumbs/{stem}.png' scenes/`): the fields a scene
// file gives a pattern.  One place, so that every tool names a scene's
// outputs alike; a tool with fields of its own (rscene-render's {name},
// {frame}, ...) expands the scene's first and its own after.
#pragma once
#include <string>

namespace rscene {

struct SceneFields {
  std::string stem;  // the file name without .rscene ("warehouse" for "a/b/warehouse.rscene")
  std::string dir;   // the folder as given ("a/b"; "." for a bare name)
};

// The fields of the scene at `path` ("" or "-": standard input, stem "stdin").
SceneFields sceneFields(const std::string& path);

// Whether `pattern` uses {stem} or {dir}.
bool hasSceneFields(const std::string& pattern);

// `pattern` with {stem} and {dir} replaced and every other field, and the
// literal braces `{{` and `}}`, left as written; braces inside the values
// are doubled, so the result is still a pattern (for a second expansion).
std::string withSceneFields(const std::string& pattern, const SceneFields& fields);

// `pattern` with {stem} and {dir} replaced and `{{`, `}}` made braces: a
// whole path.  False with `error` on another field or an unmatched brace.
bool expandScenePattern(const std::string& pattern, const SceneFields& fields, std::string& out, std::string* error);

}  // namespace rscene
