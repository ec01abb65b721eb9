// Stage 04: the ray-space hierarchy (Roger, Assarsson & Holzschuch 2007). Primary visibility is stage 02's G-buffer
// (it derives from 02's RasterizedPrimaryStage);
// every bounce of secondary rays (shadow, reflection, refraction) is traced through a hierarchy built over that
// bounce's own rays (gpu_ray_hierarchy.h), through the wavefront pipeline's batch hook (Traversal::trace_batch and
// shadow_batch). Nothing is built over the triangles but their bounding spheres, so a moving scene costs nothing
// extra. The image and every hit equal brute force's (stage 02's).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "02_raster_hybrid/rasterized_primary_stage.h"
#include "gpu_ray_hierarchy.h"

namespace rt {

class RayHierarchyRenderer : public RasterizedPrimaryStage {
public:
    RayHierarchyRenderer();
    ~RayHierarchyRenderer() override;

    void add_options(CLI::App& app) override;   // the GPU options and hierarchy_options.h's
    // --heatmap on a scene with cut-outs: the leaf pass would need a 17th storage block (GL 4.5 guarantees 16).
    std::string unsupported(const Scene& scene, const RenderSettings& settings) const override;
    HierarchyOptions hierarchy_options;

protected:
    void build(const Scene& scene, const RenderSettings& settings) override;
    void render_sample(const Scene& scene, const RenderSettings& settings, glm::vec2 offset) override;
    std::vector<std::string> stage_programs() const override;
    void add_stage_stats(FrameResult& result) override;   // hierarchy_stats.h
    // One batch of the pipeline through the hierarchy (stage 05 overrides it to sort the batch's rays first).
    virtual void trace_batch(const gpu::BatchTraceInputs& in, bool shadow);
    // The hierarchy of this frame (after build()), for stage 05.
    const GpuRayHierarchy& hierarchy() const { return *hierarchy_; }

private:

    std::unique_ptr<GpuRayHierarchy> hierarchy_;   // created with the first frame (needs the context)
    bool traced_ = false;                          // whether any secondary ray was traced this frame
};

}  // namespace rt
