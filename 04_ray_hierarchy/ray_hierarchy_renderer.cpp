#include "ray_hierarchy_renderer.h"

#include "hierarchy_stats.h"

namespace rt {

RayHierarchyRenderer::RayHierarchyRenderer()
    : RasterizedPrimaryStage({.trace_batch = [this](const gpu::BatchTraceInputs& in) { trace_batch(in, false); },
                              .shadow_batch = [this](const gpu::BatchTraceInputs& in) { trace_batch(in, true); },
                              // --pixel: the ray's (ray, triangle) pairs at level 0, its own node tests
                              .steps = "leaf pairs"}) {}
RayHierarchyRenderer::~RayHierarchyRenderer() = default;

std::string RayHierarchyRenderer::unsupported(const Scene&, const RenderSettings& settings) const {
    // The leaf pass with the opacity test (cut-outs) binds 16 storage blocks, GL 4.5's guaranteed minimum and
    // llvmpipe's limit; counting tests per pixel would be the 17th, and the link fails after the compile.
    if (settings.record_tests_per_pixel && settings.effects.cutouts)
        return std::string(settings.watch_pixel >= 0 ? "--pixel" : "--heatmap") +
               ": not available in this stage for a scene with cut-outs (the leaf pass would need 17 GL "
               "storage blocks; GL 4.5 guarantees 16): use stage 03, or --effects without cutouts";
    return {};
}

void RayHierarchyRenderer::add_options(CLI::App& app) {
    RasterizedPrimaryStage::add_options(app);
    add_hierarchy_options(app, hierarchy_options);
}

void RayHierarchyRenderer::build(const Scene& scene, const RenderSettings&) {
    if (!hierarchy_) hierarchy_ = std::make_unique<GpuRayHierarchy>();
    hierarchy_->options = hierarchy_options;
    hierarchy_->timer = &timer();
    hierarchy_->reset_stats();
    traced_ = false;
    // The only per-frame work on the geometry: the triangles' bounding spheres and the objects (the tree).
    auto scope = timer().scope("build");
    hierarchy_->prepare(gpu_scene(), object_ranges(scene.material_ids), scene.bounds);
}

void RayHierarchyRenderer::trace_batch(const gpu::BatchTraceInputs& in, bool shadow) {
    traced_ = true;
    hierarchy_->trace(in, shadow);
}

void RayHierarchyRenderer::render_sample(const Scene& scene, const RenderSettings& settings, glm::vec2 offset) {
    rasterize_and_shade_sample(scene, settings, offset);
}

std::vector<std::string> RayHierarchyRenderer::stage_programs() const {
    std::vector<std::string> programs = RasterizedPrimaryStage::stage_programs();
    for (std::string& p : GpuRayHierarchy::program_names()) programs.push_back(std::move(p));
    return programs;
}

void RayHierarchyRenderer::add_stage_stats(FrameResult& result) {
    HierarchyFrameStats f = hierarchy_->frame_stats();   // the frame's one read of the GPU's sums
    f.traced = traced_;
    for (int k = 1; k < kRayKinds; ++k) {
        const std::string kind = ray_kind_name(RayKind(k));
        f.times[std::size_t(k)] = {pass_ms(result, "rh_build." + kind), pass_ms(result, "rh_traverse." + kind),
                                   pass_ms(result, "rh_local." + kind)};
    }
    f.fold_ms = pass_ms(result, "rh_local.fold");
    result.extra["ray_hierarchy"] = f;
    add_syncs(result, f.gpu_cpu_syncs);
}

}  // namespace rt
