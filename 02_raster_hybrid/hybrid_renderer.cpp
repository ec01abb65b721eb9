#include "hybrid_renderer.h"

namespace rt {

namespace {

// The traversal stage 02 plugs into the wavefront pipeline: every ray against every triangle.
gpu::Traversal brute_force_traversal() { return {"common/brute_force.glsl", {}, {}}; }

}  // namespace

HybridRenderer::HybridRenderer() : GpuStage(brute_force_traversal()) {}
HybridRenderer::~HybridRenderer() = default;

void HybridRenderer::render_sample(const Scene& scene, const RenderSettings& settings, glm::vec2 offset) {
    if (!gbuffer_) gbuffer_ = std::make_unique<gpu::GBuffer>();
    {
        // Pass 1: primary visibility by rasterization into the G-buffer.
        auto raster = timer().scope("raster");
        gbuffer_->render(gpu_scene(), scene.camera, scene.bounds, settings.width, settings.height, offset);
        wavefront().record_pass("gbuffer");
    }
    // Passes 2..n: the pixels become the pipeline's primary hits, then shading and the secondary rays.
    gpu_scene().bind();
    gbuffer_->shade_sample(wavefront(), offset);
}

}  // namespace rt
