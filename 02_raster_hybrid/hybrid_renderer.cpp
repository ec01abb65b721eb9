#include "hybrid_renderer.h"

namespace rt {

namespace {

// The traversal stage 02 plugs into the wavefront pipeline: every ray against every triangle.
gpu::Traversal brute_force_traversal() { return {"02_raster_hybrid/brute_force.glsl", {}, {}}; }

}  // namespace

HybridRenderer::HybridRenderer() : GpuStage(brute_force_traversal()) {}
HybridRenderer::~HybridRenderer() = default;

void HybridRenderer::render_sample(const Scene& scene, const RenderSettings& settings, glm::vec2 offset) {
    if (!gbuffer_) gbuffer_ = std::make_unique<gpu::GBuffer>();
    {
        // Pass 1: primary visibility by rasterization, and the pixels become the pipeline's primary hits.
        auto raster = timer().scope("raster");
        gbuffer_->render(gpu_scene(), scene.camera, scene.bounds, settings.width, settings.height, offset);
        wavefront().record_pass("gbuffer");
        gpu_scene().bind();
        gbuffer_->push_primary_hits(wavefront(), settings.width, settings.height, offset);
    }
    // Passes 2..n: shading and the secondary rays, bounce by bounce.
    wavefront().shade_sample();
}

}  // namespace rt
