#include "grid_renderer.h"

#include <stdexcept>

#include "common/gpu/gl/storage_limit.h"
#include "grid_stats.h"

namespace rt {

GridRenderer::GridRenderer()
    : RasterizedPrimaryStage({.glsl = "03_uniform_grid/shaders/grid.glsl",   // the 3D-DDA, per ray
                              .defines = {{"GRID_STATS", "1"}},
                              .bind = [this] { bind_grid(); },
                              .steps = "grid cells"}) {}
GridRenderer::~GridRenderer() = default;

void GridRenderer::add_options(CLI::App& app) {
    RasterizedPrimaryStage::add_options(app);
    add_grid_options(app, grid_options);
}

bool GridRenderer::needs_grid(const Scene& scene, const RenderSettings& settings, bool trace_primary) {
    const Effects& e = settings.effects;
    const bool shadows = e.shadows && scene.light_count() > 0;
    const bool secondary = settings.max_depth > 0 && (e.reflections || e.refractions);
    return trace_primary || shadows || secondary;
}

void GridRenderer::build(const Scene& scene, const RenderSettings& settings) {
    built_ = needs_grid(scene, settings, grid_options.trace_primary);
    if (!built_) return;   // every ray is rasterized: nothing to build
    if (!grid_) grid_ = std::make_unique<GpuGrid>();
    // The heuristic's grid must leave room in one storage block for the pairs too: when its cells alone would take
    // over half of it, lambda is halved until they do not (reported as lambda_used). --grid-res is taken as given.
    glm::ivec3 res = grid_options.res;
    lambda_used_ = grid_options.lambda;
    if (res.x == 0) {
        const std::size_t half_block = gpu::max_storage_block_bytes() / 2;
        for (;;) {
            res = choose_resolution(scene.bounds, scene.triangle_count(), lambda_used_);
            if (std::size_t(res.x) * res.y * res.z * 8 <= half_block || lambda_used_ < 1e-3f) break;
            lambda_used_ *= 0.5f;
        }
    }
    auto scope = timer().scope("build");
    grid_->build(gpu_scene(), make_grid_params(scene.bounds, res, scene.triangle_count()));
}

void GridRenderer::bind_grid() const {
    // needs_grid() follows the pipeline's own rule for which passes run; a traced ray without a grid is a bug.
    if (!built_) throw std::logic_error("03_uniform_grid: a ray was traced but no grid was built for this frame");
    grid_->bind();
}

void GridRenderer::render_sample(const Scene& scene, const RenderSettings& settings, glm::vec2 offset) {
    if (grid_options.trace_primary) {
        gpu_scene().bind();
        wavefront().trace_camera_sample(offset);
        return;
    }
    rasterize_and_shade_sample(scene, settings, offset);
}

std::vector<std::string> GridRenderer::stage_programs() const {
    std::vector<std::string> programs;
    if (!grid_options.trace_primary) programs = RasterizedPrimaryStage::stage_programs();
    if (built_)
        for (const char* p : {"grid_count.comp", "grid_write.comp", "grid_ranges.comp"})
            programs.push_back(std::string("03_uniform_grid/shaders/") + p);
    return programs;
}

void GridRenderer::add_stage_stats(FrameResult& result) {
    GridFrameStats stats;
    stats.built = built_;
    stats.trace_primary = grid_options.trace_primary;
    if (built_) {
        const GridParams& g = grid_->params();
        stats.resolution = g.res;
        if (grid_options.res.x == 0) {   // the heuristic chose the resolution
            stats.lambda = grid_options.lambda;
            stats.lambda_used = lambda_used_;
        }
        stats.cells = g.cell_count;
        stats.pairs = grid_->pairs();
        count_cell_occupancy(grid_->cell_ranges(), stats);
        stats.build_ms = result.stats.build_ms;
        // grid.glsl's counters: rays [k], cells visited [kRayKinds + k], tests [2 kRayKinds + k], bound reached
        // [3 kRayKinds].
        const std::vector<std::uint64_t> s = grid_->traversal_stats();
        for (std::size_t k = 0; k < std::size_t(kRayKinds); ++k)
            stats.walks[k] = {s[k], s[kRayKinds + k], s[2 * kRayKinds + k]};
        stats.loop_bound_reached = s[3 * kRayKinds];
        stats.gpu_cpu_syncs = grid_->syncs();
    }
    result.extra["grid"] = stats;
    add_syncs(result, stats.gpu_cpu_syncs);
}

}  // namespace rt
