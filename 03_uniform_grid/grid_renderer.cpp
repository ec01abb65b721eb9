#include "grid_renderer.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "common/app/options.h"
#include "common/gpu/gl/storage_limit.h"

namespace rt {

glm::ivec3 parse_grid_res(const std::string& text) {
    glm::ivec3 res;
    std::istringstream in(text);
    char c1 = 0, c2 = 0;
    if (!(in >> res.x >> c1 >> res.y >> c2 >> res.z) || c1 != ',' || c2 != ',' || !(in >> std::ws).eof())
        throw std::invalid_argument("'" + text + "': expected X,Y,Z (three positive integers)");
    for (int a = 0; a < 3; ++a)
        if (res[a] < 1 || res[a] > kMaxGridResPerAxis)
            throw std::invalid_argument("'" + text + "': each axis must be in 1.." +
                                        std::to_string(kMaxGridResPerAxis));
    return res;
}

GridRenderer::GridRenderer()
    : RasterizedPrimaryStage({"03_uniform_grid/shaders/grid.glsl", {{"GRID_STATS", "1"}}, [this] { bind_grid(); }, {}, {}, "grid cells"}) {}
GridRenderer::~GridRenderer() = default;

void GridRenderer::add_options(CLI::App& app) {
    RasterizedPrimaryStage::add_options(app);
    app.add_option("--grid-lambda", grid_options.lambda,
                   "Grid cells per triangle for the resolution heuristic (changes the cost, never the image)")
        ->capture_default_str()
        ->check(number_in(1e-3, 1e3));   // finite: NaN and Inf are refused
    app.add_option_function<std::string>(
           "--grid-res", [this](const std::string& s) { grid_options.res = parse_grid_res(s); },
           "Grid resolution X,Y,Z instead of the heuristic")
        ->check(CLI::Validator(
            [](std::string& s) {
                try {
                    parse_grid_res(s);
                    return std::string();
                } catch (const std::invalid_argument& e) {
                    return std::string(e.what());
                }
            },
            "X,Y,Z"));
    app.add_option_function<std::string>(
           "--primary", [this](const std::string& s) { grid_options.trace_primary = s == "trace"; },
           "Primary rays: raster (stage 02's G-buffer, default) or trace (camera rays through the grid)")
        ->check(CLI::IsMember({"raster", "trace"}));
}

bool GridRenderer::needs_grid(const Scene& scene, const RenderSettings& settings, bool trace_primary) {
    const Effects& e = settings.effects;
    const bool shadows = e.shadows && !scene.lights.empty();
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
    nlohmann::json grid = {{"built", built_}, {"primary", grid_options.trace_primary ? "trace" : "raster"},
                           {"bounds", "Scene::bounds, from the CPU"}};
    if (!built_) {
        result.extra["grid"] = grid;
        return;
    }
    const GridParams& g = grid_->params();
    const std::vector<std::uint32_t> ranges = grid_->cell_ranges();
    std::size_t empty = 0, max_size = 0;
    for (std::size_t c = 0; c < g.cell_count; ++c) {
        const std::size_t size = ranges[2 * c + 1] - ranges[2 * c];
        empty += size == 0;
        max_size = std::max(max_size, size);
    }
    const std::size_t non_empty = g.cell_count - empty;
    grid["resolution"] = {g.res.x, g.res.y, g.res.z};
    grid["lambda"] = grid_options.res.x > 0 ? nlohmann::json(nullptr) : nlohmann::json(grid_options.lambda);
    grid["lambda_used"] = grid_options.res.x > 0 ? nlohmann::json(nullptr) : nlohmann::json(lambda_used_);
    grid["cells"] = g.cell_count;
    grid["pairs"] = grid_->pairs();
    grid["empty_cells"] = empty;
    grid["mean_triangles_per_nonempty_cell"] = non_empty ? double(grid_->pairs()) / double(non_empty) : 0.0;
    grid["max_triangles_per_cell"] = max_size;
    grid["build_ms"] = result.stats.build_ms;

    // The traversal's counters, per ray kind.
    const std::vector<std::uint64_t> s = grid_->traversal_stats();
    nlohmann::json kinds = nlohmann::json::object();
    // grid.glsl's layout: rays [k], cells visited [kRayKinds + k], tests [2 kRayKinds + k], bound reached [3 kRayKinds].
    for (int k = 0; k < kRayKinds; ++k) {
        if (s[std::size_t(k)] == 0) continue;
        const double rays = double(s[std::size_t(k)]);
        kinds[ray_kind_name(RayKind(k))] = {{"rays", s[std::size_t(k)]},
                                {"cells_visited_per_ray", double(s[std::size_t(kRayKinds + k)]) / rays},
                                {"tests_per_ray", double(s[std::size_t(2 * kRayKinds + k)]) / rays}};
    }
    grid["traversal"] = kinds;
    grid["loop_bound_reached"] = s[std::size_t(3 * kRayKinds)];
    result.extra["grid"] = grid;
}

}  // namespace rt
