// Stage 05's renderer: sorting changes the cost of the hierarchy, never the frame.
#include <gtest/gtest.h>

#include <cstdlib>

#include "common/gpu/gpu_test_context.h"
#include "common/gpu/same_frame_expectations.h"
#include "common/scene/builtin_scenes.h"
#include "common/scene/effects.h"
#include "sorting_renderer.h"
#include "tests/stage_test_fixture.h"

namespace rt {
namespace {

FrameResult render_05(const Scene& s, int width, int height, SortOptions sort) {
    const RenderSettings settings = test_frame_settings(s, width, height, true);
    RaySortingRenderer renderer;
    renderer.sort_options = sort;
    return renderer.render(s, settings);
}

// Image, ray counts and every hit (in the pipeline's order) equal bit for bit; the sorted frame really sorted.
// `compresses`: neighbouring shadow rays share keys (not so where the pixels' footprints exceed the key's cells).
// `shadow_batches`, when given, gets how many shadow batches were sorted.
void expect_same_frame_sorted_or_not(const std::string& name, SortOptions on, int width, int height, bool compresses,
                                     std::uint64_t* shadow_batches = nullptr) {
    const Scene s = builtin_scene(name);
    SortOptions off = on;
    off.sort = false;
    const FrameResult a = render_05(s, width, height, off), b = render_05(s, width, height, on);
    expect_same_frame(a, b, name);
    if (::testing::Test::HasFatalFailure()) return;
    EXPECT_FALSE(bool(a.extra["ray_sorting"]["sort"])) << name;
    EXPECT_TRUE(bool(b.extra["ray_sorting"]["sort"])) << name;
    const auto& shadow = b.extra["ray_sorting"]["batches"]["shadow"];
    EXPECT_EQ(std::uint64_t(shadow["rays"]), a.stats.counters.rays[1]) << name << ": every shadow ray was sorted";
    if (compresses) {
        EXPECT_LT(std::uint64_t(shadow["chunks"]), std::uint64_t(shadow["rays"])) << name;
    }
    EXPECT_LE(std::uint64_t(shadow["chunks"]), std::uint64_t(shadow["rays"])) << name;
    // The same rays, a different hierarchy: the node tests differ (that is the point of sorting). The exact tests
    // do not: each (ray, triangle) pair gets the per-ray sphere test first, so the exact tests are the pairs whose
    // ray reaches the triangle's sphere, whatever hierarchy led there.
    for (const char* kind : {"shadow", "reflection", "refraction"}) {
        const auto& ka = a.extra["ray_hierarchy"]["kinds"], & kb = b.extra["ray_hierarchy"]["kinds"];
        if (!ka.contains(kind)) continue;
        EXPECT_EQ(ka[kind]["local_tests"], kb[kind]["local_tests"]) << name << " " << kind;
    }
    EXPECT_NE(a.extra["ray_hierarchy"]["kinds"]["shadow"]["node_tests"],
              b.extra["ray_hierarchy"]["kinds"]["shadow"]["node_tests"]) << name;
    if (shadow_batches) *shadow_batches = std::uint64_t(shadow["batches"]);
}

TEST(RaySortingRenderer, SortOnAndOffGiveTheSameImageHitsAndRayCounts) {
    gpu::test_context();
    expect_same_frame_sorted_or_not("cornell", {}, 64, 48, true);       // shadow, reflection and refraction rays
    expect_same_frame_sorted_or_not("mirror_box", {}, 48, 36, false);    // many bounces between mirrors
    SortOptions coarse;
    coarse.key_bits = 9;   // few, large cells: long chunks
    coarse.direction_bits = 3;
    expect_same_frame_sorted_or_not("whitted", coarse, 64, 48, true);
}

// $RT_MAX_SSBO_BYTES = 48 KiB: the pipeline hands over many small batches (each sorted on its own); still the
// same frame.
TEST(RaySortingRenderer, ManySmallBatchesUnderATinyStorageLimitGiveTheSameFrame) {
    gpu::test_context();
    std::uint64_t batches = 0, small_batches = 0;
    expect_same_frame_sorted_or_not("cornell", {}, 64, 48, true, &batches);
    ::setenv("RT_MAX_SSBO_BYTES", "49152", 1);
    expect_same_frame_sorted_or_not("cornell", {}, 64, 48, true, &small_batches);
    ::unsetenv("RT_MAX_SSBO_BYTES");
    EXPECT_GT(small_batches, 2 * batches);
}

}  // namespace
}  // namespace rt
