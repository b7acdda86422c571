// The upload side of the Renderer (gl_renderer.hpp): meshes, textures,
// instance batches, point clouds, programs and lights, once per scene;
// updatePoses() and renderScene(), the one-view wrapper rscene-render's
// single camera uses.
#include "render/renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>

#include <EGL/egl.h>
#include <utility>

#include "core/codes.hpp"
#include "core/assets.hpp"
#include "render/camera.hpp"
#include "render/deformed_surface.hpp"
#include "render/gl_renderer.hpp"
#include "render/limits.hpp"
#include "render/main_pass.hpp"
#include "render/mesh.hpp"
#include "render/mipmap.hpp"
#include "render/shaders.hpp"

namespace rscene::render {
namespace detail {
namespace {

using Clock = std::chrono::steady_clock;

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
    glDeleteProgram(p);
    return 0;
  }
  return p;
}

// The color of a missing mesh's stand-in (--allow-missing-assets): magenta,
// which cannot be mistaken for content.
const Eigen::Vector4f kPlaceholderColor(1.0f, 0.0f, 1.0f, 1.0f);

// Mesa's CPU rasterisers (llvmpipe, softpipe): some work is cheaper done here.
bool softwareGl() {
  const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return r && (std::strstr(r, "llvmpipe") || std::strstr(r, "softpipe"));
}

// The segment's legend color as one float the shaders unpack (exact: a
// 24-bit integer); 0 (black, the background's) for none.
float packedSegment(const RenderScene& scene, int segment) {
  if (segment < 0 || std::size_t(segment) >= scene.segments.size()) return 0;
  const std::uint8_t* c = scene.segments[std::size_t(segment)].rgb;
  return float((std::uint32_t(c[0]) << 16) | (std::uint32_t(c[1]) << 8) | c[2]);
}

void writeMatrix(float* data, const Eigen::Affine3d& world) {
  Eigen::Matrix4f m = world.matrix().cast<float>();
  std::copy_n(m.data(), 16, data);
}

}  // namespace

namespace {

// Programs live as long as the context (rscene-render keeps one across the
// scenes of a batch): each one is compiled once, whichever renderer asks.
// Keyed by their sources; forgotten when the context ends (gl_context.cpp).
using ProgramCache = std::map<std::pair<std::string, std::string>, GLuint>;
std::map<void*, ProgramCache>& programCaches() {
  // By EGL context; never destroyed, so that a context kept in a static
  // (the render tests') may still forget its programs at exit.
  static auto* caches = new std::map<void*, ProgramCache>;
  return *caches;
}

// A program handed out again is set back to what linking gave it: every
// uniform zero (the samplers unit 0), so that nothing a previous scene set
// reaches the next one (same pixels as a program of its own).
void resetUniforms(GLuint p) {
  GLint previous = 0, count = 0;
  glGetIntegerv(GL_CURRENT_PROGRAM, &previous);
  glUseProgram(p);
  glGetProgramiv(p, GL_ACTIVE_UNIFORMS, &count);
  std::vector<float> zeros;
  std::vector<GLint> izeros;
  std::vector<GLuint> uzeros;
  for (GLint i = 0; i < count; ++i) {
    char name[256];
    GLint size = 0;
    GLenum type = 0;
    glGetActiveUniform(p, GLuint(i), sizeof name, nullptr, &size, &type, name);
    GLint at = glGetUniformLocation(p, name);
    if (at < 0 || size < 1) continue;
    zeros.assign(std::size_t(size) * 16, 0.0f);
    izeros.assign(std::size_t(size) * 4, 0);
    uzeros.assign(std::size_t(size) * 4, 0u);
    switch (type) {
      case GL_FLOAT: glUniform1fv(at, size, zeros.data()); break;
      case GL_FLOAT_VEC2: glUniform2fv(at, size, zeros.data()); break;
      case GL_FLOAT_VEC3: glUniform3fv(at, size, zeros.data()); break;
      case GL_FLOAT_VEC4: glUniform4fv(at, size, zeros.data()); break;
      case GL_FLOAT_MAT2: glUniformMatrix2fv(at, size, GL_FALSE, zeros.data()); break;
      case GL_FLOAT_MAT3: glUniformMatrix3fv(at, size, GL_FALSE, zeros.data()); break;
      case GL_FLOAT_MAT4: glUniformMatrix4fv(at, size, GL_FALSE, zeros.data()); break;
      case GL_FLOAT_MAT2x3: glUniformMatrix2x3fv(at, size, GL_FALSE, zeros.data()); break;
      case GL_FLOAT_MAT2x4: glUniformMatrix2x4fv(at, size, GL_FALSE, zeros.data()); break;
      case GL_FLOAT_MAT3x2: glUniformMatrix3x2fv(at, size, GL_FALSE, zeros.data()); break;
      case GL_FLOAT_MAT3x4: glUniformMatrix3x4fv(at, size, GL_FALSE, zeros.data()); break;
      case GL_FLOAT_MAT4x2: glUniformMatrix4x2fv(at, size, GL_FALSE, zeros.data()); break;
      case GL_FLOAT_MAT4x3: glUniformMatrix4x3fv(at, size, GL_FALSE, zeros.data()); break;
      case GL_INT_VEC2: case GL_BOOL_VEC2: glUniform2iv(at, size, izeros.data()); break;
      case GL_INT_VEC3: case GL_BOOL_VEC3: glUniform3iv(at, size, izeros.data()); break;
      case GL_INT_VEC4: case GL_BOOL_VEC4: glUniform4iv(at, size, izeros.data()); break;
      case GL_UNSIGNED_INT: glUniform1uiv(at, size, uzeros.data()); break;
      case GL_UNSIGNED_INT_VEC2: glUniform2uiv(at, size, uzeros.data()); break;
      case GL_UNSIGNED_INT_VEC3: glUniform3uiv(at, size, uzeros.data()); break;
      case GL_UNSIGNED_INT_VEC4: glUniform4uiv(at, size, uzeros.data()); break;
      default: glUniform1iv(at, size, izeros.data()); break;  // int, bool and every sampler kind
    }
  }
  glUseProgram(GLuint(previous));
}

}  // namespace

GLuint linkProgram(const char* vertex, const char* fragment, std::string& log) {
  auto key = std::make_pair(std::string(vertex), std::string(fragment));
  auto& cache = programCaches()[eglGetCurrentContext()];
  if (auto it = cache.find(key); it != cache.end()) {
    resetUniforms(it->second);
    return it->second;
  }
  GLuint p = program(vertex, fragment, log);
  if (p) cache.emplace(std::move(key), p);
  return p;
}

void forgetPrograms(void* context) { programCaches().erase(context); }

GlRenderer::GlRenderer(const RenderScene& scene, const RenderOptions& options, Diagnostics& diagnostics,
                       std::vector<Camera> lodCameras)
    : scene_(scene),
      opt_(options),
      diags_(&diagnostics),
      lodCameras_(std::move(lodCameras)),
      ownAssets_(diskFileSystem(), assetLimits(options)),
      assets_(options.assets ? *options.assets : ownAssets_) {}

GlRenderer::~GlRenderer() {
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
  // The programs stay with the context (linkProgram()).
  if (jitter_.fbo) {
    glDeleteFramebuffers(1, &jitter_.fbo);
    glDeleteTextures(1, &jitter_.color);
  }
  if (jitter_.spreadFbo) {
    glDeleteFramebuffers(1, &jitter_.spreadFbo);
    glDeleteTextures(1, &jitter_.spread);
  }
  if (jitter_.idFbo) {
    glDeleteFramebuffers(1, &jitter_.idFbo);
    glDeleteTextures(1, &jitter_.ids);
    glDeleteRenderbuffers(1, &jitter_.idDepth);
  }
  glDeleteFramebuffers(3, color_.fbo);
  glDeleteRenderbuffers(1, &color_.msaaColor);
  GLuint colorTex[3] = {color_.resolved, color_.final, color_.msaaDepth};
  glDeleteTextures(3, colorTex);
  glDeleteFramebuffers(1, &data_.fbo);
  GLuint dataRbs[3] = {data_.segmentation, data_.depth, data_.z};
  glDeleteRenderbuffers(3, dataRbs);
}

void GlRenderer::diag(Severity s, const char* code, std::uint32_t line, std::string message, std::uint32_t column,
                      const std::string& file) {
  Diagnostic d;
  d.severity = s;
  d.code = code;
  d.line = line;
  d.column = column ? column : line && file.empty() ? 1 : 0;
  d.message = std::move(message);
  d.file = file;
  diags_->push_back(std::move(d));
}

// Missing (RS5001, the code validate --check-files and rscene-sim give the
// same file) or unreadable (RS9001) asset: an error, or a warning when allowed.
bool GlRenderer::assetProblem(std::uint32_t line, std::uint32_t column, const std::string& file,
                              const std::string& message, const char* code) {
  diag(opt_.allowMissingAssets ? Severity::Warning : Severity::Error, code, line, message, column, file);
  return opt_.allowMissingAssets;
}

// A regular file (as validate --check-files and rscene-sim ask: a FIFO or
// /dev/zero is no asset), through the asset cache's file system.
bool GlRenderer::regularFile(const std::string& path) const {
  return assets_.fileSystem().stat(path).kind == FileKind::Regular;
}

std::shared_ptr<GpuMesh> GlRenderer::uploadMesh(const MeshData& m, const std::vector<Eigen::Vector4f>* colors,
                                                GLenum usage) {
  auto g = std::make_shared<GpuMesh>();
  glGenBuffers(1, &g->vbo);
  glBindBuffer(GL_ARRAY_BUFFER, g->vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(m.vertices.size() * sizeof(float)), m.vertices.data(), usage);
  glGenBuffers(1, &g->ebo);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g->ebo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(m.indices.size() * sizeof(std::uint32_t)), m.indices.data(),
               GL_STATIC_DRAW);
  if (colors) {
    glGenBuffers(1, &g->colorVbo);
    glBindBuffer(GL_ARRAY_BUFFER, g->colorVbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(colors->size() * sizeof(Eigen::Vector4f)), colors->data(), GL_STATIC_DRAW);
  }
  g->indexCount = GLsizei(m.indices.size());
  meshes_.push_back(g);
  return g;
}

std::shared_ptr<GpuMesh> GlRenderer::primitive(Shape s, double capsuleR, double capsuleH, int segments) {
  bool round = s == Shape::Sphere || s == Shape::Cylinder || s == Shape::Capsule;
  std::string key = std::to_string(int(s));
  if (round) key += "/" + std::to_string(segments);
  if (s == Shape::Capsule) key += ":" + std::to_string(capsuleR) + ":" + std::to_string(capsuleH);
  auto it = primitives_.find(key);
  if (it != primitives_.end()) return it->second;
  if (s == Shape::GrassBlade) {  // darker at the root (per-vertex colors)
    std::vector<Eigen::Vector4f> shading = grassBladeShading();
    return primitives_[key] = uploadMesh(grassBlade(), &shading);
  }
  MeshData m = s == Shape::Sphere     ? unitSphere(segments, std::max(segments / 2, 4))
               : s == Shape::Cylinder ? unitCylinder(segments)
               : s == Shape::Capsule  ? capsule(capsuleR, capsuleH, segments)
               : s == Shape::Ground   ? unitPlane()
                                      : unitBox();
  return primitives_[key] = uploadMesh(m);
}

int GlRenderer::segmentsFor(const Eigen::AlignedBox3d& box) const {
  if (lodCameras_.empty()) return 48;  // views not known in advance: the finest
  double radius = 0.5 * box.sizes().maxCoeff();
  double pixels = 0;  // radius on screen, in the view that sees it largest
  for (const Camera& c : lodCameras_) {
    ImageSize size = cameraImageSize(c);  // the size it is drawn at when it has none of its own
    double height = size.height, aspect = double(size.width) / size.height;
    if (c.projection == "orthographic") {
      pixels = std::max(pixels, radius / std::max(c.orthoScale / 2, 1e-9) * height / 2);
    } else {
      double distance = (box.center() - c.world.position).norm() - radius;
      double t = std::tan(effectiveVerticalFov(c, aspect) * 3.14159265358979 / 360);
      pixels = std::max(pixels, distance <= c.nearPlane ? 1e9 : radius / (distance * t) * height / 2);
    }
  }
  // Sagitta r (1 - cos(pi / n)) ~ r pi^2 / (2 n^2) <= 0.5 px.
  double wanted = 3.14159265358979 * std::sqrt(std::max(pixels, 0.0));
  for (int n : {8, 12, 16, 24, 32})
    if (n >= wanted) return n;
  return 48;
}

GLuint GlRenderer::texture(const Image& image) {
  GLuint t = 0;
  glGenTextures(1, &t);
  ownedTextures_.push_back(t);
  glBindTexture(GL_TEXTURE_2D, t);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  if (software_) {  // mipmap.hpp: llvmpipe's glGenerateMipmap costs more than this loop
    std::vector<std::uint8_t> level, next;
    const std::uint8_t* from = image.rgba.data();
    int w = image.width, h = image.height;
    for (int i = 1; w > 1 || h > 1; ++i) {
      halveImage(from, w, h, next);
      w = std::max(1, w / 2);
      h = std::max(1, h / 2);
      glTexImage2D(GL_TEXTURE_2D, i, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, next.data());
      level.swap(next);
      from = level.data();
    }
  } else {
    glGenerateMipmap(GL_TEXTURE_2D);
  }
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return t;
}

GLuint GlRenderer::texture(const std::shared_ptr<const Image>& image) {
  if (!image) return 0;
  auto [it, fresh] = imageTextures_.try_emplace(image.get(), 0);
  if (fresh) it->second = texture(*image);
  return it->second;
}

bool GlRenderer::materialTexture(const RenderMaterial& m, GLuint& out) {
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
  if (!regularFile(m.albedoTexture))
    return assetProblem(m.line, m.textureColumn, m.file,
                        "texture file '" + m.albedoTexture + "' " + whyNotAFile(m.albedoTexture),
                        scene_code::kMissingFile);
  std::string err;
  std::shared_ptr<const Image> image = assets_.image(m.albedoTexture, &err);
  if (!image) {
    diag(Severity::Warning, rs::RS9002, m.line, "texture " + m.albedoTexture + " is not drawn: " + err, 0, m.file);
    return true;
  }
  out = textures_[m.albedoTexture] = texture(image);
  return true;
}

const std::vector<TexturedPart>* GlRenderer::meshFile(const std::string& path, std::uint32_t line, std::uint32_t column,
                                                      const std::string& file, bool& failed) {
  failed = false;
  auto it = meshFiles_.find(path);
  if (it != meshFiles_.end()) return it->second.empty() ? nullptr : &it->second;
  std::vector<TexturedPart>& parts = meshFiles_[path];
  if (path.empty() || !regularFile(path)) {
    failed = !assetProblem(
        line, column, file,
        path.empty() ? std::string("mesh body has no mesh file") : "mesh file '" + path + "' " + whyNotAFile(path),
        path.empty() ? scene_code::kNoMesh : scene_code::kMissingFile);
    return nullptr;
  }
  std::string err;
  std::shared_ptr<const asset::Mesh> loaded = assets_.mesh(path, asset::MeshContent::Surface, &err);
  if (!loaded) {
    failed = !assetProblem(line, column, file, "cannot read mesh " + path + ": " + err);
    return nullptr;
  }
  for (const std::string& w : loaded->warnings) diag(Severity::Warning, rs::RS9002, line, w, column, file);
  for (const asset::MeshPart& p : loaded->parts)
    parts.push_back({uploadMesh(interleave(p)), Eigen::Vector4f(p.material.baseColor.data()), p.material.metallic,
                     p.material.roughness, texture(p.material.texture)});
  return &parts;
}

InstanceRef GlRenderer::add(const std::shared_ptr<GpuMesh>& mesh, GLuint tex, bool blend, bool doubleSided,
                            bool castShadow, const Eigen::Affine3d& world, const Eigen::Vector4f& color,
                            const Eigen::Vector4f& pbr, const Eigen::Vector3f& emissive, int segment,
                            const Eigen::AlignedBox3d& bounds, bool worldObject, bool background, bool particles) {
  auto key = std::make_tuple(mesh.get(), tex, blend, doubleSided, castShadow, particles);
  auto [it, inserted] = batchIndex_.emplace(key, batches_.size());
  if (inserted) {
    Batch b;
    b.mesh = mesh;
    b.texture = tex;
    b.blend = blend;
    b.doubleSided = doubleSided;
    b.castShadow = castShadow;
    b.background = background;
    batches_.push_back(std::move(b));
  }
  Batch& batch = batches_[it->second];
  Instance& in = batch.instances.emplace_back();
  writeMatrix(in.data, world);
  std::copy_n(color.data(), 4, in.data + 16);
  std::copy_n(pbr.data(), 4, in.data + 20);
  std::copy_n(emissive.data(), 3, in.data + 24);
  in.data[27] = packedSegment(scene_, segment);
  in.bounds = bounds;
  in.worldObject = worldObject;
  visualCasters_ = visualCasters_ || (castShadow && !worldObject);
  InstanceRef ref;
  ref.batch = it->second;
  ref.slot = batch.instances.size() - 1;
  return ref;
}

bool GlRenderer::uploadDrawables() {
  const Eigen::Vector4f placeholderColor = kPlaceholderColor;
  auto pbrOf = [](const RenderMaterial& m, float checker) {
    return Eigen::Vector4f(m.metallic, m.roughness, checker, 0);
  };
  drawableRefs_.assign(scene_.drawables.size(), {});
  surfaceMeshes_.assign(scene_.surfaces.size(), nullptr);
  surfaceVersions_.assign(scene_.surfaces.size(), 0);
  for (std::size_t di = 0; di < scene_.drawables.size(); ++di) {
    const Drawable& d = scene_.drawables[di];
    std::vector<InstanceRef>& refs = drawableRefs_[di];
    const RenderMaterial& mat = scene_.materials[std::size_t(d.material)];
    auto put = [&](const std::shared_ptr<GpuMesh>& mesh, GLuint tex, bool blend, bool doubleSided,
                   const Eigen::Affine3d& post, const Eigen::Vector4f& color, const Eigen::Vector4f& pbr,
                   bool placeholder = false) {
      Eigen::Affine3d world = (placeholder ? d.placeholderWorld.value_or(d.world) : d.world) * post;
      Eigen::Vector4f flagged = pbr;
      if (!d.receiveShadow) flagged.w() += 2;  // the surface shader's flag bit 2
      InstanceRef r = add(mesh, tex, blend, doubleSided, d.castShadow, world, color, flagged,
                          placeholder ? Eigen::Vector3f::Zero() : mat.emissive, d.segment, d.bounds, d.worldObject,
                          d.shape == Shape::Ground);
      r.post = post;
      r.placeholder = placeholder;
      refs.push_back(r);
    };
    const Eigen::Affine3d id = Eigen::Affine3d::Identity();
    // A mirroring scale (a URDF's scale="1 -1 1" for the other side's leg)
    // reverses the triangles' winding: such a drawable culls no faces (its
    // normals, carried by the inverse transpose, still point outwards).
    bool twoSided = mat.doubleSided || d.doubleSided || d.world.linear().determinant() < 0;
    if (d.surface >= 0 && std::size_t(d.surface) < scene_.surfaces.size()) {  // a deformable's OBJ surface
      const DeformedSurface& s = scene_.surfaces[std::size_t(d.surface)];
      std::shared_ptr<GpuMesh> mesh = uploadMesh(surfaceMesh(s), nullptr, GL_DYNAMIC_DRAW);
      surfaceMeshes_[std::size_t(d.surface)] = mesh;
      surfaceVersions_[std::size_t(d.surface)] = s.version;
      GLuint tex = 0;
      if (!materialTexture(mat, tex)) return false;
      put(mesh, tex, mat.blend, twoSided, id, mat.color, pbrOf(mat, 0));
      continue;
    }
    if (d.shape == Shape::Mesh) {
      bool failed = false;
      const std::vector<TexturedPart>* parts = meshFile(d.meshPath, d.line, d.meshColumn, d.file, failed);
      if (failed) return false;
      if (!parts) {
        put(primitive(Shape::Box), 0, false, false, id, placeholderColor, {0, 0.6f, 0, 1}, true);
        continue;
      }
      GLuint matTex = 0;
      if (!mat.isDefault && !materialTexture(mat, matTex)) return false;
      for (const TexturedPart& p : *parts) {
        bool own = mat.isDefault;
        Eigen::Vector4f color = own ? p.color : mat.color;
        Eigen::Vector4f pbr = own ? Eigen::Vector4f(p.metallic, p.roughness, 0, 0) : pbrOf(mat, 0);
        put(p.mesh, own ? p.texture : matTex, color.w() < 0.999f || (!own && mat.blend), twoSided, id, color, pbr);
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
      put(primitive(Shape::Cylinder, 0, 0, segments), 0, false, mat.doubleSided,
          Eigen::Affine3d(Eigen::Scaling(r, r, h)), mat.color, pbr);
      for (double end : {-h / 2, h / 2})
        put(primitive(Shape::Sphere, 0, 0, segments), 0, false, mat.doubleSided,
            Eigen::Translation3d(0, 0, end) * Eigen::Scaling(r), mat.color, pbr);
      continue;
    }
    put(primitive(d.shape, d.capsuleRadius, d.capsuleHeight, segments), tex, mat.blend,
        twoSided || d.shape == Shape::Ground, id, mat.color, pbrOf(mat, d.shape == Shape::Ground ? 1.f : 0.f));
  }
  return true;
}

void GlRenderer::uploadTerrains() {
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
        m.indices.insert(m.indices.end(),
                         {i, i + 1, i + std::uint32_t(nx) + 1, i, i + std::uint32_t(nx) + 1, i + std::uint32_t(nx)});
      }
    const RenderMaterial& mat = scene_.materials[std::size_t(t.material)];
    add(uploadMesh(m, &t.colors), 0, false, true, t.castShadow, Eigen::Affine3d::Identity(),
        Eigen::Vector4f(1, 1, 1, 1), Eigen::Vector4f(mat.metallic, mat.roughness, 0, t.receiveShadow ? 0.f : 2.f),
        Eigen::Vector3f::Zero(), t.segment, t.bounds, true, true);
  }
}

bool GlRenderer::uploadInstanced() {
  instancedRefs_.assign(scene_.instanced.size(), {});
  instancedVersions_.assign(scene_.instanced.size(), 0);
  for (std::size_t bi = 0; bi < scene_.instanced.size(); ++bi) {
    const Instanced& b = scene_.instanced[bi];
    // Granular particles move along a trajectory: keep where each went.
    std::vector<InstanceRef>* refs = b.radii.empty() ? nullptr : &instancedRefs_[bi];
    instancedVersions_[bi] = b.version;
    std::shared_ptr<GpuMesh> mesh;
    bool placeholder = false;
    if (b.shape == Shape::Mesh) {
      bool failed = false;
      const std::vector<TexturedPart>* parts = meshFile(b.meshPath, b.line, b.meshColumn, {}, failed);
      if (failed) return false;
      mesh = parts ? parts->front().mesh : primitive(Shape::Box);
      placeholder = !parts;  // --allow-missing-assets: a magenta box, as for objects
    } else {
      // Round shapes as finely as the instance that looks largest needs:
      // 20,000 sand grains of 48 slices each would be 46 M triangles.
      int segments = 0;
      if (b.shape == Shape::Sphere || b.shape == Shape::Cylinder)
        for (const Eigen::AlignedBox3d& box : b.instanceBounds) {
          segments = std::max(segments, segmentsFor(box));
          if (segments >= 48) break;
        }
      mesh = primitive(b.shape, 0, 0, std::max(segments, 8));
    }
    const RenderMaterial& mat = scene_.materials[std::size_t(b.material)];
    // Visuals only, never drawn by sensor views, unless worldObject
    // (granular particles).
    if (refs) refs->reserve(b.worlds.size());
    for (std::size_t i = 0; i < b.worlds.size(); ++i) {
      InstanceRef r = add(mesh, 0, b.colors[i].w() < 0.999f, b.doubleSided, b.castShadow, b.worlds[i],
                          placeholder ? kPlaceholderColor : b.colors[i],
                          placeholder ? Eigen::Vector4f(0, 0.6f, 0, 1) : Eigen::Vector4f(mat.metallic, mat.roughness, 0, 0),
                          Eigen::Vector3f::Zero(), b.segment, b.instanceBounds[i], b.worldObject, false, refs != nullptr);
      if (refs) refs->push_back(r);
      if (refs && std::find(particleBatches_.begin(), particleBatches_.end(), r.batch) == particleBatches_.end())
        particleBatches_.insert(std::upper_bound(particleBatches_.begin(), particleBatches_.end(), r.batch), r.batch);
    }
  }
  return true;
}

void GlRenderer::uploadBackground() {
  const Look& env = scene_.environment;
  if (env.mode != Background::Hdr) return;
  std::string err;
  std::shared_ptr<const FloatImage> hdr = env.hdrPath.empty() ? nullptr : assets_.floatImage(env.hdrPath, &err);
  if (!hdr) {
    diag(Severity::Warning, rs::RS9003, env.hdrLine,
         "hdr background " + (env.hdrPath.empty() ? std::string("has no envMapPath") : env.hdrPath + ": " + err) +
             "; drawing the procedural sky");
    return;
  }
  glGenTextures(1, &hdrTexture_);
  ownedTextures_.push_back(hdrTexture_);
  glBindTexture(GL_TEXTURE_2D, hdrTexture_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB16F, hdr->width, hdr->height, 0, GL_RGB, GL_FLOAT, hdr->rgb.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

// Point clouds: one buffer, one range per cloud.
void GlRenderer::uploadPoints() {
  std::vector<float> points;
  for (const PointBatch& pc : scene_.pointClouds) {
    pointRanges_.emplace_back(GLint(points.size() / 7), GLsizei(pc.points.size()));
    pointSizes_.push_back(pc.pointSize);
    pointSegments_.push_back(pc.segment);
    for (std::size_t i = 0; i < pc.points.size(); ++i) {
      points.insert(points.end(), pc.points[i].data(), pc.points[i].data() + 3);
      points.insert(points.end(), pc.colors[i].data(), pc.colors[i].data() + 4);
    }
  }
  if (points.empty()) return;
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

bool GlRenderer::buildPrograms() {
  std::string log;
  std::string surface = shaders::surfaceFragment(!scene_.probes.empty()), post = shaders::postFragment();
  VolumeEffects::configure(scene_, surface);
  LightEffects::configure(scene_, surface);
  VolumeEffects::configure(scene_, post);
  surfaceProg_ = linkProgram(shaders::kSurfaceVertex, surface.c_str(), log);
  shadowProg_ = linkProgram(shaders::kSurfaceVertex, shaders::kDepthFragment, log);
  pointProg_ = linkProgram(shaders::kPointVertex, shaders::kPointFragment, log);
  postProg_ = linkProgram(shaders::kPostVertex, post.c_str(), log);
  dataProg_ = linkProgram(shaders::kDataVertex, shaders::kDataFragment, log);
  pointDataProg_ = linkProgram(shaders::kPointDataVertex, shaders::kDataFragment, log);
  prepassProg_ = linkProgram(shaders::kSurfaceVertex, kPrepassFragment, log);
  averageProg_ = linkProgram(shaders::kPostVertex, kAverageFragment, log);
  idProg_ = linkProgram(kIdVertex, kIdFragment, log);
  edgeProg_ = linkProgram(shaders::kPostVertex, kEdgeFragment, log);
  clearProg_ = linkProgram(shaders::kPostVertex, kClearFragment, log);
  spreadProg_ = linkProgram(shaders::kPostVertex, kSpreadFragment, log);
  if (surfaceProg_ && shadowProg_ && pointProg_ && postProg_ && dataProg_ && pointDataProg_ && prepassProg_ &&
      averageProg_ && idProg_ && edgeProg_ && clearProg_ && spreadProg_)
    return true;
  diag(Severity::Error, rs::RS9010, 0, "shader build failed: " + log);
  return false;
}

// One vertex array per batch; its instance buffer is filled by the first
// view that draws it (passes.cpp, selectInstances).
void GlRenderer::bindMesh(Batch& b) {
  glBindVertexArray(b.vao);
  glBindBuffer(GL_ARRAY_BUFFER, b.mesh->vbo);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 8 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 8 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, 8 * sizeof(float), reinterpret_cast<void*>(6 * sizeof(float)));
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.mesh->ebo);
}

void GlRenderer::makeVertexArrays() {
  for (Batch& b : batches_) {
    glGenVertexArrays(1, &b.vao);
    bindMesh(b);
    if (b.mesh->colorVbo) {
      glBindBuffer(GL_ARRAY_BUFFER, b.mesh->colorVbo);
      glEnableVertexAttribArray(3);
      glVertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
    }
    glGenBuffers(1, &b.instanceVbo);
    glBindBuffer(GL_ARRAY_BUFFER, b.instanceVbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(b.instances.size() * sizeof(float) * kInstanceFloats), nullptr,
                 GL_DYNAMIC_DRAW);
    for (int a = 0; a < 7; ++a) {
      glEnableVertexAttribArray(GLuint(4 + a));
      glVertexAttribPointer(GLuint(4 + a), 4, GL_FLOAT, GL_FALSE, kInstanceFloats * sizeof(float),
                            reinterpret_cast<void*>(std::size_t(a) * 4 * sizeof(float)));
      glVertexAttribDivisor(GLuint(4 + a), 1);
    }
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.mesh->ebo);
    glBindVertexArray(0);
  }
}

bool GlRenderer::upload() {
  software_ = softwareGl();
  if (!buildPrograms()) return false;
  if (!uploadDrawables()) return false;
  uploadTerrains();
  if (!uploadInstanced()) return false;
  uploadBackground();
  uploadPoints();
  makeVertexArrays();
  if (auto box = primitives_.find(std::to_string(int(Shape::Box))); box != primitives_.end())
    for (Batch& b : batches_) b.occluder = b.mesh == box->second && !b.blend;
  for (int background = 0; background < 2; ++background)
    for (std::size_t i = 0; i < batches_.size(); ++i)
      if (batches_[i].background == bool(background)) drawOrder_.push_back(i);
  lights_ = std::make_unique<LightEffects>(*this);
  if (!lights_->upload()) return false;
  glGenVertexArrays(1, &emptyVao_);
  volumes_ = std::make_unique<VolumeEffects>(*this);
  reflections_ = std::make_unique<ReflectionEffects>(*this);
  if (!volumes_->upload() || !reflections_->upload()) return false;
  post_ = std::make_unique<PostEffects>(*this);  // builds its programs when a view first needs them
  return glOk();
}

void GlRenderer::setParticleViews(const std::vector<Camera>& cameras) {
  lodCameras_ = cameras;
  for (std::size_t bi : particleBatches_) {
    Batch& b = batches_[bi];
    int segments = 8;
    for (const Instance& in : b.instances) {
      segments = std::max(segments, segmentsFor(in.bounds));
      if (segments >= 48) break;
    }
    std::shared_ptr<GpuMesh> mesh = primitive(Shape::Sphere, 0, 0, segments);
    if (mesh == b.mesh) continue;
    b.mesh = mesh;
    bindMesh(b);
    glBindVertexArray(0);
  }
}

void GlRenderer::updatePoses() {
  // Deformed surfaces whose vertices a frame replaced: new positions and
  // normals into the same buffer (the batches' vertex arrays keep it).
  for (std::size_t i = 0; i < surfaceMeshes_.size() && i < scene_.surfaces.size(); ++i) {
    const DeformedSurface& s = scene_.surfaces[i];
    if (!surfaceMeshes_[i] || s.version == surfaceVersions_[i]) continue;
    surfaceVertices(s, vertexScratch_);
    glBindBuffer(GL_ARRAY_BUFFER, surfaceMeshes_[i]->vbo);
    glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(vertexScratch_.size() * sizeof(float)), vertexScratch_.data());
    surfaceVersions_[i] = s.version;
  }
  // Granular particles a frame moved.
  for (std::size_t bi = 0; bi < instancedRefs_.size() && bi < scene_.instanced.size(); ++bi) {
    const Instanced& src = scene_.instanced[bi];
    if (instancedRefs_[bi].size() != src.worlds.size() || src.version == instancedVersions_[bi]) continue;
    for (std::size_t k = 0; k < src.worlds.size(); ++k) {
      const InstanceRef& r = instancedRefs_[bi][k];
      Batch& b = batches_[r.batch];
      writeMatrix(b.instances[r.slot].data, src.worlds[k]);
      b.instances[r.slot].bounds = src.instanceBounds[k];
      b.dirty = true;
    }
    instancedVersions_[bi] = src.version;
  }
  for (std::size_t di = 0; di < drawableRefs_.size() && di < scene_.drawables.size(); ++di) {
    const Drawable& d = scene_.drawables[di];
    if (d.attachment.kind == Mount::Kind::World && d.surface < 0) continue;
    for (const InstanceRef& r : drawableRefs_[di]) {
      Batch& b = batches_[r.batch];
      Instance& in = b.instances[r.slot];
      writeMatrix(in.data, (r.placeholder ? d.placeholderWorld.value_or(d.world) : d.world) * r.post);
      in.bounds = d.bounds;
      b.dirty = true;
    }
  }
  ++poseVersion_;
}

}  // namespace detail

std::unique_ptr<Renderer> Renderer::create(const RenderScene& scene, const RenderOptions& options,
                                           Diagnostics& diagnostics) {
  return createRenderer(scene, options, diagnostics, {});
}

std::unique_ptr<Renderer> createRenderer(const RenderScene& scene, const RenderOptions& options,
                                         Diagnostics& diagnostics, std::vector<Camera> lodCameras) {
  auto t0 = detail::Clock::now();
  auto r = std::make_unique<detail::GlRenderer>(scene, options, diagnostics, std::move(lodCameras));
  if (!r->upload()) return nullptr;
  glFinish();
  r->addUploadSeconds(detail::seconds(t0, detail::Clock::now()));
  return r;
}

// lib/asset refuses a texture larger than --max-texture-pixels by its
// declared size, before decoding anything.
asset::AssetLimits assetLimits(const RenderOptions& o) {
  asset::AssetLimits l;
  l.image.maxPixels = o.maxTexturePixels;
  return l;
}

bool renderScene(const RenderScene& scene, const Camera& camera, const RenderOptions& options, Image& out,
                 Diagnostics& diags, RenderTimings* timings) {
  View view;
  view.name = camera.path;
  view.camera = camera;
  view.camera.width = options.width;
  view.camera.height = options.height;
  view.passes = {Pass::Color};
  // Round shapes tessellated for this one camera at the image's size.
  std::unique_ptr<Renderer> r = createRenderer(scene, options, diags, {view.camera});
  if (!r) return false;
  ViewImages images;
  bool ok = r->render(view, images, diags);
  if (ok) out = std::move(images.color);
  if (timings) *timings = r->timings();
  return ok;
}

}  // namespace rscene::render
