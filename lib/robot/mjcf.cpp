// MJCF loading (load.hpp): MuJoCo's own compiler reads the file, so
// defaults, classes, fromto, includes, angle units and inertia from geoms
// behave exactly as MuJoCo users expect; the compiled mjModel is then read
// into the robot model (mjcf_convert.cpp).
//
// MuJoCo keeps process-wide state: the error and warning handlers (whose
// defaults print, write MUJOCO_LOG.TXT and exit) and, in 2.2.2, a global
// XML parser.  One lock serialises every load here, and the handlers are
// replaced for its duration, so the library never prints and never exits.
#include <mujoco/mujoco.h>

#include <array>
#include <cstring>
#include <memory>
#include <cctype>
#include <filesystem>
#include <mutex>
#include <regex>
#include <stdexcept>
#include <string>

#include "core/assets.hpp"
#include "robot/load.hpp"
#include "robot/mjcf.hpp"

namespace rscene::robot {
namespace {

std::mutex& mujocoLock() {
  static std::mutex m;
  return m;
}

// Warnings MuJoCo raises outside its compiler (which keeps its own) while
// the lock is held.
std::string* g_warnings = nullptr;

void collectWarning(const char* message) {
  if (g_warnings && message) *g_warnings += std::string(g_warnings->empty() ? "" : "; ") + message;
}

// mju_error must not return (MuJoCo continues as if it had exited): throw,
// and the load reports it.  The compiler installs its own handler while it
// runs, so this only guards what MuJoCo does around it.
[[noreturn]] void throwError(const char* message) { throw std::runtime_error(message ? message : "mujoco error"); }

class HandlerScope {
 public:
  explicit HandlerScope(std::string& warnings)
      : error_(mju_user_error), warning_(mju_user_warning) {
    g_warnings = &warnings;
    mju_user_error = throwError;
    mju_user_warning = collectWarning;
  }
  ~HandlerScope() {
    mju_user_error = error_;
    mju_user_warning = warning_;
    g_warnings = nullptr;
  }
  HandlerScope(const HandlerScope&) = delete;
  HandlerScope& operator=(const HandlerScope&) = delete;

 private:
  void (*error_)(const char*);
  void (*warning_)(const char*);
};

// MuJoCo's messages are several lines ("Error: ...\nElement 'geom', line
// 7"); ours are one line, lower-case, with no final period.
std::string oneLine(const std::string& text) {
  std::string out;
  bool newline = false, space = false;
  for (char c : text) {
    if (c == '\n' || c == '\r') {
      newline = true;
    } else if (c == ' ' || c == '\t') {
      space = true;
    } else {
      if (!out.empty() && newline) out += out.back() == ',' || out.back() == ':' ? " " : "; ";
      else if (!out.empty() && space) out += ' ';
      newline = space = false;
      out += c;
    }
  }
  for (bool again = true; again;) {
    again = false;
    for (const char* prefix : {"Error: ", "XML Error: ", "Warning: "})
      if (out.rfind(prefix, 0) == 0) {
        out.erase(0, std::char_traits<char>::length(prefix));
        again = true;
      }
  }
  while (!out.empty() && (out.back() == '.' || out.back() == ';')) out.pop_back();
  if (!out.empty()) out[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(out[0])));
  return out;
}

// The line MuJoCo names: "line 7", "line = 7" or tinyxml2's "Line number=7".
std::uint32_t lineOf(const std::string& text) {
  static const std::regex line(R"([Ll]ine(?: number)?\s*=?\s*(\d{1,9}))");
  std::smatch m;
  if (!std::regex_search(text, m, line)) return 0;
  return static_cast<std::uint32_t>(std::stoul(m[1].str()));
}

// A stand-in for a mesh file that is not there: a tetrahedron of 1 mm
// edges (MuJoCo needs a volume), in the file's format by its extension;
// empty for a format MuJoCo 2.2.2 reads that has none here (.msh).
std::string placeholderMesh(const std::string& file) {
  std::string ext = std::filesystem::path(file).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  static const float v[4][3] = {{0, 0, 0}, {1e-3f, 0, 0}, {0, 1e-3f, 0}, {0, 0, 1e-3f}};
  static const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  if (ext == ".stl") {
    std::string stl(84 + 4 * 50, '\0');
    const std::uint32_t n = 4;
    std::memcpy(&stl[80], &n, 4);
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) std::memcpy(&stl[84 + i * 50 + 12 + k * 12], v[f[i][k]], 12);
    return stl;
  }
  if (ext == ".obj")
    return "v 0 0 0\nv 0.001 0 0\nv 0 0.001 0\nv 0 0 0.001\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  return {};
}

struct VfsDeleter {
  void operator()(mjVFS* v) const {
    mj_deleteVFS(v);
    delete v;
  }
};

}  // namespace

bool loadMjcf(const std::string& path, const LoadOptions& options, Model& out, Diagnostics& diagnostics) {
  out = Model{};
  out.sourceFile = path;
  auto fail = [&](const char* code, const std::string& file, int line, std::string message) {
    Diagnostic d;
    d.severity = Severity::Error;
    d.code = code;
    d.line = static_cast<std::uint32_t>(line);
    d.message = std::move(message);
    d.file = file;
    diagnostics.push_back(std::move(d));
    return false;
  };
  // The file and every file it names: regular files under the cap, so
  // MuJoCo never reads a FIFO, a device or a huge file.
  auto check = [&](const std::string& file, const std::string& from, int line, const char* what) {
    std::error_code ec;
    if (!fileExistsOnDisk(file)) {
      if (from.empty() || whyNotAFile(file) != "does not exist")
        return fail(code::kMissingFile, from.empty() ? file : from, line,
                    std::string(what) + " '" + file + "' " + whyNotAFile(file));
      return true;  // missing: MuJoCo's message names it
    }
    auto bytes = std::filesystem::file_size(file, ec);
    if (ec) return fail(code::kMissingFile, from.empty() ? file : from, line,
                        std::string(what) + " '" + file + "' cannot be read: " + ec.message());
    if (bytes > options.maxFileBytes)
      return fail(code::kBadFile, from.empty() ? file : from, line,
                  std::string(what) + " '" + file + "' is " + std::to_string(bytes) + " bytes, over the cap of " +
                      std::to_string(options.maxFileBytes));
    return true;
  };
  if (!check(path, "", 0, "robot file")) return false;
  const MjcfFiles named = scanMjcf(path, options.maxFileBytes);
  for (const MjcfFiles::Named& f : named.files)
    if (!check(f.path, f.from, f.line, "file")) return false;
  // Mesh files that do not exist: as in a URDF, a mesh only drawn is left
  // out with a warning, and one that collides is an error (a warning with
  // --allow-missing-assets, and it is left out).  MuJoCo needs every file
  // to compile, so each gets a stand-in in a virtual file system; the
  // geoms using it are skipped by the conversion (the file cannot be read).
  struct Missing {
    std::string name;  // the mesh's name
    const MjcfFiles::Named* named;
  };
  std::vector<Missing> missing;
  std::unique_ptr<mjVFS, VfsDeleter> vfs;
  for (const auto& [mesh, file] : named.meshes) {
    if (fileExistsOnDisk(file) || whyNotAFile(file) != "does not exist") continue;
    std::string stand = placeholderMesh(file);
    if (stand.empty()) continue;  // MuJoCo's own message names it
    const MjcfFiles::Named* where = nullptr;
    for (const MjcfFiles::Named& f : named.files)
      if (f.path == file) where = &f;
    if (!vfs) {
      vfs.reset(new mjVFS);
      mj_defaultVFS(vfs.get());
    }
    const std::string base = std::filesystem::path(file).filename().string();
    if (mj_findFileVFS(vfs.get(), base.c_str()) < 0) {
      if (mj_makeEmptyFileVFS(vfs.get(), base.c_str(), static_cast<int>(stand.size())) != 0) continue;
      std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), base.c_str())], stand.data(), stand.size());
    }
    missing.push_back({mesh, where});
  }
  if (named.tooDeep) return fail(code::kBadFile, path, 0, "includes nested too deep or too many included files");
  if (!named.overCaps.empty()) {
    for (const MjcfFiles::OverCap& o : named.overCaps) fail(code::kMjcfOverCap, o.file, o.line, o.message);
    return false;
  }
  if (named.compositeLine > 0)
    return fail(code::kMjcfUnsupported, named.compositeFile, named.compositeLine,
                "<composite> is not read: MuJoCo expands it into as many bodies as its count asks, "
                "which a robot model has no use for");

  std::lock_guard<std::mutex> lock(mujocoLock());
  std::string warnings;
  HandlerScope handlers(warnings);
  std::array<char, 2048> error{};
  mjModel* m = nullptr;
  try {
    m = mj_loadXML(path.c_str(), vfs.get(), error.data(), static_cast<int>(error.size()));
  } catch (const std::exception& e) {
    if (m) mj_deleteModel(m);
    return fail(code::kBadFile, path, 0, "mujoco failed on the model: " + oneLine(e.what()));
  }
  std::string text(error.data());
  if (!m) {
    if (text.empty()) text = "MuJoCo's compiler refused the model";
    return fail(code::kBadFile, path, static_cast<int>(lineOf(text)), oneLine(text));
  }
  // On success the buffer holds the compiler's warning, if any.
  if (!text.empty()) warnings += std::string(warnings.empty() ? "" : "; ") + text;
  if (!warnings.empty()) {
    Diagnostic d;
    d.severity = Severity::Warning;
    d.code = code::kMjcfApproximated;
    d.line = lineOf(warnings);
    d.message = "mujoco's compiler warns: " + oneLine(warnings);
    d.file = path;
    diagnostics.push_back(std::move(d));
  }
  if (!options.modules.empty()) {
    Diagnostic d;
    d.severity = Severity::Warning;
    d.code = code::kSkipped;
    d.message = "modules= are URDF fragments; they are not inserted into an MJCF model";
    d.file = path;
    diagnostics.push_back(std::move(d));
  }
  bool missingCollision = false;
  for (const Missing& x : missing) {
    const int id = mj_name2id(m, mjOBJ_MESH, x.name.c_str());
    bool collides = false;
    for (int g = 0; g < m->ngeom; ++g)
      collides = collides || (m->geom_type[g] == mjGEOM_MESH && m->geom_dataid[g] == id &&
                              (m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0));
    const std::string file = named.meshes.at(x.name);
    Diagnostic d;
    d.file = x.named ? x.named->from : path;
    d.line = x.named ? static_cast<std::uint32_t>(x.named->line) : 0;
    if (collides && !options.allowMissingMeshes) {
      d.severity = Severity::Error;
      d.code = code::kMissingFile;
      d.message = "collision mesh '" + file + "' not found (mesh '" + x.name + "')";
      missingCollision = true;
    } else {
      d.severity = Severity::Warning;
      d.code = collides ? code::kMissingFile : code::kSkipped;
      d.message = std::string(collides ? "collision" : "visual") + " mesh '" + file + "' not found (mesh '" + x.name +
                  "'): its geoms are left out";
    }
    diagnostics.push_back(std::move(d));
  }
  if (missingCollision) {
    mj_deleteModel(m);
    return false;
  }
  bool ok = convertMjcf(*m, path, named.meshes, out, diagnostics);
  mj_deleteModel(m);
  return ok;
}

}  // namespace rscene::robot
