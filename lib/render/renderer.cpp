#include "render/renderer.hpp"

#include "core/assets.hpp"

#include <GL/glcorearb.h>

#include <chrono>
#include <cstring>
#include <cmath>
#include <map>
#include <memory>
#include <tuple>

#include "asset/cache.hpp"
#include "render/camera.hpp"
#include "render/mesh.hpp"
#include "render/shaders.hpp"

namespace rscene::render {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kInstanceFloats = 28;  // model (16), color (4), pbr (4), emissive (4)
constexpr int kMaxLights = 8;
constexpr int kShadowSize = 2048;
// llvmpipe pays for every shadow texel it rasterises; 1024 keeps the same
// shadows at CPU-backend thumbnail sizes.
constexpr int kSoftwareShadowSize = 1024;

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

GLuint compile(GLenum type, const char* source, std::string& log) {
  GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char buf[2048];
    glGetShaderInfoLog(s, sizeof buf, nullptr, buf);
    log += buf;
  }
  return s;
}

GLuint program(const char* vs, const char* fs, std::string& log) {
  GLuint p = glCreateProgram();
  GLuint a = compile(GL_VERTEX_SHADER, vs, log), b = compile(GL_FRAGMENT_SHADER, fs, log);
  glAttachShader(p, a);
  glAttachShader(p, b);
  glLinkProgram(p);
  glDeleteShader(a);
  glDeleteShader(b);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char buf[2048];
    glGetProgramInfoLog(p, sizeof buf, nullptr, buf);
    log += buf;
    return 0;
  }
  return p;
}

GLint loc(GLuint p, const char* name) { return glGetUniformLocation(p, name); }
void setMat(GLuint p, const char* name, const Eigen::Matrix4d& m) {
  Eigen::Matrix4f f = m.cast<float>();
  glUniformMatrix4fv(loc(p, name), 1, GL_FALSE, f.data());
}
void setVec3(GLuint p, const char* name, const Eigen::Vector3f& v) { glUniform3f(loc(p, name), v.x(), v.y(), v.z()); }

struct GpuMesh {
  GLuint vbo = 0, ebo = 0, colorVbo = 0;
  GLsizei indexCount = 0;
};

struct TexturedPart {
  std::shared_ptr<GpuMesh> mesh;
  Eigen::Vector4f color;
  float metallic, roughness;
  GLuint texture;
};

struct Batch {
  std::shared_ptr<GpuMesh> mesh;
  GLuint texture = 0;
  bool blend = false, doubleSided = false, castShadow = true;
  std::vector<float> instances, outOfView;  // outOfView: cast shadows only
  GLuint vao = 0, instanceVbo = 0;
  GLsizei count = 0, inView = 0;  // the first inView instances are inside the camera's frustum
};

// What a texture or background image may cost: --max-texture-pixels
// (lib/asset refuses a larger declared size before decoding anything).
asset::AssetLimits assetLimits(const RenderOptions& o) {
  asset::AssetLimits l;
  l.image.maxPixels = o.maxTexturePixels;
  return l;
}

// Owns every GL object of one render; released in the destructor.
class Frame {
 public:
  Frame(const RenderScene& scene, const Camera& camera, const RenderOptions& options, Diagnostics& diags)
      : scene_(scene), opt_(options), diags_(diags), assets_(diskFileSystem(), assetLimits(options)) {
    aspect_ = double(options.width) / double(options.height);
    viewProj_ = projectionMatrix(camera, aspect_) * viewMatrix(camera);
    camera_ = camera;
  }
  ~Frame();
  bool prepare();
  bool draw(const Camera& camera, Image& out);

 private:
  void diag(Severity s, const char* code, std::uint32_t line, std::string message, std::uint32_t column = 0) {
    Diagnostic d;
    d.severity = s;
    d.code = code;
    d.line = line;
    d.column = column ? column : line ? 1 : 0;
    d.message = std::move(message);
    diags_.push_back(std::move(d));
  }
  // Missing (RS5001, the code validate --check-files and rscene-sim give the
  // same file) or unreadable (RS9001) asset: an error, or a warning when allowed.
  bool assetProblem(std::uint32_t line, std::uint32_t column, const std::string& message, const char* code = "RS9001") {
    diag(opt_.allowMissingAssets ? Severity::Warning : Severity::Error, code, line, message, column);
    return opt_.allowMissingAssets;
  }
  std::shared_ptr<GpuMesh> upload(const MeshData& m, const std::vector<Eigen::Vector4f>* colors = nullptr);
  std::shared_ptr<GpuMesh> primitive(Shape s, double capsuleR = 0, double capsuleH = 0, int segments = 48);
  // Segments around a round shape whose bounds are `box`: the polygon stays
  // within half a pixel of the circle at the size it is seen.
  int segmentsFor(const Eigen::AlignedBox3d& box) const;
  GLuint texture(const Image& image);
  GLuint texture(const std::shared_ptr<const Image>& image);  // one GL texture per loaded image
  bool materialTexture(const RenderMaterial& m, GLuint& out);
  const std::vector<TexturedPart>* meshFile(const std::string& path, std::uint32_t line, std::uint32_t column,
                                            bool& failed);
  void add(const std::shared_ptr<GpuMesh>& mesh, GLuint tex, bool blend, bool doubleSided, bool castShadow,
           const Eigen::Affine3d& world, const Eigen::Vector4f& color, const Eigen::Vector4f& pbr,
           const Eigen::Vector3f& emissive, bool inView = true);
  void buildLights();
  void finishBatches();
  void drawBatches(GLuint prog, bool blendPass, bool shadowPass);

  const RenderScene& scene_;
  const RenderOptions& opt_;
  Diagnostics& diags_;
  Camera camera_;
  double aspect_ = 1;
  Eigen::Matrix4d viewProj_;
  std::map<std::string, std::shared_ptr<GpuMesh>> primitives_;
  std::map<std::string, std::vector<TexturedPart>> meshFiles_;
  std::map<std::string, GLuint> textures_;
  std::map<const Image*, GLuint> imageTextures_;
  asset::AssetCache assets_;  // a mesh or texture named many times is read once
  std::vector<GLuint> ownedTextures_;
  std::vector<std::shared_ptr<GpuMesh>> meshes_;
  std::vector<Batch> batches_;
  std::map<std::tuple<GpuMesh*, GLuint, bool, bool, bool>, std::size_t> batchIndex_;
  std::vector<RenderLight> lights_;
  int shadowLight_ = -1;
  GLuint hdrTexture_ = 0;
  GLuint pointVao_ = 0, pointVbo_ = 0;
  std::vector<std::pair<GLint, GLsizei>> pointRanges_;
  std::vector<float> pointSizes_;
  std::vector<GLuint> programs_, fbos_, renderbuffers_;
  GLuint emptyVao_ = 0;
};

Frame::~Frame() {
  for (Batch& b : batches_) {
    glDeleteVertexArrays(1, &b.vao);
    glDeleteBuffers(1, &b.instanceVbo);
  }
  for (auto& m : meshes_) {
    glDeleteBuffers(1, &m->vbo);
    glDeleteBuffers(1, &m->ebo);
    if (m->colorVbo) glDeleteBuffers(1, &m->colorVbo);
  }
  if (!ownedTextures_.empty()) glDeleteTextures(GLsizei(ownedTextures_.size()), ownedTextures_.data());
  if (pointVao_) glDeleteVertexArrays(1, &pointVao_);
  if (pointVbo_) glDeleteBuffers(1, &pointVbo_);
  if (emptyVao_) glDeleteVertexArrays(1, &emptyVao_);
  for (GLuint p : programs_) glDeleteProgram(p);
  if (!fbos_.empty()) glDeleteFramebuffers(GLsizei(fbos_.size()), fbos_.data());
  if (!renderbuffers_.empty()) glDeleteRenderbuffers(GLsizei(renderbuffers_.size()), renderbuffers_.data());
}

std::shared_ptr<GpuMesh> Frame::upload(const MeshData& m, const std::vector<Eigen::Vector4f>* colors) {
  auto g = std::make_shared<GpuMesh>();
  glGenBuffers(1, &g->vbo);
  glBindBuffer(GL_ARRAY_BUFFER, g->vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(m.vertices.size() * sizeof(float)), m.vertices.data(), GL_STATIC_DRAW);
  glGenBuffers(1, &g->ebo);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g->ebo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(m.indices.size() * sizeof(std::uint32_t)), m.indices.data(),
               GL_STATIC_DRAW);
  if (colors) {
    glGenBuffers(1, &g->colorVbo);
    glBindBuffer(GL_ARRAY_BUFFER, g->colorVbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(colors->size() * sizeof(Eigen::Vector4f)), colors->data(),
                 GL_STATIC_DRAW);
  }
  g->indexCount = GLsizei(m.indices.size());
  meshes_.push_back(g);
  return g;
}

std::shared_ptr<GpuMesh> Frame::primitive(Shape s, double capsuleR, double capsuleH, int segments) {
  bool round = s == Shape::Sphere || s == Shape::Cylinder || s == Shape::Capsule;
  std::string key = std::to_string(int(s));
  if (round) key += "/" + std::to_string(segments);
  if (s == Shape::Capsule) key += ":" + std::to_string(capsuleR) + ":" + std::to_string(capsuleH);
  auto it = primitives_.find(key);
  if (it != primitives_.end()) return it->second;
  MeshData m = s == Shape::Sphere     ? unitSphere(segments, std::max(segments / 2, 4))
               : s == Shape::Cylinder ? unitCylinder(segments)
               : s == Shape::Capsule  ? capsule(capsuleR, capsuleH, segments)
               : s == Shape::Ground   ? unitPlane()
                                      : unitBox();
  return primitives_[key] = upload(m);
}

int Frame::segmentsFor(const Eigen::AlignedBox3d& box) const {
  double radius = 0.5 * box.sizes().maxCoeff();
  double pixels;  // radius on screen
  if (camera_.projection == "orthographic") {
    pixels = radius / std::max(camera_.orthoScale / 2, 1e-9) * opt_.height / 2;
  } else {
    double distance = (box.center() - camera_.world.position).norm() - radius;
    double t = std::tan(effectiveVerticalFov(camera_, aspect_) * 3.14159265358979 / 360);
    pixels = distance <= camera_.nearPlane ? 1e9 : radius / (distance * t) * opt_.height / 2;
  }
  // Sagitta r (1 - cos(pi / n)) ~ r pi^2 / (2 n^2) <= 0.5 px.
  double wanted = 3.14159265358979 * std::sqrt(std::max(pixels, 0.0));
  for (int n : {8, 12, 16, 24, 32})
    if (n >= wanted) return n;
  return 48;
}

GLuint Frame::texture(const Image& image) {
  GLuint t = 0;
  glGenTextures(1, &t);
  ownedTextures_.push_back(t);
  glBindTexture(GL_TEXTURE_2D, t);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               image.rgba.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return t;
}

GLuint Frame::texture(const std::shared_ptr<const Image>& image) {
  if (!image) return 0;
  auto [it, fresh] = imageTextures_.try_emplace(image.get(), 0);
  if (fresh) it->second = texture(*image);
  return it->second;
}

bool Frame::materialTexture(const RenderMaterial& m, GLuint& out) {
  out = 0;
  if (m.albedoTexture.empty()) return true;
  auto it = textures_.find(m.albedoTexture);
  if (it != textures_.end()) {
    out = it->second;
    return true;
  }
  textures_[m.albedoTexture] = 0;
  // Regular files only, as validate --check-files and rscene-sim (a FIFO
  // or /dev/zero is not an image).
  if (!fileExistsOnDisk(m.albedoTexture))
    return assetProblem(m.line, m.textureColumn, "texture file '" + m.albedoTexture + "' " + whyNotAFile(m.albedoTexture),
                        scene_code::kMissingFile);
  std::string err;
  std::shared_ptr<const Image> image = assets_.image(m.albedoTexture, &err);
  if (!image) {
    diag(Severity::Warning, "RS9002", m.line, "texture " + m.albedoTexture + " is not drawn: " + err);
    return true;
  }
  out = textures_[m.albedoTexture] = texture(image);
  return true;
}

const std::vector<TexturedPart>* Frame::meshFile(const std::string& path, std::uint32_t line, std::uint32_t column,
                                                 bool& failed) {
  failed = false;
  auto it = meshFiles_.find(path);
  if (it != meshFiles_.end()) return it->second.empty() ? nullptr : &it->second;
  std::vector<TexturedPart>& parts = meshFiles_[path];
  if (path.empty() || !fileExistsOnDisk(path)) {
    failed = !assetProblem(line, column,
                           path.empty() ? std::string("mesh body has no mesh file") : "mesh file '" + path + "' " + whyNotAFile(path),
                           path.empty() ? scene_code::kNoMesh : scene_code::kMissingFile);
    return nullptr;
  }
  std::string err;
  std::shared_ptr<const asset::Mesh> loaded = assets_.mesh(path, asset::MeshContent::Surface, &err);
  if (!loaded) {
    failed = !assetProblem(line, column, "cannot read mesh " + path + ": " + err);
    return nullptr;
  }
  for (const std::string& w : loaded->warnings) diag(Severity::Warning, "RS9002", line, w);
  for (const asset::MeshPart& p : loaded->parts)
    parts.push_back({upload(interleave(p)), Eigen::Vector4f(p.material.baseColor.data()), p.material.metallic,
                     p.material.roughness, texture(p.material.texture)});
  return &parts;
}

void Frame::add(const std::shared_ptr<GpuMesh>& mesh, GLuint tex, bool blend, bool doubleSided, bool castShadow,
                const Eigen::Affine3d& world, const Eigen::Vector4f& color, const Eigen::Vector4f& pbr,
                const Eigen::Vector3f& emissive, bool inView) {
  auto key = std::make_tuple(mesh.get(), tex, blend, doubleSided, castShadow);
  auto [it, inserted] = batchIndex_.emplace(key, batches_.size());
  if (inserted) {
    Batch b;
    b.mesh = mesh;
    b.texture = tex;
    b.blend = blend;
    b.doubleSided = doubleSided;
    b.castShadow = castShadow;
    batches_.push_back(std::move(b));
  }
  Batch& batch = batches_[it->second];
  std::vector<float>& v = inView ? batch.instances : batch.outOfView;
  Eigen::Matrix4f m = world.matrix().cast<float>();
  v.insert(v.end(), m.data(), m.data() + 16);
  v.insert(v.end(), color.data(), color.data() + 4);
  v.insert(v.end(), pbr.data(), pbr.data() + 4);
  v.insert(v.end(), {emissive.x(), emissive.y(), emissive.z(), 0.f});
}

bool Frame::prepare() {
  const Eigen::Vector4f placeholderColor(1.0f, 0.0f, 1.0f, 1.0f);  // magenta: cannot be mistaken for content
  auto pbrOf = [](const RenderMaterial& m, float checker) { return Eigen::Vector4f(m.metallic, m.roughness, checker, 0); };
  for (const Drawable& d : scene_.drawables) {
    const RenderMaterial& mat = scene_.materials[std::size_t(d.material)];
    bool inView = boxInFrustum(viewProj_, d.bounds);
    if (d.shape == Shape::Mesh) {
      bool failed = false;
      const std::vector<TexturedPart>* parts = meshFile(d.meshPath, d.line, d.meshColumn, failed);
      if (failed) return false;
      if (!parts) {
        add(primitive(Shape::Box), 0, false, false, true, d.world, placeholderColor, {0, 0.6f, 0, 1},
            Eigen::Vector3f::Zero(), inView);
        continue;
      }
      GLuint matTex = 0;
      if (!mat.isDefault && !materialTexture(mat, matTex)) return false;
      for (const TexturedPart& p : *parts) {
        bool own = mat.isDefault;
        Eigen::Vector4f color = own ? p.color : mat.color;
        Eigen::Vector4f pbr = own ? Eigen::Vector4f(p.metallic, p.roughness, 0, 0) : pbrOf(mat, 0);
        add(p.mesh, own ? p.texture : matTex, color.w() < 0.999f || (!own && mat.blend), mat.doubleSided,
            d.castShadow, d.world, color, pbr, mat.emissive, inView);
      }
      continue;
    }
    GLuint tex = 0;
    if (!materialTexture(mat, tex)) return false;
    int segments = d.shape == Shape::Box || d.shape == Shape::Ground ? 0 : segmentsFor(d.bounds);
    if (d.shape == Shape::Capsule && !mat.blend && !tex) {
      // An opaque capsule is a cylinder and two spheres: unit meshes that
      // join the batches of every sphere and cylinder, instead of one mesh
      // (and one draw) per capsule size.
      double r = d.capsuleRadius, h = d.capsuleHeight;
      Eigen::Vector4f pbr = pbrOf(mat, 0);
      add(primitive(Shape::Cylinder, 0, 0, segments), 0, false, mat.doubleSided, d.castShadow,
          d.world * Eigen::Scaling(r, r, h), mat.color, pbr, mat.emissive, inView);
      for (double end : {-h / 2, h / 2})
        add(primitive(Shape::Sphere, 0, 0, segments), 0, false, mat.doubleSided, d.castShadow,
            d.world * Eigen::Translation3d(0, 0, end) * Eigen::Scaling(r), mat.color, pbr, mat.emissive, inView);
      continue;
    }
    add(primitive(d.shape, d.capsuleRadius, d.capsuleHeight, segments), tex, mat.blend,
        mat.doubleSided || d.shape == Shape::Ground, d.castShadow, d.world, mat.color,
        pbrOf(mat, d.shape == Shape::Ground ? 1.f : 0.f), mat.emissive, inView);
  }
  for (const TerrainMesh& t : scene_.terrains) {
    MeshData m;
    int nx = t.xSamples, ny = t.ySamples;
    m.vertices.reserve(std::size_t(nx) * ny * 8);
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        auto at = [&](int i, int j) {
          return t.positions[std::size_t(std::clamp(j, 0, ny - 1)) * nx + std::clamp(i, 0, nx - 1)];
        };
        Eigen::Vector3f dx = at(x + 1, y) - at(x - 1, y), dy = at(x, y + 1) - at(x, y - 1);
        Eigen::Vector3f n = dx.cross(dy).normalized();
        const Eigen::Vector3f& p = at(x, y);
        m.vertices.insert(m.vertices.end(),
                          {p.x(), p.y(), p.z(), n.x(), n.y(), n.z(), float(x) / (nx - 1), float(y) / (ny - 1)});
      }
    for (int y = 0; y + 1 < ny; ++y)
      for (int x = 0; x + 1 < nx; ++x) {
        auto i = std::uint32_t(y * nx + x);
        if (t.holes[i] || t.holes[i + 1] || t.holes[i + nx] || t.holes[i + nx + 1]) continue;
        m.indices.insert(m.indices.end(), {i, i + 1, i + std::uint32_t(nx) + 1, i, i + std::uint32_t(nx) + 1,
                                           i + std::uint32_t(nx)});
      }
    const RenderMaterial& mat = scene_.materials[std::size_t(t.material)];
    add(upload(m, &t.colors), 0, false, true, t.castShadow, Eigen::Affine3d::Identity(), Eigen::Vector4f(1, 1, 1, 1),
        pbrOf(mat, 0), Eigen::Vector3f::Zero());
  }
  for (const Instanced& b : scene_.instanced) {
    std::shared_ptr<GpuMesh> mesh;
    if (b.shape == Shape::Mesh) {
      bool failed = false;
      const std::vector<TexturedPart>* parts = meshFile(b.meshPath, b.line, b.meshColumn, failed);
      if (failed) return false;
      mesh = parts ? parts->front().mesh : primitive(Shape::Box);
    } else {
      mesh = primitive(b.shape);
    }
    const RenderMaterial& mat = scene_.materials[std::size_t(b.material)];
    for (std::size_t i = 0; i < b.worlds.size(); ++i)
      add(mesh, 0, b.colors[i].w() < 0.999f, false, b.castShadow, b.worlds[i], b.colors[i], pbrOf(mat, 0),
          Eigen::Vector3f::Zero(), boxInFrustum(viewProj_, b.instanceBounds[i]));
  }
  const Look& env = scene_.environment;
  if (env.mode == Background::Hdr) {
    std::string err;
    std::shared_ptr<const FloatImage> hdr = env.hdrPath.empty() ? nullptr : assets_.floatImage(env.hdrPath, &err);
    if (!hdr) {
      diag(Severity::Warning, "RS9003", env.hdrLine,
           "hdr background " + (env.hdrPath.empty() ? std::string("has no envMapPath") : env.hdrPath + ": " + err) +
               "; drawing the procedural sky");
    } else {
      glGenTextures(1, &hdrTexture_);
      ownedTextures_.push_back(hdrTexture_);
      glBindTexture(GL_TEXTURE_2D, hdrTexture_);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB16F, hdr->width, hdr->height, 0, GL_RGB, GL_FLOAT, hdr->rgb.data());
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
  }
  // Point clouds: one buffer, one range per cloud.
  std::vector<float> points;
  for (const PointBatch& pc : scene_.pointClouds) {
    pointRanges_.emplace_back(GLint(points.size() / 7), GLsizei(pc.points.size()));
    pointSizes_.push_back(pc.pointSize);
    for (std::size_t i = 0; i < pc.points.size(); ++i) {
      points.insert(points.end(), pc.points[i].data(), pc.points[i].data() + 3);
      points.insert(points.end(), pc.colors[i].data(), pc.colors[i].data() + 4);
    }
  }
  if (!points.empty()) {
    glGenVertexArrays(1, &pointVao_);
    glBindVertexArray(pointVao_);
    glGenBuffers(1, &pointVbo_);
    glBindBuffer(GL_ARRAY_BUFFER, pointVbo_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(points.size() * sizeof(float)), points.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 7 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 7 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
    glBindVertexArray(0);
  }
  finishBatches();
  buildLights();
  return true;
}

void Frame::finishBatches() {
  for (Batch& b : batches_) {
    b.inView = GLsizei(b.instances.size() / kInstanceFloats);
    b.instances.insert(b.instances.end(), b.outOfView.begin(), b.outOfView.end());
    std::vector<float>().swap(b.outOfView);
    b.count = GLsizei(b.instances.size() / kInstanceFloats);
    glGenVertexArrays(1, &b.vao);
    glBindVertexArray(b.vao);
    glBindBuffer(GL_ARRAY_BUFFER, b.mesh->vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 8 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 8 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, 8 * sizeof(float), reinterpret_cast<void*>(6 * sizeof(float)));
    if (b.mesh->colorVbo) {
      glBindBuffer(GL_ARRAY_BUFFER, b.mesh->colorVbo);
      glEnableVertexAttribArray(3);
      glVertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
    }
    glGenBuffers(1, &b.instanceVbo);
    glBindBuffer(GL_ARRAY_BUFFER, b.instanceVbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(b.instances.size() * sizeof(float)), b.instances.data(),
                 GL_STATIC_DRAW);
    for (int a = 0; a < 7; ++a) {
      glEnableVertexAttribArray(GLuint(4 + a));
      glVertexAttribPointer(GLuint(4 + a), 4, GL_FLOAT, GL_FALSE, kInstanceFloats * sizeof(float),
                            reinterpret_cast<void*>(std::size_t(a) * 4 * sizeof(float)));
      glVertexAttribDivisor(GLuint(4 + a), 1);
    }
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.mesh->ebo);
    glBindVertexArray(0);
    std::vector<float>().swap(b.instances);
  }
}

void Frame::buildLights() {
  lights_ = scene_.lights;
  if (lights_.empty()) {  // a scene without lights is lit by the sun of its sky
    RenderLight sun;
    sun.direction = -scene_.environment.sunDirection;
    sun.color = Eigen::Vector3f(1.0f, 0.96f, 0.9f) * 3.0f;
    sun.shadows = true;
    lights_.push_back(sun);
  }
  if (lights_.size() > std::size_t(kMaxLights)) {
    diag(Severity::Warning, "RS9004", 0,
         std::to_string(lights_.size()) + " lights; only the first " + std::to_string(kMaxLights) + " are drawn");
    lights_.resize(kMaxLights);
  }
  if (!scene_.environment.shadows) return;
  for (int pass = 0; pass < 2 && shadowLight_ < 0; ++pass)
    for (std::size_t i = 0; i < lights_.size(); ++i)
      if (lights_[i].type == LightType::Directional && (pass == 1 || lights_[i].shadows)) {
        shadowLight_ = int(i);
        break;
      }
}

void Frame::drawBatches(GLuint prog, bool blendPass, bool shadowPass) {
  for (const Batch& b : batches_) {
    if (shadowPass ? !b.castShadow : b.blend != blendPass) continue;
    if (!shadowPass) {
      glUniform1i(loc(prog, "uHasAlbedo"), b.texture != 0);
      glUniform1i(loc(prog, "uDoubleSided"), b.doubleSided);
      glActiveTexture(GL_TEXTURE1);
      glBindTexture(GL_TEXTURE_2D, b.texture);
      if (b.doubleSided) glDisable(GL_CULL_FACE);
      else glEnable(GL_CULL_FACE);
    }
    GLsizei n = shadowPass ? b.count : b.inView;
    if (n == 0) continue;
    glBindVertexArray(b.vao);
    glDrawElementsInstanced(GL_TRIANGLES, b.mesh->indexCount, GL_UNSIGNED_INT, nullptr, n);
  }
  glBindVertexArray(0);
}

bool Frame::draw(const Camera& camera, Image& out) {
  const Look& env = scene_.environment;
  int w = opt_.width, h = opt_.height;
  double aspect = double(w) / double(h);
  std::string log;
  GLuint surface = program(shaders::kSurfaceVertex, shaders::kSurfaceFragment, log);
  GLuint depth = program(shaders::kSurfaceVertex, shaders::kDepthFragment, log);
  GLuint pointProg = program(shaders::kPointVertex, shaders::kPointFragment, log);
  GLuint post = program(shaders::kPostVertex, shaders::kPostFragment, log);
  programs_ = {surface, depth, pointProg, post};
  if (!surface || !depth || !pointProg || !post) {
    diag(Severity::Error, "RS9010", 0, "shader build failed: " + log);
    return false;
  }
  glVertexAttrib4f(3, 1, 1, 1, 1);  // vertex color of meshes that have none

  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  bool software = renderer && (std::strstr(renderer, "llvmpipe") || std::strstr(renderer, "softpipe"));
  int shadowSize = software ? kSoftwareShadowSize : kShadowSize;
  // Shadow map of the main light, fitted to the scene's bounds.
  Eigen::Matrix4d lightViewProj = Eigen::Matrix4d::Identity();
  GLuint shadowTex = 0;
  if (shadowLight_ >= 0) {
    Eigen::AlignedBox3d box = scene_.bounds;
    if (box.isEmpty()) box = Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, 0), Eigen::Vector3d(1, 1, 1));
    Eigen::Vector3d fwd = lights_[std::size_t(shadowLight_)].direction.normalized();
    // Cover where the shadows land too: each corner carried along the light
    // down to the lowest point (the ground), at most 50 m away.
    if (fwd.z() < -0.05) {
      double floor = std::min(box.min().z(), 0.0);
      Eigen::AlignedBox3d withShadows = box;
      for (int i = 0; i < 8; ++i) {
        Eigen::Vector3d p = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i));
        withShadows.extend(p + fwd * std::min((p.z() - floor) / -fwd.z(), 50.0));
      }
      box = withShadows;
    }
    Eigen::Vector3d c = box.center();
    double r = std::max(0.5 * box.diagonal().norm(), 0.5) * 1.1;
    Camera lc;
    Eigen::Vector3d upHint = std::abs(fwd.z()) > 0.99 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
    Eigen::Vector3d left = upHint.cross(fwd).normalized();
    Eigen::Matrix3d rot;
    rot.col(0) = fwd, rot.col(1) = left, rot.col(2) = fwd.cross(left);
    lc.world.orientation = Eigen::Quaterniond(rot);
    lc.world.position = c - fwd * 2 * r;
    lc.projection = "orthographic";
    lc.orthoScale = 2 * r;
    lc.nearPlane = 0.01;
    lc.farPlane = 4 * r;
    lightViewProj = projectionMatrix(lc, 1.0) * viewMatrix(lc);
    glGenTextures(1, &shadowTex);
    ownedTextures_.push_back(shadowTex);
    glBindTexture(GL_TEXTURE_2D, shadowTex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, shadowSize, shadowSize, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                 nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    GLuint fbo = 0;
    glGenFramebuffers(1, &fbo);
    fbos_.push_back(fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadowTex, 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    glViewport(0, 0, shadowSize, shadowSize);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glUseProgram(depth);
    setMat(depth, "uViewProj", lightViewProj);
    drawBatches(depth, false, true);
  }

  // Main pass: linear HDR, coverage in alpha, multisampled.
  GLint maxSamples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  int samples = std::clamp(opt_.samples, 1, std::max(1, int(maxSamples)));
  GLuint rb[2];
  glGenRenderbuffers(2, rb);
  renderbuffers_.insert(renderbuffers_.end(), rb, rb + 2);
  glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0, GL_RGBA16F, w, h);
  glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0, GL_DEPTH24_STENCIL8, w, h);
  GLuint fbos[3];
  glGenFramebuffers(3, fbos);
  fbos_.insert(fbos_.end(), fbos, fbos + 3);
  glBindFramebuffer(GL_FRAMEBUFFER, fbos[0]);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    diag(Severity::Error, "RS9011", 0, "cannot create a " + std::to_string(w) + "x" + std::to_string(h) +
                                           " framebuffer with " + std::to_string(samples) + " samples");
    return false;
  }
  glViewport(0, 0, w, h);
  glClearColor(0, 0, 0, 0);
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glCullFace(GL_BACK);
  Eigen::Matrix4d viewProj = projectionMatrix(camera, aspect) * viewMatrix(camera);
  // Depth pre-pass on GPUs: the lit shader then runs once per visible
  // sample.  Not on llvmpipe, where it was measured slower (it shades every
  // sample of a multisampled target and pays the rasterisation twice): 0.87
  // against 0.70 s of drawing on the 5000-object bench scene.
  bool prepass = !software;
  if (prepass) {
    glUseProgram(depth);
    setMat(depth, "uViewProj", viewProj);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDisable(GL_CULL_FACE);
    for (const Batch& b : batches_) {
      if (b.blend || b.inView == 0) continue;
      glBindVertexArray(b.vao);
      glDrawElementsInstanced(GL_TRIANGLES, b.mesh->indexCount, GL_UNSIGNED_INT, nullptr, b.inView);
    }
    glBindVertexArray(0);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
  }
  glUseProgram(surface);
  setMat(surface, "uViewProj", viewProj);
  setMat(surface, "uLightViewProj", lightViewProj);
  setVec3(surface, "uCameraPos", camera.world.position.cast<float>());
  glUniform1i(loc(surface, "uLightCount"), int(lights_.size()));
  for (std::size_t i = 0; i < lights_.size(); ++i) {
    const RenderLight& l = lights_[i];
    std::string idx = "[" + std::to_string(i) + "]";
    Eigen::Vector3f p = l.position.cast<float>(), d = l.direction.normalized().cast<float>();
    constexpr float kDeg = 3.14159265f / 180;
    glUniform4f(loc(surface, ("uLightPos" + idx).c_str()), p.x(), p.y(), p.z(), float(int(l.type)));
    glUniform4f(loc(surface, ("uLightDir" + idx).c_str()), d.x(), d.y(), d.z(), std::cos(l.coneDegrees * kDeg));
    glUniform4f(loc(surface, ("uLightColor" + idx).c_str()), l.color.x(), l.color.y(), l.color.z(),
                std::cos(std::min(l.innerConeDegrees, l.coneDegrees - 0.01f) * kDeg));
    float areaGain = l.type == LightType::Area ? std::max(l.areaSize.x() * l.areaSize.y(), 0.f) : 1.f;
    glUniform4f(loc(surface, ("uLightAtt" + idx).c_str()), l.attenuation.x() / std::max(areaGain, 1e-3f),
                l.attenuation.y() / std::max(areaGain, 1e-3f), l.attenuation.z() / std::max(areaGain, 1e-3f),
                l.range);
  }
  glUniform1i(loc(surface, "uShadowLight"), shadowLight_);
  glUniform1f(loc(surface, "uShadowTexel"), 1.0f / float(shadowSize));
  glUniform1i(loc(surface, "uShadowMap"), 0);
  glUniform1i(loc(surface, "uAlbedo"), 1);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, shadowTex);
  setVec3(surface, "uAmbient", env.ambient);
  float day = env.night ? 0.02f : float(std::clamp((env.sunDirection.z() + 0.15) / 0.35, 0.0, 1.0));
  Eigen::Vector3f skyAmbient = env.mode == Background::PlainColor ? Eigen::Vector3f(Eigen::Vector3f::Zero())
                                                                   : Eigen::Vector3f(Eigen::Vector3f(0.16f, 0.20f, 0.28f) * day);
  setVec3(surface, "uSkyAmbient", skyAmbient);
  glUniform1f(loc(surface, "uFogDensity"), env.fogDensity);
  setVec3(surface, "uFogColor", env.fogColor);
  glDisable(GL_BLEND);
  // Each sample is lit once: after a pre-pass, coplanar surfaces (stacked
  // boxes with level tops, overlapping placeholders) all pass GL_LEQUAL, so
  // the stencil lets the first one drawn through and rejects the rest
  // before they are shaded.
  if (prepass) {
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
  }
  drawBatches(surface, false, false);
  glDisable(GL_STENCIL_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  if (pointVao_) {
    glUseProgram(pointProg);
    glEnable(GL_PROGRAM_POINT_SIZE);
    setMat(pointProg, "uViewProj", viewProj);
    glBindVertexArray(pointVao_);
    for (std::size_t i = 0; i < pointRanges_.size(); ++i) {
      glUniform1f(loc(pointProg, "uPointSize"), pointSizes_[i]);
      glDrawArrays(GL_POINTS, pointRanges_[i].first, pointRanges_[i].second);
    }
    glBindVertexArray(0);
    glUseProgram(surface);
  }
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);
  drawBatches(surface, true, false);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);

  // Resolve, then background + tone map into RGBA8.
  GLuint resolved = 0, finalTex = 0;
  glGenTextures(1, &resolved);
  glGenTextures(1, &finalTex);
  ownedTextures_.push_back(resolved);
  ownedTextures_.push_back(finalTex);
  glBindTexture(GL_TEXTURE_2D, resolved);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, w, h, 0, GL_RGBA, GL_FLOAT, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, fbos[1]);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, resolved, 0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbos[0]);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbos[1]);
  glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, finalTex);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glBindFramebuffer(GL_FRAMEBUFFER, fbos[2]);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, finalTex, 0);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glUseProgram(post);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, resolved);
  glUniform1i(loc(post, "uScene"), 0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, hdrTexture_);
  glUniform1i(loc(post, "uHdr"), 1);
  setMat(post, "uInvViewProj", viewProj.inverse());
  int mode = env.mode == Background::PlainColor ? 0 : (env.mode == Background::Hdr && hdrTexture_) ? 1 : 2;
  glUniform1i(loc(post, "uMode"), mode);
  glUniform1i(loc(post, "uTransparent"), opt_.transparent);
  setVec3(post, "uBackground", env.background);
  setVec3(post, "uSunDir", env.sunDirection.cast<float>());
  glUniform1f(loc(post, "uCloud"), env.cloudCoverage);
  glUniform1i(loc(post, "uNight"), env.night);
  glUniform1f(loc(post, "uFogDensity"), env.fogDensity);
  setVec3(post, "uFogColor", env.fogColor);
  glUniform1f(loc(post, "uExposure"), env.exposure);
  glUniform1f(loc(post, "uGamma"), env.gamma);
  glUniform1i(loc(post, "uToneMap"), int(env.toneMap));
  glGenVertexArrays(1, &emptyVao_);
  glBindVertexArray(emptyVao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);

  out.width = w;
  out.height = h;
  out.rgba.assign(std::size_t(w) * h * 4, 0);
  std::vector<std::uint8_t> rows(out.rgba.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  for (int y = 0; y < h; ++y)  // GL rows are bottom-up
    std::copy_n(&rows[std::size_t(h - 1 - y) * w * 4], std::size_t(w) * 4, out.pixel(0, y));
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (GLenum e = glGetError(); e != GL_NO_ERROR) {
    diag(Severity::Error, "RS9012", 0, "OpenGL error 0x" + [&] {
      char b[16];
      std::snprintf(b, sizeof b, "%04x", e);
      return std::string(b);
    }());
    return false;
  }
  return true;
}

}  // namespace

bool renderScene(const RenderScene& scene, const Camera& camera, const RenderOptions& options, Image& out,
                 Diagnostics& diags, RenderTimings* timings) {
  auto t0 = Clock::now();
  Frame frame(scene, camera, options, diags);
  if (!frame.prepare()) return false;
  glFinish();
  auto t1 = Clock::now();
  bool ok = frame.draw(camera, out);
  auto t2 = Clock::now();
  if (timings) {
    timings->uploadSeconds = seconds(t0, t1);
    timings->drawSeconds = seconds(t1, t2);
  }
  return ok;
}

}  // namespace rscene::render
