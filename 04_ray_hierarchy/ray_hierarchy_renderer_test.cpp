// Stage 04's renderer: its image, hits and ray counts equal stage 02's for every branching, a --levels limit and
// every --objects mode, on later frames of a moving scene, and under tiny pair buffers and storage limits (many chunks
// and windows, a pruned hit list).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <tuple>

#include "02_raster_hybrid/hybrid_renderer.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/testing/frame_counts.h"
#include "common/gpu/testing/same_frame_expectations.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "ray_hierarchy_renderer.h"
#include "tests/stage_test_fixture.h"

namespace rt {
namespace {

FrameResult render_rh(const Scene& s, const RenderSettings& settings, HierarchyOptions o) {
    RayHierarchyRenderer renderer;
    renderer.hierarchy_options = o;
    return renderer.render(s, settings);
}

TEST(RayHierarchyRenderer, CornellEqualsStage02ForEveryBranchingAndALevelLimit) {
    gpu::test_context();
    const Scene s = builtin_scene("cornell");
    const RenderSettings settings = test_frame_settings(s);
    HybridRenderer stage02;
    const FrameResult reference = stage02.render(s, settings);
    for (const HierarchyOptions o :
         {HierarchyOptions{4, 0, ObjectMode::tree}, HierarchyOptions{8, 0, ObjectMode::tree},
          HierarchyOptions{16, 0, ObjectMode::tree}, HierarchyOptions{8, 2, ObjectMode::tree},
          HierarchyOptions{4, 0, ObjectMode::meshes}, HierarchyOptions{8, 2, ObjectMode::meshes},
          HierarchyOptions{4, 1, ObjectMode::triangles}}) {
        const FrameResult r = render_rh(s, settings, o);
        const std::string what = "B=" + std::to_string(o.branching) + " levels " + std::to_string(o.levels) + " " +
                                 object_mode_name(o.objects);
        expect_same_frame(r, reference, what);
        const auto& refl = r.extra["ray_hierarchy"]["kinds"]["reflection"];
        // At 64x48 neighbouring rays diverge: B = 4 still skips most tests, B = 16 fewer (see README.md).
        EXPECT_LT(double(refl["percent_of_brute_force"]), o.branching == 4 ? 25.0 : 75.0) << what;
        if (o.levels > 0) {
            EXPECT_EQ(refl["levels"].size(), std::size_t(o.levels) + 1) << what;
        }
        EXPECT_LT(r.stats.counters.intersection_tests, reference.stats.counters.intersection_tests) << what;
    }
}

TEST(RayHierarchyRenderer, LaterFramesOfTheDynamicSceneEqualStage02) {
    gpu::test_context();
    for (float time : {0.0f, 0.5f}) {
        const Scene s = builtin_scene("dynamic", time);
        const RenderSettings settings = test_frame_settings(s);
        HybridRenderer stage02;
        expect_same_frame(render_rh(s, settings, {}), stage02.render(s, settings), "dynamic t=" + std::to_string(time));
    }
}

std::vector<HitRecord> sorted_by_ray(std::vector<HitRecord> hits) {
    std::sort(hits.begin(), hits.end(), [](const HitRecord& a, const HitRecord& b) {
        return std::tie(a.pixel, a.sample, a.path, a.kind_light) < std::tie(b.pixel, b.sample, b.path, b.kind_light);
    });
    return hits;
}

// Pair buffers of 128 entries and a hit list of 2 entries per ray: the speculative tries run out of room and their
// groups are traced again (gpu_ray_hierarchy.h), in many chunks and windows, and the hit list fills up and is pruned;
// the frame is the same, pair for pair, and so are the tests counted. So it is without speculation.
TEST(RayHierarchyRenderer, TinyPairBuffersGiveTheSameImageHitsAndCounts) {
    gpu::test_context();
    const Scene s = builtin_scene("cornell");
    const RenderSettings settings = test_frame_settings(s);
    const FrameResult reference = render_rh(s, settings, {});
    HierarchyOptions tiny_options;
    tiny_options.pair_capacity = 128;
    tiny_options.hit_list_per_ray = 2;
    const FrameResult tiny = render_rh(s, settings, tiny_options);
    expect_same_frame(tiny, reference, "128 pairs per buffer");
    EXPECT_EQ(tiny.stats.counters.intersection_tests, reference.stats.counters.intersection_tests);
    const auto& t = tiny.extra["ray_hierarchy"];
    const auto& r = reference.extra["ray_hierarchy"];
    EXPECT_EQ(t["pair_capacity"], 128);
    EXPECT_GT(std::uint64_t(t["windows"]), 10 * std::uint64_t(r["windows"]));
    EXPECT_GT(std::uint64_t(t["hit_list_prunes"]), 0u);
    EXPECT_GT(std::uint64_t(t["groups_retraced"]), 0u);
    for (const char* kind : {"shadow", "reflection", "refraction"})
        for (const char* key : {"node_tests", "local_tests", "fold_tests"})
            EXPECT_EQ(t["kinds"][kind][key], r["kinds"][kind][key]) << kind << " " << key;
    tiny_options.speculate = false;
    const FrameResult windowed = render_rh(s, settings, tiny_options);
    expect_same_frame(windowed, reference, "128 pairs per buffer, no speculation");
    EXPECT_EQ(windowed.stats.counters.intersection_tests, reference.stats.counters.intersection_tests);
    EXPECT_EQ(windowed.extra["ray_hierarchy"]["groups_retraced"], 0);
    for (const char* kind : {"shadow", "reflection", "refraction"})
        for (const char* key : {"node_tests", "local_tests", "fold_tests"})
            EXPECT_EQ(windowed.extra["ray_hierarchy"]["kinds"][kind][key], r["kinds"][kind][key]) << kind << " " << key;
}

// $RT_MAX_SSBO_BYTES = 48 KiB: the pipeline's batches, and the stage's buffers with them, shrink (3072 pairs). The
// frame equals stage 02's under the same limit, hit for hit in the same order, and the unlimited frame's image.
TEST(RayHierarchyRenderer, ATinyStorageLimitGivesStage02sFrame) {
    gpu::test_context();
    const Scene s = builtin_scene("cornell");
    const RenderSettings settings = test_frame_settings(s);
    const FrameResult unlimited = render_rh(s, settings, {});
    ::setenv("RT_MAX_SSBO_BYTES", "49152", 1);
    const FrameResult tiny = render_rh(s, settings, {});
    HybridRenderer stage02;
    const FrameResult tiny02 = stage02.render(s, settings);
    ::unsetenv("RT_MAX_SSBO_BYTES");
    expect_same_frame(tiny, tiny02, "04 vs 02 at 48 KiB");
    EXPECT_EQ(tiny.extra["ray_hierarchy"]["pair_capacity"], 3072);
    for (std::size_t i = 0; i < tiny.image.pixels.size(); ++i)
        ASSERT_EQ(tiny.image.pixels[i], unlimited.image.pixels[i]) << "pixel " << i;
    const auto a = sorted_by_ray(tiny.hits), b = sorted_by_ray(unlimited.hits);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a[i].triangle, b[i].triangle) << "ray " << i;
        ASSERT_EQ(std::bit_cast<std::uint32_t>(a[i].t), std::bit_cast<std::uint32_t>(b[i].t)) << "ray " << i;
    }
}

// What a whitted frame asks of the GPU (common/gpu/gl/gl_counters.h), pinned so that a change to it shows here; the
// second frame finds the still scene resident and uploads none of it.
TEST(RayHierarchyRenderer, WhittedFrameCountsWhatItAsksOfTheGpu) {
    RayHierarchyRenderer stage;
    const auto counts = gpu::whitted_frame_counts(stage);
    EXPECT_EQ(counts[0], (gpu::FrameCounts{417, 24, 5, 550456, 17624}));
    EXPECT_EQ(counts[1], (gpu::FrameCounts{417, 24, 5, 0, 17624}));
}

}  // namespace
}  // namespace rt
