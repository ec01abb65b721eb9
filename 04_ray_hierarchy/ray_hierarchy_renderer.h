// Stage 04: the ray-space hierarchy (Roger, Assarsson & Holzschuch 2007). Primary visibility is stage 02's G-buffer;
// every bounce of secondary rays (shadow, reflection, refraction) is traced through a hierarchy built over that
// bounce's own rays (gpu_ray_hierarchy.h), a batch at a time. Nothing is built over the triangles but their bounding
// spheres, so a moving scene costs nothing extra. The image and every hit equal brute force's (stage 02's).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/gpu/pipeline/gpu_stage.h"
#include "gpu_ray_hierarchy.h"

namespace rt {

// The hierarchy as the pipeline's traversal: each batch of rays gets its hierarchy, traversed against the tree of
// the triangles' bounding spheres.
class HierarchyTraversal final : public gpu::Traversal {
public:
    explicit HierarchyTraversal(HierarchyOptions& options);
    ~HierarchyTraversal() override;

    void add_options(CLI::App& app) override;   // hierarchy_options.h
    // --heatmap on a scene with cut-outs: the leaf pass would need a 17th storage block (GL 4.5 guarantees 16).
    std::string unsupported(const Scene& scene, const RenderSettings& settings) const override;
    void build(const gpu::FrameInputs& frame) override;
    void trace_batch(const gpu::BatchTraceInputs& in, bool shadow) override;
    std::string steps() const override { return "leaf pairs"; }   // --pixel: a ray's pairs at level 0
    void report(gpu::FrameReport& report) override;               // hierarchy_stats.h
    std::vector<std::string> programs() const override { return GpuRayHierarchy::program_names(); }

    // The hierarchy of this frame (after build()), for stage 05.
    const GpuRayHierarchy& hierarchy() const { return *hierarchy_; }

private:
    HierarchyOptions& options_;                    // the stage's
    std::unique_ptr<GpuRayHierarchy> hierarchy_;   // created with the first frame (needs the context)
    bool traced_ = false;                          // whether any secondary ray was traced this frame
};

// Stage 02's rasterized primary visibility + the ray-space hierarchy.
class RayHierarchyRenderer : public gpu::GpuStage {
public:
    RayHierarchyRenderer();
    HierarchyOptions hierarchy_options;   // read by the traversal, which holds it by reference
};

}  // namespace rt
