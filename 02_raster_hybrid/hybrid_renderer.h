// Stage 02: the raster/ray-tracing hybrid (Roger, Assarsson & Holzschuch 2007, "Whitted Ray-Tracing for Dynamic
// Scenes using a Ray-Space Hierarchy on the GPU"; Reis). Primary rays give exactly what rasterization gives, so
// the GPU rasterizes them into a G-buffer, and only the secondary rays (shadow, reflection, refraction) are traced,
// by the wavefront pipeline of common/gpu/wavefront.h with a brute-force traversal (common/shaders/brute_force.glsl,
// traced in slices of triangles: common/gpu/brute_force_traversal.h).
// Context, options, window, timers and stats come from common/gpu/gpu_stage.h; this is the per-frame code.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/gpu/brute_force_traversal.h"
#include "common/gpu/gpu_stage.h"

namespace rt {

class HybridRenderer : public gpu::GpuStage {
public:
    HybridRenderer();
    ~HybridRenderer() override;

protected:
    // No structure to build: brute force. Each sample rasterizes the G-buffer, then the pipeline shades and traces.
    void render_sample(const Scene& scene, const RenderSettings& settings, glm::vec2 offset) override;
    bool rasterizes_primary_rays() const override { return true; }
    std::vector<std::string> stage_programs() const override { return {"common/shaders/raster/primary_hits.comp"}; }

private:
    gpu::BruteForceTraversal brute_force_;
};

}  // namespace rt
