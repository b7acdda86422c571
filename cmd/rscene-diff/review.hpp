// rscene-diff --review DIR: a folder a reviewer reads beside a pull
// request.  before.png and after.png (both scenes from one camera, drawn
// on one OpenGL context), changes.png (the new scene with the changed
// parts marked from the renderer's id pass), review.md (GitHub Markdown:
// a summary line and a table per folder of changed records) and
// index.html (one self-contained page: the table and a before/after
// toggle and slider, images inline).
#pragma once
#include <string>
#include <string_view>

#include "common/cli.hpp"
#include "core/diff.hpp"
#include "core/document.hpp"

namespace rscene::diffout {

// The fixed names of what --review writes.
inline constexpr const char* kReviewFiles[] = {"before.png", "after.png", "changes.png", "review.md", "index.html"};

struct ReviewOptions {
  std::string dir;
  std::string camera;         // "" (the scenes' shared camera, else "changes"), "auto", "changes", a path or id
  int width = 0, height = 0;  // 0: the camera's, else 1280x720
  std::string backend = "auto";
};

// One side of the diff as main.cpp read it.
struct ReviewSide {
  const cli::Input& input;
  const Document& document;
  std::string_view text;
  std::string name;     // in messages and on the page
  bool empty = false;   // /dev/null: no scene on this side
};

// Makes DIR (and its parents) or checks that it is a folder (a file or a
// symbolic link there is refused): before anything is read or drawn.
// Prints the error; false on failure.
bool prepareReviewDir(const std::string& dir);

// Draws both scenes and writes the five files; prints its errors.  The
// exit status: 0 when `result` is the same, 1 when not, 2 on an error.
int writeReview(const ReviewOptions& options, const ReviewSide& before, const ReviewSide& after,
                const DiffResult& result);

// A side did not parse: review.md and index.html hold the line diff
// `lines` (no images).  Returns 2 (the error was printed), or 2 on a
// write failure as well.
int writeLineReview(const ReviewOptions& options, const std::string& oldName, const std::string& newName,
                    const std::string& lines);

// The pages, for tests.  `images`: whether the PNGs were drawn;
// `lineDiff`: a side did not parse, these lines are shown instead.
std::string reviewMarkdown(const std::string& oldName, const std::string& newName, const DiffResult& result,
                           bool images, const std::string& note, const std::string& lineDiff = "");
std::string reviewHtml(const std::string& oldName, const std::string& newName, const DiffResult& result,
                       const std::string& beforePng, const std::string& afterPng, const std::string& changesPng,
                       const std::string& note, const std::string& lineDiff);

}  // namespace rscene::diffout
