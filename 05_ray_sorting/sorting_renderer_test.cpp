// Stage 05's renderer: sorting changes the cost of the hierarchy, never the frame.
#include <gtest/gtest.h>

#include <cstdlib>

#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/testing/same_frame_expectations.h"
#include "common/scene/builtin/builtin_scenes.h"
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
    off.mode = SortMode::off;
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
    // Sorting reads nothing back inside a batch, however many batches there are: its read-backs are the frame
    // statistics' (the chunk sums, and auto's choices). The frame's total is the pipeline's (the same rays, so the
    // same as unsorted), the hierarchy's and the sorting's.
    const std::uint64_t sorting_syncs = b.extra["ray_sorting"]["gpu_cpu_syncs"];
    EXPECT_EQ(sorting_syncs, on.mode == SortMode::automatic ? 2u : 1u) << name;
    const std::uint64_t pipeline_a = std::uint64_t(a.extra["gpu_cpu_syncs"]) -
                                     std::uint64_t(a.extra["ray_hierarchy"]["gpu_cpu_syncs"]);
    const std::uint64_t pipeline_b = std::uint64_t(b.extra["gpu_cpu_syncs"]) -
                                     std::uint64_t(b.extra["ray_hierarchy"]["gpu_cpu_syncs"]) - sorting_syncs;
    EXPECT_EQ(pipeline_b, pipeline_a) << name;
    if (shadow_batches) *shadow_batches = std::uint64_t(shadow["batches"]);
}

// --sort on: every batch sorted, whatever the choice of --sort auto would be.
SortOptions always_sorted() {
    SortOptions on;
    on.mode = SortMode::on;
    return on;
}

TEST(RaySortingRenderer, SortOnAndOffGiveTheSameImageHitsAndRayCounts) {
    gpu::test_context();
    expect_same_frame_sorted_or_not("cornell", always_sorted(), 64, 48, true);   // shadow, reflection, refraction
    expect_same_frame_sorted_or_not("mirror_box", always_sorted(), 48, 36, false);   // many bounces between mirrors
    SortOptions coarse = always_sorted();
    coarse.key_bits = 9;   // few, large cells: long chunks
    coarse.direction_bits = 3;
    expect_same_frame_sorted_or_not("whitted", coarse, 64, 48, true);
}

// $RT_MAX_SSBO_BYTES = 48 KiB: the pipeline hands over many small batches (each sorted on its own); still the
// same frame.
TEST(RaySortingRenderer, ManySmallBatchesUnderATinyStorageLimitGiveTheSameFrame) {
    gpu::test_context();
    std::uint64_t batches = 0, small_batches = 0;
    expect_same_frame_sorted_or_not("cornell", always_sorted(), 64, 48, true, &batches);
    ::setenv("RT_MAX_SSBO_BYTES", "49152", 1);
    expect_same_frame_sorted_or_not("cornell", always_sorted(), 64, 48, true, &small_batches);
    ::unsetenv("RT_MAX_SSBO_BYTES");
    EXPECT_GT(small_batches, 2 * batches);
}

// --sort auto: the same frame as off and on; it keeps a batch's sorted order only where that order's level-1 nodes
// are tighter, and says how many it kept. Where it keeps none the hierarchy is exactly stage 04's (same node tests);
// where it keeps all, exactly --sort on's.
TEST(RaySortingRenderer, AutoGivesTheSameFrameAndKeepsTheSortOnlyWhereItIsTighter) {
    gpu::test_context();
    for (const char* name : {"cornell", "whitted", "spheres:45", "mirror_box"}) {
        const Scene s = builtin_scene(name);
        SortOptions off, on = always_sorted(), automatic;
        off.mode = SortMode::off;
        ASSERT_EQ(automatic.mode, SortMode::automatic) << "auto is the default";
        const FrameResult a = render_05(s, 48, 36, off), b = render_05(s, 48, 36, on), c = render_05(s, 48, 36,
                                                                                                   automatic);
        expect_same_frame(a, c, name);
        expect_same_frame(b, c, name);
        EXPECT_EQ(c.extra["ray_sorting"]["mode"], "auto") << name;
        const auto& batches = c.extra["ray_sorting"]["batches"];
        std::uint64_t kept = 0, all = 0;
        for (const char* kind : {"trace", "shadow"}) {
            if (!batches.contains(kind)) continue;
            EXPECT_LE(std::uint64_t(batches[kind]["sorted_batches"]), std::uint64_t(batches[kind]["batches"]));
            EXPECT_LE(std::uint64_t(batches[kind]["sorted_rays"]), std::uint64_t(batches[kind]["rays"]));
            kept += std::uint64_t(batches[kind]["sorted_batches"]);
            all += std::uint64_t(batches[kind]["batches"]);
            EXPECT_EQ(b.extra["ray_sorting"]["batches"][kind]["sorted_batches"], b.extra["ray_sorting"]["batches"][kind]
                                                                                     ["batches"]) << name;
        }
        const auto node_tests = [](const FrameResult& r) {
            std::uint64_t n = 0;
            for (const auto& [kind, k] : r.extra["ray_hierarchy"]["kinds"].items()) n += std::uint64_t(k["node_tests"]);
            return n;
        };
        if (kept == 0) {
            EXPECT_EQ(node_tests(c), node_tests(a)) << name << ": no sort kept is stage 04";
        }
        if (kept == all) {
            EXPECT_EQ(node_tests(c), node_tests(b)) << name << ": every sort kept is --sort on";
        }
    }
}

// --sort auto across frames: each batch takes the order that won when it was last measured (the queue's: no sort at
// all; a sorted one: that one sort, no second key, no measure) for probe_every - 1 frames, then it is measured again.
// The frames are all the same frame: the same image and hits as --sort off, and the same hierarchy (node tests) as the
// first, fully measured one, so every batch took the order its measure chose (absorption keeps fine orders,
// mirror_box coarse ones, and both leave some batches in queue order).
TEST(RaySortingRenderer, AutoTakesTheOrderThatWonUnmeasuredUntilItsNextProbe) {
    gpu::test_context();
    for (const char* name : {"absorption", "mirror_box"}) {
        const Scene s = builtin_scene(name);
        const RenderSettings settings = test_frame_settings(s, 48, 36, true);
        SortOptions off;
        off.mode = SortMode::off;
        const FrameResult reference = render_05(s, 48, 36, off);
        RaySortingRenderer renderer;
        renderer.sort_options.probe_every = 3;
        std::vector<FrameResult> frames;
        for (int f = 0; f < 5; ++f) frames.push_back(renderer.render(s, settings));
        const auto count = [](const FrameResult& r, const char* kind, const char* key) -> std::uint64_t {
            const auto& b = r.extra["ray_sorting"]["batches"];
            return b.contains(kind) ? std::uint64_t(b[kind][key]) : 0u;
        };
        std::uint64_t queue_won = 0, sorted = 0;
        for (const char* kind : {"trace", "shadow"}) {
            const std::uint64_t all = count(frames[0], kind, "batches"), kept = count(frames[0], kind,
                                                                                    "sorted_batches");
            const std::uint64_t fine = count(frames[0], kind, "fine_batches");
            for (int f : {0, 3}) {   // probe_every 3: frames 1 and 4 measure every batch
                const FrameResult& r = frames[std::size_t(f)];
                EXPECT_EQ(count(r, kind, "measured_batches"), all) << name << " " << kind << " frame " << f + 1;
                EXPECT_EQ(count(r, kind, "skipped_batches"), 0u) << name << " " << kind << " frame " << f + 1;
            }
            queue_won += all - kept;
            sorted += kept;
            for (int f : {1, 2, 4}) {   // frames 2, 3 and 5 take the orders frame 1 (or 4) chose
                const FrameResult& r = frames[std::size_t(f)];
                EXPECT_EQ(count(r, kind, "measured_batches"), 0u) << name << " " << kind << " frame " << f + 1;
                EXPECT_EQ(count(r, kind, "skipped_batches"), all - kept) << name << " " << kind << " frame " << f + 1;
                EXPECT_EQ(count(r, kind, "batches"), kept) << name << " " << kind << " frame " << f + 1;
                EXPECT_EQ(count(r, kind, "sorted_batches"), kept) << name << " " << kind << " frame " << f + 1;
                EXPECT_EQ(count(r, kind, "fine_batches"), fine) << name << " " << kind << " frame " << f + 1;
            }
        }
        EXPECT_GT(queue_won, 0u) << name << ": some batch must keep the queue's order";
        EXPECT_GT(sorted, 0u) << name << ": some batch must keep a sorted order";
        const auto counts = [](const FrameResult& r) {   // the hierarchy's counts per ray kind, not its times
            nlohmann::json kinds = r.extra["ray_hierarchy"]["kinds"];
            for (auto& [kind, k] : kinds.items()) k.erase("time_ms");
            return kinds;
        };
        for (const FrameResult& f : frames) {
            expect_same_frame(reference, f, name);
            EXPECT_EQ(counts(f), counts(frames[0])) << name;
            EXPECT_EQ(f.extra["ray_sorting"]["gpu_cpu_syncs"], 2u) << name << ": the choices come with the tally";
        }
    }
    const Scene s = builtin_scene("absorption");
    RaySortingRenderer renderer;
    renderer.render(s, test_frame_settings(s, 48, 36, true));
    const FrameResult second = renderer.render(s, test_frame_settings(s, 48, 36, true));
    EXPECT_GT(std::uint64_t(second.extra["ray_sorting"]["batches"]["trace"]["fine_batches"]), 0u)
        << "absorption's reflection and refraction batches keep the fine order, sorted by the fine key alone";
}

// A frame with more batches of a kind than the records hold (kOrderRecords; a tiny storage limit cuts the queue into
// many small batches): the batches past the records are measured every frame, the others remembered; the same frame.
TEST(RaySortingRenderer, BatchesPastTheRecordsAreMeasuredEveryFrame) {
    gpu::test_context();
    const Scene s = builtin_scene("cornell");
    const RenderSettings settings = test_frame_settings(s, 64, 48, true);
    ::setenv("RT_MAX_SSBO_BYTES", "20000", 1);
    SortOptions off;
    off.mode = SortMode::off;
    const FrameResult reference = render_05(s, 64, 48, off);
    RaySortingRenderer renderer;
    const FrameResult first = renderer.render(s, settings), second = renderer.render(s, settings);
    ::unsetenv("RT_MAX_SSBO_BYTES");
    const auto& a = first.extra["ray_sorting"]["batches"]["shadow"];
    const auto& b = second.extra["ray_sorting"]["batches"]["shadow"];
    const std::uint64_t batches = a["batches"];
    ASSERT_GT(batches, std::uint64_t(kOrderRecords)) << "the frame must have more shadow batches than records";
    EXPECT_EQ(std::uint64_t(a["measured_batches"]), batches);
    EXPECT_EQ(std::uint64_t(b["measured_batches"]), batches - kOrderRecords);
    EXPECT_EQ(std::uint64_t(b["batches"]) + std::uint64_t(b["skipped_batches"]), batches);
    expect_same_frame(reference, first, "cornell");
    expect_same_frame(reference, second, "cornell");
}

// --probe-every 1: every batch is sorted and measured in every frame.
TEST(RaySortingRenderer, ProbeEveryFrameSortsEveryBatchEveryFrame) {
    gpu::test_context();
    const Scene s = builtin_scene("whitted");
    const RenderSettings settings = test_frame_settings(s, 48, 36, true);
    RaySortingRenderer renderer;
    renderer.sort_options.probe_every = 1;
    const FrameResult first = renderer.render(s, settings), second = renderer.render(s, settings);
    for (const char* kind : {"trace", "shadow"}) {
        EXPECT_EQ(second.extra["ray_sorting"]["batches"][kind]["skipped_batches"], 0u) << kind;
        EXPECT_EQ(second.extra["ray_sorting"]["batches"][kind]["batches"],
                  first.extra["ray_sorting"]["batches"][kind]["batches"]) << kind;
    }
}

}  // namespace
}  // namespace rt
