// Stage 02's lesson as a base class: a GPU stage whose primary rays are rasterized, not traced. Primary rays find
// exactly what rasterization finds, so each sample draws the scene into a G-buffer (gbuffer.h: the triangle id per
// pixel), turns its pixels into the wavefront pipeline's primary hits (shaders/primary_hits.comp, exercise
// 02.primary_hits) and traces only what comes after them. Stage 02 (hybrid_renderer.h) traces those secondary rays by
// brute force; stages 03 and 04 derive from this class too and keep its primary visibility, replacing only the
// traversal (03 may also trace its primary rays: --primary trace).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/gpu/pipeline/gpu_stage.h"

namespace rt {

namespace gpu {
class GBuffer;
}

class RasterizedPrimaryStage : public gpu::GpuStage {
public:
    explicit RasterizedPrimaryStage(gpu::Traversal traversal);
    ~RasterizedPrimaryStage() override;

protected:
    // One sample: this sample's G-buffer (timed as "raster"), whose pixels the pipeline then shades as primary hits
    // before tracing everything after them with the stage's traversal.
    void rasterize_and_shade_sample(const Scene& scene, const RenderSettings& settings, glm::vec2 offset);
    bool rasterizes_primary_rays() const override { return true; }
    // The G-buffer's programs (primary_hits.comp, and deferred_rays.comp with cut-outs).
    std::vector<std::string> stage_programs() const override;

private:
    std::unique_ptr<gpu::GBuffer> gbuffer_;   // from the first sample (a GL context is current then)
};

}  // namespace rt
