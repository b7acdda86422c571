// LightEffects: the lit pass's direct light (internal to lib/render, beside
// gl_effects.hpp).  It keeps every light of the scene in a texture buffer
// (kLightTexels texels each), lists per view which local lights reach
// each 16x16-pixel tile (light_grid.hpp), and draws the shadow maps of the
// lights that cast shadows into one depth atlas (shadow_fit.hpp):
// directional lights fitted to what the view sees, spot lights as
// perspective maps, point and area lights (and spots wider than 60
// degrees) as six cube faces.  Its GLSL is shader_lights.cpp.
#pragma once
#include <GL/glcorearb.h>

#include <cstdint>
#include <vector>

#include "render/light_grid.hpp"
#include "render/shadow_fit.hpp"
#include "render/view.hpp"

namespace rscene::render::detail {

class GlRenderer;

// Texels (RGBA32F) per light in the light buffer; shader_lights.cpp reads
// the same layout.
inline constexpr int kLightTexels = 13;
inline constexpr int kLightTileSize = 16;
// Directional lights also given as uniforms (shader_lights.cpp: kHeadLights).
inline constexpr int kHeadLights = 8;

class LightEffects {
 public:
  explicit LightEffects(GlRenderer& r) : r_(r) {}
  ~LightEffects();
  LightEffects(const LightEffects&) = delete;
  LightEffects& operator=(const LightEffects&) = delete;
  // Switches on, in the surface program's source, the light code the scene
  // needs: the tile lists only with a point, spot or area light, the
  // buffer loop only past kHeadLights directional lights (llvmpipe pays
  // for compiled code at every fragment, taken or not).
  static void configure(const RenderScene& scene, std::string& fragmentSource);
  // The lights, which of them cast shadows and at what resolution, the
  // atlas and the buffers: false with an error diagnostic.
  bool upload();
  // Before a view's lit pass, outside it: redraws the shadow maps whose
  // casters moved (updatePoses), whose kind of view changed (a sensor
  // draws world objects only), or, for a fitted directional light, whose
  // box changed with the view.  Adds its time to RenderTimings::shadowSeconds.
  bool prepare(const View& view, const Eigen::Matrix4d& viewProj);
  // The lights, the view's tile lists and the shadow atlas on `program`,
  // with the maps the last prepare() drew (call it for the same view first).
  void bind(GLuint program, const View& view, const Eigen::Matrix4d& viewProj);

 private:
  enum class MapKind { None = 0, Ortho = 1, Perspective = 2, Cube = 3 };
  struct Caster {
    std::size_t light = 0;  // into lights_
    MapKind kind = MapKind::None;
    int resolution = 0;        // of the map, or of one cube face
    Eigen::Vector2i origin{0, 0};  // in the atlas, texels
    float strength = 1, bias = 0, pcfRadius = 1;
    bool fitted = false;            // a directional light fitted to each view
    std::vector<ShadowView> views;  // 1, or 6 cube faces
    Eigen::AlignedBox3d reachBox;   // what the light can reach (casters outside it are skipped)
  };

  void chooseCasters();
  bool makeAtlas();
  void makeShadowArrays();
  // Recomputes the views of every caster (the fitted ones only when
  // `fittedOnly`) for a camera of clip matrix `viewProj`.
  void placeViews(const Eigen::Matrix4d& viewProj, bool fittedOnly);
  void drawMap(const ShadowView& v, const Eigen::Vector2i& origin, int size, const Eigen::AlignedBox3d& reach,
               bool sensor, bool ortho);
  void writeLightBuffer();

  GlRenderer& r_;
  std::vector<RenderLight> lights_;  // directional ones first
  int directionalCount_ = 0;
  std::vector<float> reach_;
  std::vector<Eigen::AlignedBox3d> bounds_;  // what each light can reach
  // The local lights the grid lists: their boxes and indices into lights_.
  std::vector<Eigen::AlignedBox3d> localBounds_;
  std::vector<std::int32_t> localIndices_;
  std::size_t firstShadowed_ = 0;  // into localIndices_: where lights with shadow maps start
  std::vector<Caster> casters_;
  std::vector<int> casterOf_;  // per light: index into casters_, -1
  int atlasSide_ = 0;
  GLuint atlasTex_ = 0, atlasFbo_ = 0, depthProg_ = 0;
  GLuint lightBuffer_ = 0, lightTex_ = 0, gridBuffer_ = 0, gridTex_ = 0, instanceVbo_ = 0;
  std::vector<GLuint> shadowVaos_;  // per batch; 0 for batches that cast none
  std::uint64_t drawnVersion_ = 0;
  bool drawnForSensor_ = false;
  std::vector<float> texels_, matrices_;
  LightGrid grid_;
};

}  // namespace rscene::render::detail
