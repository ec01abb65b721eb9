// Stage 03 on the GPU: the grid built by the GPU equals the CPU grid cell by cell; the GLSL walk (grid_walk.glsl)
// visits exactly the cells and t-ranges of walk_grid on the DDA hard cases; and the renderer's image and hits do not
// depend on the grid's resolution (only its cost does), equal stage 02's, and never reach the walk's loop bound.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "01_naive/naive_renderer.h"
#include "02_raster_hybrid/hybrid_renderer.h"
#include "common/gpu/testing/glsl_test_harness.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/testing/frame_counts.h"
#include "common/gpu/testing/same_frame_expectations.h"
#include "common/gpu/gl/storage_limit.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "dda_cases.h"
#include "tests/hit_compare.h"
#include "tests/stage_test_fixture.h"
#include "gpu_grid.h"
#include "grid_renderer.h"

namespace rt {
namespace {

// ---------------------------------------------------------------------------------------------------------------
// The GPU build equals the CPU build.

void expect_same_grid(const Scene& s, glm::ivec3 res, const std::string& what) {
    gpu::test_context();
    gpu::GpuScene gpu_scene;
    gpu_scene.upload(s);
    GpuGrid gpu_grid;
    gpu_grid.build(gpu_scene, make_grid_params(s.bounds, res, s.triangle_count()));
    const CpuGrid cpu = build_grid(s, res);
    ASSERT_EQ(gpu_grid.pairs(), cpu.pairs()) << what;
    const std::vector<std::uint32_t> ranges = gpu_grid.cell_ranges(), triangles = gpu_grid.triangles();
    for (std::size_t c = 0; c < cpu.cells.size(); ++c) {
        const std::vector<std::uint32_t> list(triangles.begin() + ranges[2 * c], triangles.begin() + ranges[2 * c + 1]);
        ASSERT_EQ(list, cpu.cells[c]) << what << ", cell " << c;
    }
}

TEST(GpuGrid, EqualsTheCpuGridCellByCell) {
    for (const char* name : {"whitted", "cornell", "diffuse", "spheres:16", "far"}) {
        const Scene s = builtin_scene(name);
        expect_same_grid(s, choose_resolution(s.bounds, s.triangle_count(), kDefaultGridLambda), name);
        expect_same_grid(s, {1, 1, 1}, std::string(name) + " one cell");
        expect_same_grid(s, {7, 3, 5}, std::string(name) + " 7x3x5");
    }
}

// The floor quad of spheres:450 spans about 57,000 of the 239x8x239 cells: far more than one shader invocation may
// loop over on llvmpipe (65,535 iterations in all), so the build must split a triangle's cells across invocations.
TEST(GpuGrid, EqualsTheCpuGridOnALargeFlatGridUnderAWideQuad) {
    const Scene s = builtin_scene("spheres:450");
    expect_same_grid(s, choose_resolution(s.bounds, s.triangle_count(), kDefaultGridLambda), "spheres:450");
}

// One triangle over a whole 1024x1024x1 grid (a million cells, 2,048 build chunks).
TEST(GpuGrid, EqualsTheCpuGridForOneTriangleOverAMillionCells) {
    const Scene s = builtin_scene("spheres:1");
    expect_same_grid(s, {1024, 1, 1024}, "spheres:1 on 1024x1x1024");
}

TEST(GpuGrid, EqualsTheCpuGridOnFramesOfTheDynamicScene) {
    for (float time : {0.0f, 0.25f, 0.5f, 1.75f}) {
        const Scene s = builtin_scene("dynamic", time);
        expect_same_grid(s, choose_resolution(s.bounds, s.triangle_count(), kDefaultGridLambda),
                         "dynamic at t = " + std::to_string(time));
    }
}

// ---------------------------------------------------------------------------------------------------------------
// The GLSL walk against walk_grid.

constexpr std::size_t kMaxSteps = 96;
constexpr std::size_t kOutStride = 1 + 3 * kMaxSteps;

const char* kWalkBody = R"(
#include "03_uniform_grid/shaders/grid_walk.glsl"
void test_main() {
    const Ray r = make_ray(in_vec3(0), in_vec3(3), in_f(6));
    GridWalk w;
    uint n = 0u;
    if (grid_walk_begin(r, w)) {
        for (int i = 0; i < grid_walk_bound(); ++i) {
            grid_walk_cell_end(r, w);
            if (n < 96u) {
                out_u(1u + 3u * n, grid_cell_index(w.cell));
                out_f(2u + 3u * n, w.t);
                out_f(3u + 3u * n, w.t1);
            }
            ++n;
            if (!grid_walk_next(w)) break;
        }
    }
    out_u(0u, n);
}
)";

std::uint32_t bits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

// Runs the cases (all on the grid of the first) through the GLSL walk; expects walk_grid's steps, bit for bit.
void expect_glsl_walks_like_cpu(const std::vector<dda_cases::DdaCase>& cases) {
    gpu::test_context();
    static gpu::GlslTestHarness harness("grid_walk", kWalkBody);
    const GridParams& g = cases[0].grid;
    std::vector<std::uint32_t> header(GpuGrid::kHeaderBytes / 4 + 2, 0u);
    std::memcpy(header.data(), &g, sizeof g);
    gpu::Buffer grid = gpu::Buffer::from(header);
    gpu::Words in;
    for (const auto& c : cases) in << c.origin << c.direction << c.tmax;
    const std::vector<std::uint32_t> out =
        harness.run(in.words, cases.size(), 7, kOutStride, [&] { grid.bind(24); });
    for (std::size_t i = 0; i < cases.size(); ++i) {
        std::vector<GridStep> steps;
        walk_grid(g, cases[i].origin, cases[i].direction, cases[i].tmax, [&](const GridStep& s) {
            steps.push_back(s);
            return true;
        });
        const std::uint32_t* o = &out[i * kOutStride];
        ASSERT_EQ(o[0], steps.size()) << cases[i].name;
        for (std::size_t k = 0; k < std::min(steps.size(), kMaxSteps); ++k) {
            const GridStep& s = steps[k];
            EXPECT_EQ(o[1 + 3 * k], std::uint32_t(s.cell.x + g.res.x * (s.cell.y + g.res.y * s.cell.z)))
                << cases[i].name << " step " << k;
            EXPECT_EQ(o[2 + 3 * k], bits(s.t0)) << cases[i].name << " step " << k;
            EXPECT_EQ(o[3 + 3 * k], bits(s.t1)) << cases[i].name << " step " << k;
        }
    }
}

class GlslDdaHardCase : public ::testing::TestWithParam<dda_cases::DdaCase> {};

TEST_P(GlslDdaHardCase, VisitsTheCellsAndTRangesOfTheCppWalk) { expect_glsl_walks_like_cpu({GetParam()}); }

INSTANTIATE_TEST_SUITE_P(Glsl, GlslDdaHardCase, ::testing::ValuesIn(dda_cases::cases()),
                         [](const auto& test_case) { return test_case.param.name; });

TEST(GlslDda, RandomRaysWalkLikeTheCpp) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<dda_cases::DdaCase> cases;
    const GridParams g = dda_cases::grid({9, 4, 13}, {-1.0f, 0.5f, 2.0f}, {0.3f, 0.7f, 0.2f});
    for (int i = 0; i < 500; ++i) {
        dda_cases::DdaCase c{"random " + std::to_string(i), g, {4.0f * u(rng), 4.0f * u(rng), 4.0f * u(rng)},
                             {u(rng), u(rng), u(rng)}};
        if (i % 4 == 0) c.direction[i % 3] = i % 8 == 0 ? 0.0f : -0.0f;
        cases.push_back(c);
    }
    expect_glsl_walks_like_cpu(cases);
}

// ---------------------------------------------------------------------------------------------------------------
// The renderer: resolution changes only the cost; the image and hits equal stage 02's.

FrameResult render_grid(const Scene& s, const RenderSettings& settings, GridOptions options) {
    GridRenderer renderer;
    renderer.grid_options = options;
    return renderer.render(s, settings);
}

TEST(GridRenderer, LambdaAndResolutionChangeOnlyTheCost) {
    gpu::test_context();
    for (const char* name : {"whitted", "spheres:16"}) {
        const Scene s = builtin_scene(name);
        const RenderSettings settings = test_frame_settings(s);
        const FrameResult reference = render_grid(s, settings, {});
        EXPECT_EQ(reference.extra["grid"]["loop_bound_reached"], 0);
        std::uint64_t tests_reference = reference.stats.counters.intersection_tests;
        bool cost_changed = false;
        for (GridOptions o : {GridOptions{0.25f}, GridOptions{20.0f}, GridOptions{4.0f, {1, 1, 1}},
                              GridOptions{4.0f, {13, 2, 7}}}) {
            const FrameResult r = render_grid(s, settings, o);
            expect_same_frame(r, reference, std::string(name) + " lambda " + std::to_string(o.lambda) + " res " +
                                                std::to_string(o.res.x));
            EXPECT_EQ(r.extra["grid"]["loop_bound_reached"], 0);
            cost_changed |= r.stats.counters.intersection_tests != tests_reference;
        }
        EXPECT_TRUE(cost_changed) << name;
    }
}

TEST(GridRenderer, ImageAndHitsEqualStage02s) {
    gpu::test_context();
    const Scene s = builtin_scene("whitted");
    const RenderSettings settings = test_frame_settings(s);
    HybridRenderer stage02;
    expect_same_frame(render_grid(s, settings, {}), stage02.render(s, settings), "03 vs 02");
}

// Traced primary rays: the same frame as brute force tracing them (02_raster_hybrid/shaders/brute_force.glsl through the same pipeline).
class TracedBruteForce : public gpu::GpuStage {
public:
    TracedBruteForce()
        : GpuStage(std::make_unique<gpu::TracedPrimary>(),
                   std::make_unique<gpu::GlslTraversal>("02_raster_hybrid/shaders/brute_force.glsl")) {}
};

TEST(GridRenderer, TracedPrimaryRaysGiveBruteForcesFrame) {
    gpu::test_context();
    for (const char* name : {"whitted", "far"}) {
        const Scene s = builtin_scene(name);
        const RenderSettings settings = test_frame_settings(s);
        TracedBruteForce brute;
        GridOptions options;
        options.trace_primary = true;
        const FrameResult grid = render_grid(s, settings, options);
        const FrameResult reference = brute.render(s, settings);
        expect_same_frame(grid, reference, name);
        EXPECT_GT(grid.extra["grid"]["traversal"]["primary"]["rays"], 0);
        EXPECT_EQ(grid.extra["grid"]["loop_bound_reached"], 0);
        // The frame's read-backs: the pipeline's (the same rays as brute force's, so as many) and the grid's: three
        // in its build, two for its statistics.
        EXPECT_EQ(grid.extra["grid"]["gpu_cpu_syncs"], 5u) << name;
        EXPECT_EQ(std::uint64_t(grid.extra["gpu_cpu_syncs"]), std::uint64_t(reference.extra["gpu_cpu_syncs"]) + 5u)
            << name;
    }
}

// The large flat grid whose floor quad an unsplit build would cut short on llvmpipe (GpuGrid test above): every
// traced ray finds what stage 01's brute force finds, floor included. (Its 100,802 triangles are beyond what one GPU
// invocation may loop over on llvmpipe, so the reference is the CPU's brute force, not brute_force.glsl.)
TEST(GridRenderer, TracedRaysOfALargeFlatGridHitWhatStage01Hits) {
    gpu::test_context();
    const Scene s = builtin_scene("spheres:450");
    RenderSettings settings = test_frame_settings(s);
    settings.width = 32;
    settings.height = 24;
    GridOptions options;
    options.trace_primary = true;
    const FrameResult grid = render_grid(s, settings, options);
    NaiveRenderer stage01;
    const HitComparison c = compare_hits(grid.hits, stage01.render(s, settings).hits, {});
    EXPECT_TRUE(c.passed({})) << c.report({});
    EXPECT_EQ(c.count_a[0], 32u * 24u);
    EXPECT_GT(c.compared, 0u);
    EXPECT_EQ(grid.extra["grid"]["loop_bound_reached"], 0);
}

TEST(GridRenderer, AHeuristicGridTooLargeForTheStorageLimitLowersLambda) {
    gpu::test_context();
    const Scene s = builtin_scene("spheres:100");
    RenderSettings settings = test_frame_settings(s);
    settings.record_hits = false;
    const FrameResult r = render_grid(s, settings, GridOptions{900.0f});
    const double lambda_used = r.extra["grid"]["lambda_used"];
    EXPECT_LT(lambda_used, 900.0);
    EXPECT_LE(std::size_t(r.extra["grid"]["cells"]) * 8, gpu::max_storage_block_bytes() / 2);
}

TEST(GridRenderer, NothingIsBuiltWhenNoRayIsTraced) {
    gpu::test_context();
    const Scene s = builtin_scene("diffuse");
    RenderSettings settings = test_frame_settings(s);
    settings.effects = Effects{};   // rasterized primaries, no shadow, reflection or refraction rays
    const FrameResult r = render_grid(s, settings, {});
    EXPECT_EQ(r.extra["grid"]["built"], false);
    EXPECT_EQ(r.stats.build_ms, 0.0);
}

// What a whitted frame asks of the GPU (common/gpu/gl/gl_counters.h), pinned so that a change to it shows here; the
// second frame finds the still scene resident and uploads none of it.
TEST(GridRenderer, WhittedFrameCountsWhatItAsksOfTheGpu) {
    GridRenderer stage;
    const auto counts = gpu::whitted_frame_counts(stage);
    EXPECT_EQ(counts[0], (gpu::FrameCounts{82, 15, 6, 550456, 224}));
    EXPECT_EQ(counts[1], (gpu::FrameCounts{82, 15, 6, 0, 224}));
}

}  // namespace
}  // namespace rt
