// The OpenGL Renderer (view.hpp) behind renderScene() and rscene-render's
// views: internal to lib/render.  renderer.cpp uploads the scene once
// (meshes, textures, instance data, programs); passes.cpp draws views:
// the lit color pass and the flat data pass (segmentation + linear depth).
//
// Instances stay on the CPU after the upload as well as on the GPU: each
// view draws a subset (a sensor view only world objects) with the
// instances inside its frustum first, so a batch's instance buffer is
// rewritten when the next view selects or orders differently, and
// updatePoses() rewrites only the matrices of what moved.
#pragma once
#include <GL/glcorearb.h>

#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "core/codes.hpp"
#include "asset/cache.hpp"
#include "render/gl_effects.hpp"
#include "render/gl_post.hpp"
#include "render/gl_lights.hpp"
#include "render/mesh.hpp"
#include "render/view.hpp"

namespace rscene::render::detail {

// Compiles and links a program (renderer.cpp); 0 with the log appended.
// The program belongs to the context, not the caller (never deleted
// there): the same sources give the same program again, its uniforms set
// back to zero, to every renderer made on the context.
GLuint linkProgram(const char* vertex, const char* fragment, std::string& log);
// Forgets the programs when their context ends (gl_context.cpp).
void forgetPrograms(void* eglContext);

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

// Per-instance floats: model (16), color (4), pbr (4), emissive rgb (3) and
// the segment color packed as 0xRRGGBB in a float (exact: < 2^24).
constexpr int kInstanceFloats = 28;

struct Instance {
  float data[kInstanceFloats];
  Eigen::AlignedBox3d bounds;  // world, for each view's frustum test
  bool worldObject = false;    // drawn by sensor views
};

struct Batch {
  std::shared_ptr<GpuMesh> mesh;
  GLuint texture = 0;
  bool blend = false, doubleSided = false, castShadow = true;
  // The ground plane or a terrain: drawn after everything else, so that
  // the depth test rejects what objects hide before it is shaded
  // (llvmpipe shades every fragment that passes; it has no pre-pass).
  bool background = false;
  // Its mesh is the unit box primitive and it is opaque: its instances
  // hide what is behind them (occlusion.hpp).
  bool occluder = false;
  std::vector<Instance> instances;  // in the order they were added
  GLuint vao = 0, instanceVbo = 0;
  // The GPU buffer holds instances[order[i]]: the first inView inside the
  // last view's frustum, then the rest of what that view may draw (they
  // still cast shadows).  dirty: a matrix changed since the upload.
  std::vector<std::uint32_t> order;
  GLsizei inView = 0, count = 0;
  bool dirty = true;
  bool everUploaded = false;
};

// Where a scene drawable's instances went, to move them (updatePoses).
struct InstanceRef {
  std::size_t batch = 0, slot = 0;
  Eigen::Affine3d post = Eigen::Affine3d::Identity();  // after Drawable::world (a capsule's parts)
  bool placeholder = false;                            // drawn at Drawable::placeholderWorld
};

// Framebuffers of one image size, made on first use and kept while views
// of that size follow (a size change remakes them).
struct ColorTargets {
  int width = 0, height = 0, samples = 0;
  GLuint msaaColor = 0, resolved = 0, final = 0;
  GLuint msaaDepth = 0;  // a texture: GL_TEXTURE_2D_MULTISAMPLE when samples > 1, else GL_TEXTURE_2D
  GLuint fbo[3] = {0, 0, 0};  // multisampled, resolved, final
};
// The single-sample target of one jittered lit pass (main_pass.hpp); the
// passes are averaged into ColorTargets' first framebuffer.
struct JitterTargets {
  int width = 0, height = 0;
  GLuint fbo = 0, color = 0;
  // Multisampled ids and depth: where the samples of a pixel differ.
  int idSamples = 0;
  GLuint idFbo = 0, ids = 0, idDepth = 0;
  // The instance ids of every sample side by side (w * samples x h), read
  // back to leave out what no sample sees.
  int spreadWidth = 0, spreadHeight = 0;
  GLuint spreadFbo = 0, spread = 0;
};
struct DataTargets {
  int width = 0, height = 0;
  GLuint segmentation = 0, depth = 0, z = 0, fbo = 0;
};

class GlRenderer final : public Renderer {
  friend class LightEffects;
  friend class VolumeEffects;
  friend class ReflectionEffects;
  friend class PostEffects;

 public:
  GlRenderer(const RenderScene& scene, const RenderOptions& options, Diagnostics& diagnostics,
             std::vector<Camera> lodCameras);
  ~GlRenderer() override;
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  bool upload();  // create(): false with an error diagnostic
  void updatePoses() override;
  void setParticleViews(const std::vector<Camera>& cameras) override;
  bool render(const View& view, ViewImages& out, Diagnostics& diagnostics) override;
  RenderTimings timings() const override { return timings_; }
  void addUploadSeconds(double s) { timings_.uploadSeconds += s; }

 private:
  // ---- upload (renderer.cpp)
  // `file`: the robot file `line` is in; empty: the scene.
  void diag(Severity s, const char* code, std::uint32_t line, std::string message, std::uint32_t column = 0,
            const std::string& file = {});
  bool assetProblem(std::uint32_t line, std::uint32_t column, const std::string& file, const std::string& message,
                    const char* code = rs::RS9001);
  // `usage` GL_DYNAMIC_DRAW for a deformable's surface, rewritten per frame.
  std::shared_ptr<GpuMesh> uploadMesh(const MeshData& m, const std::vector<Eigen::Vector4f>* colors = nullptr,
                                      GLenum usage = GL_STATIC_DRAW);
  std::shared_ptr<GpuMesh> primitive(Shape s, double capsuleR = 0, double capsuleH = 0, int segments = 48);
  int segmentsFor(const Eigen::AlignedBox3d& box) const;
  GLuint texture(const Image& image);
  GLuint texture(const std::shared_ptr<const Image>& image);
  bool materialTexture(const RenderMaterial& m, GLuint& out);
  const std::vector<TexturedPart>* meshFile(const std::string& path, std::uint32_t line, std::uint32_t column,
                                            const std::string& file, bool& failed);
  bool regularFile(const std::string& path) const;
  // Adds one instance; returns where it went.
  InstanceRef add(const std::shared_ptr<GpuMesh>& mesh, GLuint tex, bool blend, bool doubleSided, bool castShadow,
                  const Eigen::Affine3d& world, const Eigen::Vector4f& color, const Eigen::Vector4f& pbr,
                  const Eigen::Vector3f& emissive, int segment, const Eigen::AlignedBox3d& bounds, bool worldObject,
                  bool background = false, bool particles = false);
  bool uploadDrawables();
  void uploadTerrains();
  bool uploadInstanced();
  void uploadBackground();
  void uploadPoints();
  bool buildPrograms();
  void makeVertexArrays();
  // Points the batch's vertex array at its mesh's vertex and index buffers.
  void bindMesh(Batch& b);

  // ---- drawing (passes.cpp)
  // Chooses and orders each batch's instances for `view` (re-uploading a
  // batch only when that changed).
  void selectInstances(const View& view, const Eigen::Matrix4d& viewProj);
  // Makes `order` the batch's (its first inView drawn), uploading the
  // instance data when that changed; `data`: scratch.
  void setOrder(Batch& b, std::vector<std::uint32_t>& order, GLsizei inView, std::vector<float>& data);
  void drawBatches(GLuint prog, bool blendPass, bool shadowPass, bool flat = false);
  bool colorPass(const View& view, const Eigen::Matrix4d& viewProj, Image& out);
  bool dataPass(const View& view, const Eigen::Matrix4d& viewProj, ViewImages& out, bool wantDepth,
                bool wantSegmentation);
  bool colorTargets(int w, int h, int samples);
  // ---- the lit pass's layers (lit_layers.cpp, main_pass.hpp)
  // Opaque batches (after a depth pre-pass when `prepass`), point clouds,
  // then blended batches, into the bound framebuffer.
  void drawLayers(const View& view, const Eigen::Matrix4d& viewProj, bool prepass);
  // One single-sample pass per sample position, averaged into color_.fbo[0]
  // (single-sample then): MSAA's coverage at a software rasteriser's
  // early-depth speed.
  bool jitteredLayers(const View& view, const Eigen::Matrix4d& viewProj, int samples);
  bool jitterTargets(int w, int h);
  // Sets the stencil (of color_'s depth-stencil) to 1 where the `samples`
  // samples of a pixel do not all see the same triangle; false when it
  // cannot (then every pass draws every pixel).
  bool markEdges(const View& view, const Eigen::Matrix4d& viewProj, int samples);
  // After the opaque ids: moves the instances no sample sees out of view.
  void keepVisible(int samples, const std::vector<std::pair<std::size_t, GLuint>>& firstIds);
  const std::vector<Eigen::Vector2f>& samplePositions(int samples);
  bool dataTargets(int w, int h);
  bool glOk();

  const RenderScene& scene_;
  RenderOptions opt_;
  Diagnostics* diags_;
  std::vector<Camera> lodCameras_;  // round shapes are tessellated for these views
  std::map<std::string, std::shared_ptr<GpuMesh>> primitives_;
  std::map<std::string, std::vector<TexturedPart>> meshFiles_;
  std::map<std::string, GLuint> textures_;
  std::map<const Image*, GLuint> imageTextures_;
  asset::AssetCache ownAssets_;
  asset::AssetCache& assets_;  // a mesh or texture named many times is read once
  std::vector<GLuint> ownedTextures_;
  std::vector<std::shared_ptr<GpuMesh>> meshes_;
  std::vector<Batch> batches_;
  std::vector<std::size_t> drawOrder_;  // into batches_: background batches last
  // By mesh, texture, blend, double-sided, casting shadows, and granular
  // particles: those keep batches of their own, whose sphere
  // setParticleViews() re-tessellates for each frame's views (sharing one
  // with a large sphere near the camera kept 2,916 grains at 48 slices).
  std::map<std::tuple<GpuMesh*, GLuint, bool, bool, bool, bool>, std::size_t> batchIndex_;
  std::vector<std::vector<InstanceRef>> drawableRefs_;  // per RenderScene::drawables
  // Per RenderScene::surfaces: its vertex buffer and the version uploaded
  // (updatePoses() rewrites the vertices when the surface's moved on).
  std::vector<std::shared_ptr<GpuMesh>> surfaceMeshes_;
  std::vector<std::uint64_t> surfaceVersions_;
  // Per RenderScene::instanced: where each instance went, for the granular
  // batches trajectory frames move (others: empty), and the version uploaded.
  std::vector<std::vector<InstanceRef>> instancedRefs_;
  std::vector<std::uint64_t> instancedVersions_;
  std::vector<std::size_t> particleBatches_;  // batches holding granular particles, ascending
  std::vector<float> vertexScratch_;
  GLuint hdrTexture_ = 0;
  GLuint pointVao_ = 0, pointVbo_ = 0;
  std::vector<std::pair<GLint, GLsizei>> pointRanges_;
  std::vector<float> pointSizes_;
  std::vector<int> pointSegments_;
  GLuint surfaceProg_ = 0, shadowProg_ = 0, pointProg_ = 0, postProg_ = 0, dataProg_ = 0, pointDataProg_ = 0;
  GLuint prepassProg_ = 0, averageProg_ = 0, idProg_ = 0, edgeProg_ = 0, clearProg_ = 0,
         spreadProg_ = 0;  // main_pass.hpp
  GLuint emptyVao_ = 0;
  bool software_ = false;
  // Bumped by updatePoses(): shadow maps drawn at an older version are redrawn.
  std::uint64_t poseVersion_ = 1;
  // Whether anything a sensor does not see casts a shadow: when nothing
  // does, camera and sensor views share one shadow map.
  bool visualCasters_ = false;
  ColorTargets color_;
  DataTargets data_;
  JitterTargets jitter_;
  // Layers of surface per pixel the current view's in-view instances
  // estimate (selectInstances): picks the lit pass's strategy.
  double depthComplexity_ = 0;
  // The lit pass drew fewer instances than selectInstances chose (those no
  // sample sees, markEdges): a data pass of the same view selects again.
  bool reselect_ = false;
  std::map<int, std::vector<Eigen::Vector2f>> samplePositions_;  // per requested sample count
  RenderTimings timings_;
  // Where colorPass's post-processing began (its lit layers drawn): the
  // split of RenderTimings.
  std::chrono::steady_clock::time_point postStart_;
  // The lit pass's modules (gl_effects.hpp): freed after ~GlRenderer's body,
  // while the GL context still exists.
  std::unique_ptr<LightEffects> lights_;
  std::unique_ptr<VolumeEffects> volumes_;
  std::unique_ptr<ReflectionEffects> reflections_;
  std::unique_ptr<PostEffects> post_;  // after the lit pass (gl_post.hpp)
};

}  // namespace rscene::render::detail
