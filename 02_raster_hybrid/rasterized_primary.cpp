#include "rasterized_primary.h"

#include "gbuffer.h"

namespace rt {

RasterizedPrimary::RasterizedPrimary() = default;
// Declared here, where GBuffer is complete; the stage destroys it while the context is still current.
RasterizedPrimary::~RasterizedPrimary() = default;

void RasterizedPrimary::render_sample(const gpu::FrameInputs& frame, gpu::Wavefront& wavefront, glm::vec2 offset) {
    if (!gbuffer_) gbuffer_ = std::make_unique<gpu::GBuffer>();
    {
        // Primary visibility by rasterization into the G-buffer.
        auto raster = frame.timer.scope("raster");
        gbuffer_->render(frame.gpu_scene, frame.scene.camera, frame.scene.bounds, frame.settings.width,
                         frame.settings.height, offset);
        wavefront.record_pass("gbuffer");
    }
    // The pixels become the pipeline's primary hits; then shading and the secondary rays, bounce by bounce.
    frame.gpu_scene.bind();
    gbuffer_->shade_sample(wavefront, offset);
}

std::vector<std::string> RasterizedPrimary::programs() const {
    if (!gbuffer_) return {gpu::GBuffer::kPrimaryHitsProgram};
    return gbuffer_->programs();
}

}  // namespace rt
