#include "grid_renderer.h"

#include <stdexcept>

#include "02_raster_hybrid/rasterized_primary.h"
#include "common/gpu/gl/storage_limit.h"

namespace rt {

namespace {

// Whether any ray of the frame is traced: traced primaries, shadows with lights, or reflections/refractions.
bool needs_grid(const gpu::FrameInputs& frame) {
    const Effects& e = frame.settings.effects;
    const bool shadows = e.shadows && frame.scene.light_count() > 0;
    const bool secondary = frame.settings.max_depth > 0 && (e.reflections || e.refractions);
    return frame.primary_traced || shadows || secondary;
}

// --primary: stage 02's G-buffer (raster, the default) or camera rays through the grid (trace).
class GridPrimary final : public gpu::PrimaryVisibility {
public:
    explicit GridPrimary(const GridOptions& options) : options_(options) {}
    void render_sample(const gpu::FrameInputs& frame, gpu::Wavefront& wavefront, glm::vec2 offset) override {
        chosen().render_sample(frame, wavefront, offset);
    }
    bool rasterized() const override { return !options_.trace_primary; }
    std::vector<std::string> programs() const override { return chosen().programs(); }

private:
    gpu::PrimaryVisibility& chosen() {
        return options_.trace_primary ? static_cast<gpu::PrimaryVisibility&>(traced_) : raster_;
    }
    const gpu::PrimaryVisibility& chosen() const {
        return options_.trace_primary ? static_cast<const gpu::PrimaryVisibility&>(traced_) : raster_;
    }
    const GridOptions& options_;
    RasterizedPrimary raster_;
    gpu::TracedPrimary traced_;
};

}  // namespace

void GridTraversal::build(const gpu::FrameInputs& frame) {
    built_ = needs_grid(frame);
    if (!built_) return;   // every ray is rasterized: nothing to build
    if (!grid_) grid_ = std::make_unique<GpuGrid>();
    // The heuristic's grid must leave room in one storage block for the pairs too: when its cells alone would take
    // over half of it, lambda is halved until they do not (reported as lambda_used). --grid-res is taken as given.
    const Scene& scene = frame.scene;
    glm::ivec3 res = options_.res;
    lambda_used_ = options_.lambda;
    if (res.x == 0) {
        const std::size_t half_block = gpu::max_storage_block_bytes() / 2;
        for (;;) {
            res = choose_resolution(scene.bounds, scene.triangle_count(), lambda_used_);
            if (std::size_t(res.x) * res.y * res.z * 8 <= half_block || lambda_used_ < 1e-3f) break;
            lambda_used_ *= 0.5f;
        }
    }
    auto scope = frame.timer.scope("build");
    grid_->build(frame.gpu_scene, make_grid_params(scene.bounds, res, scene.triangle_count()));
}

void GridTraversal::bind() const {
    // needs_grid() follows the pipeline's own rule for which passes run; a traced ray without a grid is a bug.
    if (!built_) throw std::logic_error("03_uniform_grid: a ray was traced but no grid was built for this frame");
    grid_->bind();
}

std::vector<std::string> GridTraversal::programs() const {
    std::vector<std::string> programs;
    if (built_)
        for (const char* p : {"grid_count.comp", "grid_write.comp", "grid_ranges.comp"})
            programs.push_back(std::string("03_uniform_grid/shaders/") + p);
    return programs;
}

void GridTraversal::report(gpu::FrameReport& report) {
    GridFrameStats stats = built_ ? grid_->frame_stats() : GridFrameStats{};
    stats.trace_primary = options_.trace_primary;
    if (built_) {
        if (options_.res.x == 0) {   // the heuristic chose the resolution
            stats.lambda = options_.lambda;
            stats.lambda_used = lambda_used_;
        }
        stats.build_ms = report.result.stats.build_ms;
    }
    report.result.extra["grid"] = stats;
    report.syncs += stats.gpu_cpu_syncs;
}

GridRenderer::GridRenderer()
    : GpuStage(std::make_unique<GridPrimary>(grid_options), std::make_unique<GridTraversal>(grid_options)) {}

}  // namespace rt
