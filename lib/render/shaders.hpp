// GLSL 3.30 core sources of the renderer's programs.
#pragma once

namespace rscene::render::shaders {

extern const char* const kSurfaceVertex;    // instanced meshes (lit + shadow-depth passes)
extern const char* const kSurfaceFragment;  // GGX PBR, lights, shadow, ambient, fog
extern const char* const kDepthFragment;    // shadow map pass
extern const char* const kPointVertex;
extern const char* const kPointFragment;
extern const char* const kDataVertex;       // segmentation + linear depth (instanced meshes)
extern const char* const kPointDataVertex;  // the same for point clouds
extern const char* const kDataFragment;     // writes both targets
extern const char* const kPostVertex;       // full-screen triangle
extern const char* const kPostFragment;     // background, exposure, tone map, gamma

}  // namespace rscene::render::shaders
