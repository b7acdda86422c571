// GLSL 3.30 core sources of the renderer's programs.
//
// The surface (lit) fragment is assembled by surfaceFragment() from a
// prelude (inputs, the `Surface` struct), the modules' GLSL and a main:
//   shader_lights.cpp       directLight(Surface): lights and shadows
//   shader_volumes.cpp      applyDecals, volumeIrradiance, applyFog
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
extern const char* const kReflectionsGlsl;
extern const char* const kSkyGlsl;
extern const char* const kPostPrelude;
extern const char* const kPostMain;

std::string surfaceFragment();  // GGX PBR, lights, shadows, decals, indirect light, fog
std::string postFragment();     // background, exposure, tone map, gamma

}  // namespace rscene::render::shaders
