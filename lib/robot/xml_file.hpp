// Reading a robot file (URDF, URDF module, MJCF) into a tinyxml2 document:
// one size-capped read through lib/core's file access (regular files only,
// so a FIFO or /dev/zero is refused instead of read without end), then the
// XML parse, each failure a diagnostic naming the file.
#pragma once
#include <tinyxml2.h>

#include "core/filesystem.hpp"

#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostic.hpp"

namespace rscene::robot {

// A diagnostic about `file` at `line` (0: the whole file).
Diagnostic robotDiagnostic(Severity severity, const char* code, const std::string& file, int line,
                           std::string message);

// Reads `path` (at most `maxBytes`) and parses it.  Returns false after an
// RS5001 (missing, not a regular file) or RS7030 (too large, unreadable,
// not well-formed XML) error.  A file that is not the robot file itself (a
// sensor set) names itself `what` and takes its own code for the second.
bool readXmlFile(const FileSystem& files, const std::string& path, std::size_t maxBytes, tinyxml2::XMLDocument& doc,
                 Diagnostics& diagnostics, const char* what = "robot file", const char* badFileCode = nullptr);

// An XML declaration (<?xml ...?>) after a comment or another node of the
// prolog is not well-formed and tinyxml2 refuses it; RaiSim's parser reads
// such files (its ANYmal and cart-pole URDFs start with a comment).  Each
// such declaration is blanked in `text` (spaces, newlines kept, so lines
// stay) and its line returned, for a warning (RS7054).  Declarations before
// anything else, repeated or not, tinyxml2 reads itself.
std::vector<int> blankMisplacedDeclarations(std::string& text);

// True when `text` holds something a preprocessor should have replaced:
// xacro's ${...} and $(...), RaiSim template variables @@NAME.
bool looksLikeTemplate(const char* text);

// One finite number as XML attributes write it (a leading '+' allowed).
bool parseXmlNumber(std::string_view token, double& out);
// Whitespace-separated finite numbers; false when one is not.
bool parseXmlNumbers(const char* text, std::vector<double>& out);

// URDF's <origin rpy>: fixed-axis roll, pitch, yaw, R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Quaterniond rpyToQuaternion(double roll, double pitch, double yaw);

}  // namespace rscene::robot
