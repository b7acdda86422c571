// GLSL of the cube-face programs of image-based light and reflection
// probes (shader_reflections.cpp), drawn by gl_reflections.cpp with
// shaders::kPostVertex's full-screen triangle into one cube face at a time.
#pragma once
#include <string>

namespace rscene::render::shaders {

// The background (plain colour, HDR or the procedural sky) along each
// texel's direction; with uCapture, a probe camera's lit image over it.
std::string backgroundFaceFragment();
// A cube map prefiltered with the GGX lobe of one roughness.
std::string prefilterFragment();

}  // namespace rscene::render::shaders
