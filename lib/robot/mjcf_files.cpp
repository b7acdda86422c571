// What an MJCF file names besides itself (mjcf.hpp): the files it includes
// and the asset files MuJoCo will read, looked at before MuJoCo reads them,
// and the mesh geoms' files and frames after.
//
// Before: MuJoCo reads whatever a model names, without a size cap, and a
// FIFO or a device named as a mesh would never end; a <composite> expands
// to as many bodies as its count asks (100 x 100 takes MuJoCo 2.2.2 about
// 20 s).  So the file and its includes are scanned first (tinyxml2):
// named files must be regular files under the cap, composites are refused.
//
// After: MuJoCo 2.2.2's compiled model keeps a mesh's vertices but not its
// file, and it has moved the vertices: scaled (mesh scale, refpos/refquat)
// and re-expressed in the mesh's inertial frame, with the geom's pose
// compensating.  The robot model names mesh files that the renderer and
// simulator read themselves, so two things are recovered:
//   - the file: <asset><mesh file=> of the model and its includes, resolved
//     as MuJoCo does (compiler meshdir, else assetdir, relative to the main
//     file's directory; absolute paths as written);
//   - the frame: the file compiled alone by MuJoCo (an in-memory model in a
//     virtual file system) gives the file's vertices in a frame MuJoCo
//     knows; the affine map from those to the model's compiled vertices,
//     fitted over all vertices (same file, same processing, same order), is
//     a rotation times a diagonal scale plus a translation: exactly the
//     visual's origin and meshScale.
#include <mujoco/mujoco.h>
#include <tinyxml2.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>

#include "core/assets.hpp"
#include "robot/mjcf.hpp"

namespace rscene::robot {
namespace {

namespace fs = std::filesystem;

struct Scan {
  std::string meshdir, texturedir, assetdir;
  bool haveMeshdir = false, haveTexturedir = false;
  struct Asset {
    std::string tag, name, file, from;  // from: the XML file that names it
    int line = 0;
  };
  std::vector<Asset> assets;
  MjcfFiles out;
  std::uintmax_t maxFileBytes = 0;
};

// Include depth and file count caps: MuJoCo refuses a repeated include
// itself; these only bound this scan.
constexpr int kMaxIncludeDepth = 16;
constexpr int kMaxIncludedFiles = 256;

// MuJoCo 2.2.2's allocations that a few bytes of XML can ask for (RS7053).
// <size>: nuser_* values per element (x elements), nkey keyframes (MuJoCo
// takes time quadratic in them: 100000 took 30 s), njmax (mjData holds a
// dense njmax x njmax matrix: 8000 took 764 MB), nconmax contacts (~600
// bytes each), nstack and nuserdata numbers (8 bytes each).  Height fields
// and textures: samples (4096 x 4096 = 16.8 M; a 20000 x 20000 height
// field took 3 GB and 16 s, a cube texture counts six faces).
struct SizeCap {
  const char* attribute;
  double cap;
};
constexpr SizeCap kSizeCaps[] = {
    {"nuser_body", 1000},  {"nuser_jnt", 1000},   {"nuser_geom", 1000},      {"nuser_site", 1000},
    {"nuser_cam", 1000},   {"nuser_tendon", 1000}, {"nuser_actuator", 1000}, {"nuser_sensor", 1000},
    {"nkey", 1000},        {"njmax", 4000},        {"nconmax", 100000},      {"nstack", 1e7},
    {"nuserdata", 1e6},
};
constexpr double kMaxSamples = 4096.0 * 4096.0;

std::string whole(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.0f", v);
  return buf;
}

// A number MuJoCo would read as a count (it reads a leading integer; a
// value that is not one is left to its own message).
bool countOf(const tinyxml2::XMLElement* e, const char* attribute, double& out) {
  const char* text = e->Attribute(attribute);
  if (!text) return false;
  char* end = nullptr;
  out = std::strtod(text, &end);
  return end != text && std::isfinite(out);
}

// Width and height from a PNG file's header; false when it is not a PNG.
bool pngSize(const fs::path& file, double& width, double& height) {
  std::FILE* f = std::fopen(file.string().c_str(), "rb");
  if (!f) return false;
  unsigned char h[24];
  std::size_t n = std::fread(h, 1, sizeof h, f);
  std::fclose(f);
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (n < sizeof h || std::memcmp(h, kSignature, 8) != 0) return false;
  auto be32 = [&](int at) {
    return double((std::uint32_t(h[at]) << 24) | (std::uint32_t(h[at + 1]) << 16) | (std::uint32_t(h[at + 2]) << 8) |
                  std::uint32_t(h[at + 3]));
  };
  width = be32(16);
  height = be32(20);
  return true;
}

void overCap(Scan& scan, const std::string& file, const tinyxml2::XMLElement* e, std::string message);

void checkSize(const tinyxml2::XMLElement* e, const std::string& file, Scan& scan) {
  for (const SizeCap& c : kSizeCaps) {
    double v = 0;
    if (countOf(e, c.attribute, v) && v > c.cap)
      overCap(scan, file, e,
              std::string("<size ") + c.attribute + "=\"" + e->Attribute(c.attribute) + "\"> is over the cap of " +
                  whole(c.cap) + ": MuJoCo would allocate it while it compiles the model");
  }
}

// A height field's nrow x ncol, a builtin texture's width x height (a cube
// or skybox: six width x width faces).
void checkSamples(const tinyxml2::XMLElement* e, const std::string& file, Scan& scan) {
  const std::string tag = e->Name();
  double a = 0, b = 0, samples = 0;
  std::string what;
  if (tag == "hfield" && countOf(e, "nrow", a) && countOf(e, "ncol", b)) {
    samples = a * b;
    what = "nrow x ncol = " + whole(a) + " x " + whole(b);
  } else if (tag == "texture" && e->Attribute("builtin") && std::strcmp(e->Attribute("builtin"), "none") != 0) {
    const char* type = e->Attribute("type");
    const bool cube = type && (std::strcmp(type, "cube") == 0 || std::strcmp(type, "skybox") == 0);
    if (!countOf(e, "width", a)) return;
    if (cube) {
      samples = 6 * a * a;
      what = "6 faces of width x width = " + whole(a) + " x " + whole(a);
    } else if (countOf(e, "height", b)) {
      samples = a * b;
      what = "width x height = " + whole(a) + " x " + whole(b);
    }
  }
  if (samples > kMaxSamples)
    overCap(scan, file, e,
            "<" + tag + "> " + what + " samples is over the cap of 4096 x 4096: MuJoCo would allocate them");
}

void overCap(Scan& scan, const std::string& file, const tinyxml2::XMLElement* e, std::string message) {
  scan.out.overCaps.push_back({file, e->GetLineNum(), std::move(message)});
}

void scanElement(const tinyxml2::XMLElement* e, const std::string& file, const fs::path& modelDir, Scan& scan,
                 int depth);

void scanFile(const fs::path& file, const fs::path& modelDir, Scan& scan, int depth) {
  if (depth > kMaxIncludeDepth || static_cast<int>(scan.out.files.size()) > kMaxIncludedFiles) {
    scan.out.tooDeep = true;
    return;
  }
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(file.string().c_str()) != tinyxml2::XML_SUCCESS) return;  // MuJoCo says why
  if (const tinyxml2::XMLElement* root = doc.RootElement()) scanElement(root, file.string(), modelDir, scan, depth);
}

void scanElement(const tinyxml2::XMLElement* e, const std::string& file, const fs::path& modelDir, Scan& scan,
                 int depth) {
  for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "compiler") {
      if (const char* d = c->Attribute("meshdir")) {
        scan.meshdir = d;
        scan.haveMeshdir = true;
      }
      if (const char* d = c->Attribute("texturedir")) {
        scan.texturedir = d;
        scan.haveTexturedir = true;
      }
      if (const char* d = c->Attribute("assetdir")) scan.assetdir = d;
    } else if (tag == "include") {
      if (const char* name = c->Attribute("file")) {
        fs::path included = modelDir / name;
        scan.out.files.push_back({included.lexically_normal().string(), file, c->GetLineNum()});
        // Only a regular file under the cap is read (loadMjcf reports the rest).
        std::error_code ec;
        if (fileExistsOnDisk(included.string()) && fs::file_size(included, ec) <= scan.maxFileBytes && !ec)
          scanFile(included, modelDir, scan, depth + 1);
      }
    } else if (tag == "size") {
      checkSize(c, file, scan);
    } else if (tag == "composite") {
      if (scan.out.compositeLine == 0) {
        scan.out.compositeFile = file;
        scan.out.compositeLine = c->GetLineNum();
      }
    } else {
      if (std::strcmp(e->Name(), "asset") == 0) checkSamples(c, file, scan);
      if (const char* name = c->Attribute("file"); name && std::strcmp(e->Name(), "asset") == 0) {
        const char* given = c->Attribute("name");
        scan.assets.push_back({tag, given ? given : fs::path(name).stem().string(), name, file, c->GetLineNum()});
      }
      scanElement(c, file, modelDir, scan, depth);
    }
  }
}

struct VfsDeleter {
  void operator()(mjVFS* v) const {
    mj_deleteVFS(v);
    delete v;
  }
};

}  // namespace

MjcfFiles scanMjcf(const std::string& path, std::uintmax_t maxFileBytes) {
  fs::path modelDir = fs::path(path).parent_path();
  Scan scan;
  scan.maxFileBytes = maxFileBytes;
  scanFile(path, modelDir, scan, 0);
  // Meshes, height fields and skins in meshdir, textures in texturedir;
  // either defaults to assetdir.
  const std::string meshdir = scan.haveMeshdir ? scan.meshdir : scan.assetdir;
  const std::string texturedir = scan.haveTexturedir ? scan.texturedir : scan.assetdir;
  for (const Scan::Asset& a : scan.assets) {
    fs::path p = a.file;
    if (p.is_relative()) p = modelDir / (a.tag == "texture" ? texturedir : meshdir) / p;
    const std::string resolved = p.lexically_normal().string();
    scan.out.files.push_back({resolved, a.from, a.line});
    // A PNG texture or height field: its header's size, before MuJoCo
    // decodes it (a few kilobytes can say 100000 x 100000).
    double w = 0, h = 0;
    if ((a.tag == "texture" || a.tag == "hfield") && fileExistsOnDisk(resolved) && pngSize(p, w, h) &&
        w * h > kMaxSamples)
      scan.out.overCaps.push_back({a.from, a.line,
                                   "<" + a.tag + "> file '" + a.file + "' is a PNG of " + whole(w) + " x " + whole(h) +
                                       " pixels, over the cap of 4096 x 4096: MuJoCo would decode it whole"});
    if (a.tag == "mesh") scan.out.meshes[a.name] = resolved;
  }
  return std::move(scan.out);
}

bool mjcfMeshFrame(const std::string& file, const float* vertices, int count, Pose& frame, Eigen::Vector3d& scale,
                   std::string& why) {
  // The file alone: one mesh, one world geom at the identity, so the geom's
  // pose is the frame MuJoCo moved the file's vertices to.
  std::unique_ptr<mjVFS, VfsDeleter> vfs(new mjVFS);
  mj_defaultVFS(vfs.get());
  const fs::path p(file);
  const std::string name = p.filename().string();
  // MuJoCo 2.2.2 joins a directory argument oddly; the whole path works
  // and the file is stored under its name without the path.
  if (mj_addFileVFS(vfs.get(), "", file.c_str()) != 0) {
    why = "cannot read it";
    return false;
  }
  const std::string xml = "<mujoco><asset><mesh name=\"m\" file=\"" + name +
                          "\"/></asset><worldbody><geom type=\"mesh\" mesh=\"m\"/></worldbody></mujoco>";
  const char* modelName = "rscene_mesh_frame.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), modelName, static_cast<int>(xml.size())) != 0) {
    why = "the virtual file system is full";
    return false;
  }
  int index = mj_findFileVFS(vfs.get(), modelName);
  std::memcpy(vfs->filedata[index], xml.data(), xml.size());
  char error[512] = "";
  mjModel* alone = mj_loadXML(modelName, vfs.get(), error, sizeof error);
  if (!alone) {
    why = std::string("MuJoCo refuses it alone: ") + error;
    return false;
  }
  std::unique_ptr<mjModel, void (*)(mjModel*)> guard(alone, mj_deleteModel);
  if (alone->nmesh != 1 || alone->mesh_vertnum[0] != count || count < 4) {
    why = "MuJoCo reads it differently alone";
    return false;
  }
  // File vertex v = M0 * c0 (c0: compiled alone); the model's compiled
  // vertex c1 = A c0 + b, fitted by least squares about the centroids.
  const Pose m0{Eigen::Vector3d(alone->geom_pos[0], alone->geom_pos[1], alone->geom_pos[2]),
                Eigen::Quaterniond(alone->geom_quat[0], alone->geom_quat[1], alone->geom_quat[2], alone->geom_quat[3])
                    .normalized()};
  Eigen::Matrix3Xd c0(3, count), c1(3, count);
  for (int i = 0; i < count; ++i) {
    c0.col(i) = Eigen::Vector3f(alone->mesh_vert + 3 * i).cast<double>();
    c1.col(i) = Eigen::Vector3f(vertices + 3 * i).cast<double>();
  }
  const Eigen::Vector3d mean0 = c0.rowwise().mean(), mean1 = c1.rowwise().mean();
  const Eigen::Matrix3Xd d0 = c0.colwise() - mean0, d1 = c1.colwise() - mean1;
  const Eigen::Matrix3d cov = d0 * d0.transpose();
  if (std::abs(cov.determinant()) < 1e-30) {
    why = "it is flat";
    return false;
  }
  const Eigen::Matrix3d a = (d1 * d0.transpose()) * cov.inverse();
  const Eigen::Vector3d b = mean1 - a * mean0;
  double size = std::max(d1.cwiseAbs().maxCoeff(), 1e-12);
  double residual = ((a * c0).colwise() + b - c1).cwiseAbs().maxCoeff();
  if (residual > 1e-4 * size) {
    why = "its vertices do not map onto the compiled ones (residual " + std::to_string(residual) + ")";
    return false;
  }
  // c1 = L v + t with L = A R0^T, t = b - L c0pos; L = Q diag(s).
  const Eigen::Matrix3d r0 = m0.orientation.toRotationMatrix();
  const Eigen::Matrix3d l = a * r0.transpose();
  const Eigen::Vector3d t = b - l * m0.position;
  scale = l.colwise().norm().transpose();
  if (scale.minCoeff() < 1e-12) {
    why = "its scale is zero";
    return false;
  }
  Eigen::Matrix3d q = l * scale.cwiseInverse().asDiagonal();
  if (q.determinant() < 0) {  // a mirroring scale: keep a rotation, mirror one axis
    scale.z() = -scale.z();
    q.col(2) = -q.col(2);
  }
  // Snap to the nearest rotation (the fit is as exact as float vertices).
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(q, Eigen::ComputeFullU | Eigen::ComputeFullV);
  q = svd.matrixU() * svd.matrixV().transpose();
  frame.position = t;
  frame.orientation = Eigen::Quaterniond(q).normalized();
  return true;
}

}  // namespace rscene::robot
