#include "rasterized_primary_stage.h"

#include <utility>

#include "gbuffer.h"

namespace rt {

RasterizedPrimaryStage::RasterizedPrimaryStage(gpu::Traversal traversal) : GpuStage(std::move(traversal)) {}

// Declared here, where GBuffer is complete; runs before GpuStage's destructor, so the G-buffer's GL objects go
// while the context is still current.
RasterizedPrimaryStage::~RasterizedPrimaryStage() = default;

void RasterizedPrimaryStage::rasterize_and_shade_sample(const Scene& scene, const RenderSettings& settings,
                                                        glm::vec2 offset) {
    if (!gbuffer_) gbuffer_ = std::make_unique<gpu::GBuffer>();
    {
        // Primary visibility by rasterization into the G-buffer.
        auto raster = timer().scope("raster");
        gbuffer_->render(gpu_scene(), scene.camera, scene.bounds, settings.width, settings.height, offset);
        wavefront().record_pass("gbuffer");
    }
    // The pixels become the pipeline's primary hits; then shading and the secondary rays, bounce by bounce.
    gpu_scene().bind();
    gbuffer_->shade_sample(wavefront(), offset);
}

std::vector<std::string> RasterizedPrimaryStage::stage_programs() const {
    if (!gbuffer_) return {gpu::GBuffer::kPrimaryHitsProgram};
    return gbuffer_->programs();
}

}  // namespace rt
