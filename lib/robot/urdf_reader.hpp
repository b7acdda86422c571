// Internal to the URDF loader (urdf.cpp reads elements, urdf_tree.cpp joins
// them into the model): links and joints as read, with the names of the
// links a joint joins, before the tree is checked and indexed.
#pragma once
#include <tinyxml2.h>

#include <string>
#include <vector>

#include "core/diagnostic.hpp"
#include "robot/load.hpp"
#include "robot/model.hpp"

namespace rscene::robot::urdf {

struct RawJoint {
  Joint joint;  // parentLink/childLink not set yet
  std::string parent, child;
  bool floating = false;  // type="floating": only allowed between `world` and the base
};

// The file the model's lines refer to is `sourceFile`; a link or joint from
// a module has its own `file`.  Returns false after an RS7032 error: no
// link, duplicate names, a joint to an unknown link, a link with two
// parents, no root or two roots, a cycle, a floating joint below the root.
bool buildTree(const std::string& sourceFile, std::vector<Link> links, std::vector<RawJoint> joints, Model& out,
               Diagnostics& diagnostics);

// The URDF `doc`, already parsed from `path`, and the modules `options`
// names; no scaling (loadModel scales).
bool loadDocument(const std::string& path, const tinyxml2::XMLDocument& doc, const LoadOptions& options,
                  Model& out, Diagnostics& diagnostics);

}  // namespace rscene::robot::urdf
