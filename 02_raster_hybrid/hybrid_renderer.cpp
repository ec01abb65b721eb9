#include "hybrid_renderer.h"

namespace rt {

// The traversal stage 02 plugs into the wavefront pipeline: every ray against every triangle, in slices of
// triangles (brute_force_traversal.h). The lambda reads the scene the frame uploaded.
HybridRenderer::HybridRenderer()
    : RasterizedPrimaryStage({}), brute_force_([this] { return gpu_scene().triangle_count(); }) {
    set_traversal(brute_force_.traversal());
}
HybridRenderer::~HybridRenderer() = default;

void HybridRenderer::render_sample(const Scene& scene, const RenderSettings& settings, glm::vec2 offset) {
    // The G-buffer gives the primary hits; the brute-force traversal traces the rest.
    rasterize_and_shade_sample(scene, settings, offset);
}

}  // namespace rt
