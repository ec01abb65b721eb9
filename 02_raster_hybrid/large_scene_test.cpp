// Stage 02 on a scene beyond what one GPU invocation may loop over on llvmpipe (65,535 iterations in all; docs/gpu.md,
// "Known limit"): its brute force traces in slices of triangles (02_raster_hybrid/brute_force_traversal.h), so every
// secondary ray still finds exactly what stage 01's brute force finds, with the bounds of the hits tests
// (within 64 ulps, as tests/hits.cmake compares 02 with 01).
#include <gtest/gtest.h>

#include "01_naive/naive_renderer.h"
#include "02_raster_hybrid/brute_force_traversal.h"
#include "common/gpu/pipeline/gpu_stage.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "hybrid_renderer.h"
#include "tests/hit_compare.h"
#include "tests/stage_test_fixture.h"

namespace rt {
namespace {

Scene spheres_300() {
    FlattenOptions options;
    options.aspect = 4.0f / 3.0f;
    return flatten(make_builtin_scene("spheres:300"), options);
}

// Stage 02's traversal tracing the camera rays too (closest hits through the slices), as 03's --primary trace does.
class TracedBruteForce : public gpu::GpuStage {
public:
    TracedBruteForce()
        : GpuStage(std::make_unique<gpu::TracedPrimary>(), std::make_unique<gpu::BruteForceTraversal>()) {}
};

void expect_hits_like_stage01(const FrameResult& a, const Scene& scene, const RenderSettings& settings,
                              double primary_fraction) {
    NaiveRenderer stage01;
    const FrameResult b = stage01.render(scene, settings);
    HitCompareOptions bounds;
    bounds.primary_fraction = primary_fraction;
    bounds.ray_ulps = 64;
    bounds.t_ulps = 64;
    const HitComparison c = compare_hits(a.hits, b.hits, bounds);
    EXPECT_TRUE(c.passed(bounds)) << c.report(bounds);
    EXPECT_GT(c.count_a[int(RayKind::Shadow)], 100u);
}

TEST(BruteForceSlices, TracedRaysOfASceneBeyondOneInvocationsLoopLimitHitWhatStage01Hits) {
    gpu::test_context();
    const Scene scene = spheres_300();
    ASSERT_GT(scene.triangle_count(), 4u * 16384u);   // more than 65,535 and four slices
    const RenderSettings settings = test_frame_settings(scene, 32, 24);
    TracedBruteForce traced;
    expect_hits_like_stage01(traced.render(scene, settings), scene, settings, 0.0);
}

// Stage 02 itself, with the bounds of tests/hits.cmake (rasterized primaries: up to 0.5% may hit a neighbour across
// an edge, their trees left out; 6 of 3072 here): every other shadow ray answers as stage 01's.
TEST(BruteForceSlices, Stage02sShadowRaysOfASceneBeyondOneInvocationsLoopLimitAnswerAsStage01s) {
    gpu::test_context();
    const Scene scene = spheres_300();
    const RenderSettings settings = test_frame_settings(scene, 64, 48);
    HybridRenderer stage02;
    expect_hits_like_stage01(stage02.render(scene, settings), scene, settings, 0.005);
}

}  // namespace
}  // namespace rt
