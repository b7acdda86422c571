// GLSL 3.30 core sources of the renderer's programs.
//
// The surface (lit) fragment is assembled by surfaceFragment() from a
// prelude (inputs, the `Surface` struct), the modules' GLSL and a main:
//   shader_lights.cpp       directLight(Surface): lights and shadows
//   shader_volumes.cpp      kFogGlsl (also the post pass's), then applyDecals, volumeIrradiance, applyFog
//   shader_reflections.cpp  indirectLight(Surface, irradiance): ambient, sky, probes
//   shader_sky.cpp          sky(dir): the procedural sky (also the post pass's)
// Each module declares the uniforms it reads; the renderer sets them.
#pragma once
#include <string>

namespace rscene::render::shaders {

extern const char* const kSurfaceVertex;    // instanced meshes (lit + shadow-depth passes)
extern const char* const kDepthFragment;    // shadow maps and the depth pre-pass
extern const char* const kShadowMapVertex;  // shadow maps: positions of instanced meshes (shader_lights.cpp)
extern const char* const kPointVertex;
extern const char* const kPointFragment;
extern const char* const kDataVertex;       // segmentation + linear depth (instanced meshes)
extern const char* const kPointDataVertex;  // the same for point clouds
extern const char* const kDataFragment;     // writes both targets
extern const char* const kPostVertex;       // full-screen triangle

// Pieces of the assembled programs.
extern const char* const kSurfacePrelude;
extern const char* const kSurfaceMain;
extern const char* const kLightsGlsl;
extern const char* const kVolumesGlsl;
extern const char* const kFogGlsl;  // height fog and fog spheres: the surface's and the post pass's
extern const char* const kReflectionsGlsl;
extern const char* const kSkyGlsl;
extern const char* const kPostPrelude;
extern const char* const kPostMain;

// GGX PBR, lights, shadows, decals, indirect light, fog; with the code of
// reflection probes when the scene has some.
std::string surfaceFragment(bool reflectionProbes = false);
std::string postFragment();     // background, exposure, tone map, gamma

// Post-processing passes (shader_post_effects.cpp, run by gl_post.cpp).
extern const char* const kDepthResolveFragment;
std::string ssaoFragment(bool multisampled);  // reading a multisampled depth buffer or a single one
extern const char* const kSsaoBlurFragment;
extern const char* const kBloomPrefilterFragment;
extern const char* const kBloomDownFragment;
extern const char* const kBloomUpFragment;
extern const char* const kLuminanceFragment;
extern const char* const kFxaaFragment;
std::string dofFragment();
std::string finalFragment();  // bloom and depth of field added, then exposure, tone map, gamma

}  // namespace rscene::render::shaders
