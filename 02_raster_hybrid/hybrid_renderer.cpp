#include "hybrid_renderer.h"

namespace rt {

namespace {

// The traversal stage 02 plugs into the wavefront pipeline: every ray against every triangle.
gpu::Traversal brute_force_traversal() { return {"common/brute_force.glsl", {}, {}}; }

}  // namespace

HybridRenderer::HybridRenderer() : GpuStage(brute_force_traversal()) {}
HybridRenderer::~HybridRenderer() = default;

void HybridRenderer::render_sample(const Scene& scene, const RenderSettings& settings, glm::vec2 offset) {
    // The G-buffer gives the primary hits; the brute-force traversal traces the rest.
    rasterize_and_shade_sample(scene, settings, offset);
}

}  // namespace rt
