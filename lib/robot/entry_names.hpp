// Joint names for a diff (rscene-diff, rscene.diff in Python): the entries of an articulated record's
// generalizedCoordinate and generalizedVelocity named from its robot model
// (lib/robot), filled into DiffOptions::entryNames so lib/core's diff stays
// free of robots.
#pragma once
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/document.hpp"
#include "robot/load.hpp"
#include "scene/scene.hpp"

namespace rscene::robot {

class EntryNames {
 public:
  // `sceneDir`: where each side's robot files resolve from (its scene's
  // directory; in git's mode the repository path's, the old side being a
  // temporary file).
  void addSide(const Document& doc, std::string sceneDir);

  // Names of the entries of `field` of record `record` of `doc`; empty when
  // it is no articulated record's coordinate or velocity, or its model
  // cannot be read (the diff then names entries by index and says nothing
  // about the model: that is rscene-validate --check-files' job).
  std::vector<std::string> operator()(const Document& doc, std::size_t record, std::string_view field);

 private:
  struct Side {
    std::string sceneDir;
    std::unique_ptr<Scene> scene;  // built on the first question
    std::map<std::size_t, const Articulated*> byRecord;
  };
  std::map<const Document*, Side> sides_;
  ModelCache models_;
};

}  // namespace rscene::robot
