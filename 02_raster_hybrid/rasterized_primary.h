// Stage 02's lesson: primary visibility by rasterization, not ray tracing. Primary rays find exactly what
// rasterization finds, so each sample draws the scene into a G-buffer (gbuffer.h: the triangle id per pixel), turns
// its pixels into the wavefront pipeline's primary hits (shaders/primary_hits.comp, exercise 02.primary_hits), and the
// pipeline traces only what comes after them. Every GPU stage (02-05) is this primary visibility plus a traversal
// (common/gpu/pipeline/gpu_stage.h); 03 may trace its camera rays instead (--primary trace).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/gpu/pipeline/primary_visibility.h"

namespace rt {

namespace gpu {
class GBuffer;
}

class RasterizedPrimary final : public gpu::PrimaryVisibility {
public:
    RasterizedPrimary();
    ~RasterizedPrimary() override;

    // One sample: this sample's G-buffer (timed as "raster"), whose pixels the pipeline then shades as primary hits
    // before tracing everything after them with the stage's traversal.
    void render_sample(const gpu::FrameInputs& frame, gpu::Wavefront& wavefront, glm::vec2 offset) override;
    bool rasterized() const override { return true; }
    // The G-buffer's programs (primary_hits.comp, and deferred_rays.comp with cut-outs).
    std::vector<std::string> programs() const override;

private:
    std::unique_ptr<gpu::GBuffer> gbuffer_;   // from the first sample (a GL context is current then)
};

}  // namespace rt
