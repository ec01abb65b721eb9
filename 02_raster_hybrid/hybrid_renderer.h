// Stage 02: the raster/ray-tracing hybrid (Roger, Assarsson & Holzschuch 2007, "Whitted Ray-Tracing for Dynamic
// Scenes using a Ray-Space Hierarchy on the GPU"; Reis). Primary rays give exactly what rasterization gives, so
// the GPU rasterizes them into a G-buffer (rasterized_primary_stage.h, gbuffer.h), and only the secondary rays
// (shadow, reflection, refraction) are traced, by the wavefront pipeline of common/gpu/pipeline/wavefront.h with a
// brute-force traversal (shaders/brute_force.glsl, traced in slices of triangles: brute_force_traversal.h).
// Context, options, window, timers and stats come from common/gpu/pipeline/gpu_stage.h; this is the per-frame code.
#pragma once

#include "02_raster_hybrid/brute_force_traversal.h"
#include "02_raster_hybrid/rasterized_primary_stage.h"

namespace rt {

class HybridRenderer : public RasterizedPrimaryStage {
public:
    HybridRenderer();
    ~HybridRenderer() override;

protected:
    // No structure to build: brute force. Each sample rasterizes the G-buffer, then the pipeline shades and traces.
    void render_sample(const Scene& scene, const RenderSettings& settings, glm::vec2 offset) override;

private:
    gpu::BruteForceTraversal brute_force_;
};

}  // namespace rt
