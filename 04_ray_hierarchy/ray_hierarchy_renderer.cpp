#include "ray_hierarchy_renderer.h"

#include "02_raster_hybrid/rasterized_primary.h"
#include "hierarchy_stats.h"

namespace rt {

HierarchyTraversal::HierarchyTraversal(HierarchyOptions& options) : options_(options) {}
HierarchyTraversal::~HierarchyTraversal() = default;

void HierarchyTraversal::add_options(CLI::App& app) { add_hierarchy_options(app, options_); }

std::string HierarchyTraversal::unsupported(const Scene&, const RenderSettings& settings) const {
    // The leaf pass with the opacity test (cut-outs) binds 16 storage blocks, GL 4.5's guaranteed minimum and
    // llvmpipe's limit; counting tests per pixel would be the 17th, and the link fails after the compile.
    if (settings.record_tests_per_pixel && settings.effects.cutouts)
        return std::string(settings.watch_pixel >= 0 ? "--pixel" : "--heatmap") +
               ": not available in this stage for a scene with cut-outs (the leaf pass would need 17 GL "
               "storage blocks; GL 4.5 guarantees 16): use stage 03, or --effects without cutouts";
    return {};
}

void HierarchyTraversal::build(const gpu::FrameInputs& frame) {
    if (!hierarchy_) hierarchy_ = std::make_unique<GpuRayHierarchy>();
    hierarchy_->options = options_;
    hierarchy_->timer = &frame.timer;
    hierarchy_->reset_stats();
    traced_ = false;
    // The only per-frame work on the geometry: the triangles' bounding spheres and the objects (the tree).
    auto scope = frame.timer.scope("build");
    hierarchy_->prepare(frame.gpu_scene, object_ranges(frame.scene.material_ids), frame.scene.bounds);
}

// One batch: a hierarchy over its rays, built bottom-up, traversed top-down (gpu_ray_hierarchy.h).
void HierarchyTraversal::trace_batch(const gpu::BatchTraceInputs& in, bool shadow) {
    traced_ = true;
    hierarchy_->trace(in, shadow);
}

void HierarchyTraversal::report(gpu::FrameReport& report) {
    HierarchyFrameStats f = hierarchy_->frame_stats();   // the frame's one read of the GPU's sums
    f.traced = traced_;
    for (int k = 1; k < kRayKinds; ++k) {
        const std::string kind = ray_kind_name(RayKind(k));
        f.times[std::size_t(k)] = {report.pass_ms("rh_build." + kind), report.pass_ms("rh_traverse." + kind),
                                   report.pass_ms("rh_local." + kind)};
    }
    f.fold_ms = report.pass_ms("rh_local.fold");
    report.result.extra["ray_hierarchy"] = f;
    report.syncs += f.gpu_cpu_syncs;
}

RayHierarchyRenderer::RayHierarchyRenderer()
    : GpuStage(std::make_unique<RasterizedPrimary>(), std::make_unique<HierarchyTraversal>(hierarchy_options)) {}

}  // namespace rt
