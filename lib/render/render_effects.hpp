// Fills RenderScene's decals, fogs, irradiance volumes, probes and the
// post-processing and shadow fields of its Look from the scene model
// (internal to lib/render: prepareScene() calls it).
#pragma once
#include "core/document.hpp"
#include "render/render_scene.hpp"
#include "scene/scene.hpp"

namespace rscene::render {

void prepareEffects(const Document& doc, const Scene& scene, RenderScene& out);

}  // namespace rscene::render
