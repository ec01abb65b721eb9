// Stage 05's renderer: sorting changes the cost of the hierarchy, never the frame.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/testing/frame_counts.h"
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

// The pairs the hierarchy tested in a frame, every kind: node tests and leaf pairs (GpuRayHierarchy::tally_pairs).
std::uint64_t pairs_tested(const FrameResult& r) {
    std::uint64_t n = 0;
    for (const auto& [kind, k] : r.extra["ray_hierarchy"]["kinds"].items())
        n += std::uint64_t(k["node_tests"]) + std::uint64_t(k["leaf_pairs"]);
    return n;
}

// A batch-kind count of a frame's "ray_sorting" statistics (0 where the kind had no batch).
std::uint64_t sort_count(const FrameResult& r, const char* kind, const char* key) {
    const auto& b = r.extra["ray_sorting"]["batches"];
    return b.contains(kind) ? std::uint64_t(b[kind][key]) : 0u;
}

// `count` frames of the built-in scene `name` at 48x36, one renderer with --sort auto every `probe_every` frames
// (and `costs`: --sort-batch-cost and --sort-ray-cost); `reference` gets the scene's --sort off frame (stage 04's).
struct SortCosts {
    unsigned batch = kSortBatchCost, ray = kSortRayCost;
};
constexpr SortCosts kAnySaving{0, 0};   // a kept sort stays if it saves any pair: the cycle's own tests
std::vector<FrameResult> auto_frames(const std::string& name, int count, unsigned probe_every, FrameResult& reference,
                                     SortCosts costs = {}) {
    // material_maps with its glowing panel not an area light (--area-lights off): its punctual light's shadow
    // batches are the ones whose kept sorts a check drops.
    FlattenOptions options;
    if (name == "material_maps") options.area_lights = AreaLightMode::Off;
    const Scene s = flatten(make_builtin_scene(name), options);
    SortOptions off;
    off.mode = SortMode::off;
    reference = render_05(s, 48, 36, off);
    RaySortingRenderer renderer;
    renderer.sort_options.probe_every = probe_every;
    renderer.sort_options.batch_cost = costs.batch;
    renderer.sort_options.ray_cost = costs.ray;
    std::vector<FrameResult> frames;
    for (int f = 0; f < count; ++f) frames.push_back(renderer.render(s, test_frame_settings(s, 48, 36, true)));
    return frames;
}

// --sort auto across frames (sorting_renderer.h), probe_every 4: frame 1 measures every batch; frame 2 traces the
// batches whose measure kept a sort in the queue's order, to check it (stage 04's frame exactly); frames 3 and 4 take
// the orders that won, unmeasured: the queue's (no sort at all) or the kept sort that tested fewer pairs than the
// queue's order did; frame 5 measures again, frame 6 checks again. Every frame is the same frame as --sort off (image
// and hits); the hierarchy's counts repeat with the cycle, and the remembered frames test no more pairs than either
// the measured frame or stage 04 (absorption and material_maps keep some sorts, drop some and leave some batches in
// the queue's order). The sort's cost is 0 here (any saving keeps a sort): at 48x36 no sort saves what its passes
// cost, and the cycle is the same with it.
TEST(RaySortingRenderer, AutoTakesTheOrderThatWonUnmeasuredUntilItsNextProbe) {
    gpu::test_context();
    for (const char* name : {"absorption", "material_maps"}) {
        FrameResult reference;
        const std::vector<FrameResult> frames = auto_frames(name, 6, 4, reference, kAnySaving);
        const auto counts = [](const FrameResult& r) {   // the hierarchy's counts per ray kind, not its times
            nlohmann::json kinds = r.extra["ray_hierarchy"]["kinds"];
            for (auto& [kind, k] : kinds.items()) k.erase("time_ms");
            return kinds;
        };
        std::uint64_t queue_won = 0, sorted = 0, dropped = 0;
        for (const char* kind : {"trace", "shadow"}) {
            const std::uint64_t all = sort_count(frames[0], kind, "batches");
            const std::uint64_t kept = sort_count(frames[0], kind, "sorted_batches");
            const std::uint64_t lost = sort_count(frames[1], kind, "sorts_dropped");
            EXPECT_LE(lost, kept) << name << " " << kind;
            for (int f : {0, 4}) {   // frames 1 and 5 measure every batch
                const FrameResult& r = frames[std::size_t(f)];
                EXPECT_EQ(sort_count(r, kind, "measured_batches"), all) << name << " " << kind << " frame " << f + 1;
                EXPECT_EQ(sort_count(r, kind, "skipped_batches"), 0u) << name << " " << kind << " frame " << f + 1;
            }
            for (int f : {1, 5}) {   // frames 2 and 6 trace every batch in the queue's order; the kept sorts checked
                const FrameResult& r = frames[std::size_t(f)];
                EXPECT_EQ(sort_count(r, kind, "measured_batches"), 0u) << name << " " << kind << " frame " << f + 1;
                EXPECT_EQ(sort_count(r, kind, "batches"), 0u) << name << " " << kind << " frame " << f + 1;
                EXPECT_EQ(sort_count(r, kind, "skipped_batches"), all) << name << " " << kind << " frame " << f + 1;
                EXPECT_EQ(sort_count(r, kind, "checked_batches"), kept) << name << " " << kind << " frame " << f + 1;
                EXPECT_EQ(sort_count(r, kind, "sorts_dropped"), lost) << name << " " << kind << " frame " << f + 1;
            }
            for (int f : {2, 3}) {   // frames 3 and 4 take the orders that won, unmeasured
                const FrameResult& r = frames[std::size_t(f)];
                EXPECT_EQ(sort_count(r, kind, "measured_batches"), 0u) << name << " " << kind << " frame " << f + 1;
                EXPECT_EQ(sort_count(r, kind, "checked_batches"), 0u) << name << " " << kind << " frame " << f + 1;
                EXPECT_EQ(sort_count(r, kind, "skipped_batches"), all - kept + lost) << name << " " << kind;
                EXPECT_EQ(sort_count(r, kind, "batches"), kept - lost) << name << " " << kind << " frame " << f + 1;
                EXPECT_EQ(sort_count(r, kind, "sorted_batches"), kept - lost) << name << " " << kind;
                EXPECT_LE(sort_count(r, kind, "fine_batches"), sort_count(frames[0], kind, "fine_batches")) << name;
            }
            queue_won += all - kept + lost;
            sorted += kept - lost;
            dropped += lost;
        }
        EXPECT_GT(queue_won, 0u) << name << ": some batch must keep the queue's order";
        EXPECT_GT(sorted, 0u) << name << ": some batch must keep a sorted order";
        EXPECT_GT(dropped, 0u) << name << ": some check must find the kept sort no better";
        for (const FrameResult& f : frames) {
            expect_same_frame(reference, f, name);
            EXPECT_EQ(f.extra["ray_sorting"]["gpu_cpu_syncs"], 2u) << name << ": the choices come with the tally";
        }
        EXPECT_EQ(counts(frames[4]), counts(frames[0])) << name << ": measured again, the same choices";
        EXPECT_EQ(counts(frames[1]), counts(reference)) << name << ": the check is stage 04's frame";
        EXPECT_EQ(counts(frames[5]), counts(reference)) << name;
        EXPECT_EQ(counts(frames[3]), counts(frames[2])) << name;
        EXPECT_LT(pairs_tested(frames[2]), pairs_tested(frames[1])) << name << ": the sorts kept test fewer pairs";
        EXPECT_LE(pairs_tested(frames[2]), pairs_tested(frames[0])) << name << ": no more than the measured frame";
    }
    const Scene s = builtin_scene("absorption");
    RaySortingRenderer renderer;
    renderer.sort_options.batch_cost = kAnySaving.batch;
    renderer.sort_options.ray_cost = kAnySaving.ray;
    for (int f = 0; f < 2; ++f) renderer.render(s, test_frame_settings(s, 48, 36, true));
    const FrameResult third = renderer.render(s, test_frame_settings(s, 48, 36, true));
    EXPECT_GT(std::uint64_t(third.extra["ray_sorting"]["batches"]["trace"]["fine_batches"]), 0u)
        << "absorption's reflection and refraction batches keep the fine order, sorted by the fine key alone";
}

// Sorting never loses, once checked: from the third frame on (measured, checked), every scene's frame tests at most
// the pairs stage 04's does. On spheres:12 at this size the measure keeps a shadow sort that tests more pairs in
// frame 1: the check drops it, and frame 3 is stage 04's.
TEST(RaySortingRenderer, AfterTheCheckSortingNeverTestsMorePairsThanTheQueueOrder) {
    gpu::test_context();
    for (const char* name :
         {"spheres:4", "spheres:12", "cornell", "whitted", "absorption", "mirror_box", "spheres:45"}) {
        FrameResult reference;
        const std::vector<FrameResult> frames = auto_frames(name, 3, SortOptions{}.probe_every, reference);
        for (const FrameResult& f : frames) expect_same_frame(reference, f, name);
        EXPECT_EQ(pairs_tested(frames[1]), pairs_tested(reference)) << name << ": the check is stage 04's frame";
        EXPECT_LE(pairs_tested(frames[2]), pairs_tested(reference)) << name;
        if (std::string(name) == "spheres:12") {
            EXPECT_GT(pairs_tested(frames[0]), pairs_tested(reference)) << name << ": the measure keeps a losing sort";
            EXPECT_EQ(sort_count(frames[1], "shadow", "sorts_dropped"), 1u) << name;
            EXPECT_EQ(pairs_tested(frames[2]), pairs_tested(reference)) << name << ": and the check drops it";
        }
    }
}

// The check weighs a sort's cost (--sort-batch-cost, --sort-ray-cost; order_choice.h, sort_pays): the sorts that
// any saving keeps (absorption and material_maps at 48x36: the cycle test above) are all dropped when a batch's sort
// costs more than any batch can save, by either term, and the third frame is then stage 04's; the default costs keep
// at most the sorts that any saving keeps.
TEST(RaySortingRenderer, TheCheckDropsASortThatSavesLessThanItCosts) {
    gpu::test_context();
    const auto kept_sorts = [](const FrameResult& r) {
        return sort_count(r, "trace", "sorted_batches") + sort_count(r, "shadow", "sorted_batches");
    };
    for (const char* name : {"absorption", "material_maps"}) {
        FrameResult reference;
        const std::vector<FrameResult> any = auto_frames(name, 3, SortOptions{}.probe_every, reference, kAnySaving);
        ASSERT_GT(kept_sorts(any[2]), 0u) << name << ": with any saving some sort must be kept";
        for (SortCosts costs : {SortCosts{100000000, 0}, SortCosts{0, 100000}}) {
            const std::vector<FrameResult> frames = auto_frames(name, 3, SortOptions{}.probe_every, reference, costs);
            EXPECT_EQ(kept_sorts(frames[0]), kept_sorts(any[0])) << name << ": the measure does not weigh the cost";
            EXPECT_EQ(kept_sorts(frames[2]), 0u) << name << " " << costs.batch << " " << costs.ray;
            EXPECT_EQ(sort_count(frames[1], "trace", "sorts_dropped") + sort_count(frames[1], "shadow", "sorts_dropped"),
                      kept_sorts(frames[0])) << name << ": the check drops every kept sort";
            EXPECT_EQ(pairs_tested(frames[2]), pairs_tested(reference)) << name << ": the third frame is stage 04's";
            for (const FrameResult& f : frames) expect_same_frame(reference, f, name);
        }
        const std::vector<FrameResult> defaults = auto_frames(name, 3, SortOptions{}.probe_every, reference);
        EXPECT_LE(kept_sorts(defaults[2]), kept_sorts(any[2])) << name;
        EXPECT_LE(pairs_tested(defaults[2]), pairs_tested(reference)) << name;
        EXPECT_EQ(defaults[2].extra["ray_sorting"]["batch_cost"], kSortBatchCost) << name;
        EXPECT_EQ(defaults[2].extra["ray_sorting"]["ray_cost"], kSortRayCost) << name;
    }
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

// What a whitted frame asks of the GPU (common/gpu/gl/gl_counters.h), pinned so that a change to it shows here; the
// second frame finds the still scene resident and uploads none of it. (The first frame of --sort auto measures every
// batch's orders: 308 dispatches more than the second, which takes the remembered orders.)
TEST(RaySortingRenderer, WhittedFrameCountsWhatItAsksOfTheGpu) {
    RaySortingRenderer stage;
    const auto counts = gpu::whitted_frame_counts(stage);
    EXPECT_EQ(counts[0], (gpu::FrameCounts{725, 24, 7, 550456, 18456}));
    EXPECT_EQ(counts[1], (gpu::FrameCounts{417, 24, 7, 0, 18184}));
}

}  // namespace
}  // namespace rt
