// The stats every GPU stage reports, through the shared base (common/gpu/pipeline/gpu_stage.h), on stage 02 and on a
// stage that traces its primary rays as 03 can: rasterized vs traced rays, GPU-timed phases, shader compilation
// reported apart (and only when something was compiled).
#include <gtest/gtest.h>

#include "common/gpu/testing/frame_counts.h"
#include "common/gpu/testing/same_frame_expectations.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "hybrid_renderer.h"

namespace rt {
namespace {

struct Frame {
    Scene scene;
    RenderSettings settings;
};

Frame whitted_frame(int width, int height) {
    FlattenOptions options;
    options.aspect = float(width) / float(height);
    Frame f{flatten(make_builtin_scene("whitted"), options), {}};
    f.settings.width = width;
    f.settings.height = height;
    f.settings.effects = analyze_effects(f.scene);
    return f;
}

// The smallest GPU stage: brute force, primary rays traced by the shared pipeline.
class TracedPrimaryStage : public gpu::GpuStage {
public:
    TracedPrimaryStage()
        : GpuStage(std::make_unique<gpu::TracedPrimary>(),
                   std::make_unique<gpu::GlslTraversal>("02_raster_hybrid/shaders/brute_force.glsl")) {}
};

TEST(GpuStageStats, HybridRasterizesPrimaryRaysAndTimesEachPhase) {
    gpu::test_context();
    const Frame f = whitted_frame(40, 30);
    HybridRenderer stage;
    const FrameResult first = stage.render(f.scene, f.settings);
    const FrameStats& s = first.stats;
    EXPECT_EQ(s.counters.rays[int(RayKind::Primary)], 40u * 30u);
    EXPECT_EQ(s.rasterized_rays, 40u * 30u);
    EXPECT_EQ(s.traced_rays(), s.counters.total_rays() - 40u * 30u);
    EXPECT_GT(s.traced_rays(), 0u);
    EXPECT_GT(s.raster_ms, 0.0);
    EXPECT_GT(s.trace_ms, 0.0);
    EXPECT_GT(s.shade_ms, 0.0);
    EXPECT_EQ(s.build_ms, 0.0) << "brute force builds nothing";
    EXPECT_GT(s.compile_ms, 0.0) << "the first frame compiles the passes";
    for (const char* key : {"backend", "passes", "pass_dispatches", "shader_defines", "programs", "pass_time_ms"})
        EXPECT_TRUE(first.extra.contains(key)) << key;
    EXPECT_TRUE(first.extra["pass_time_ms"].contains("raster"));

    // The same variant again: nothing to compile, the same counts.
    const FrameResult second = stage.render(f.scene, f.settings);
    EXPECT_EQ(second.stats.compile_ms, 0.0);
    EXPECT_EQ(second.stats.rasterized_rays, s.rasterized_rays);
    EXPECT_EQ(second.stats.counters.total_rays(), s.counters.total_rays());
}

TEST(GpuStageStats, TracedPrimaryRaysAreTracedNotRasterized) {
    gpu::test_context();
    const Frame f = whitted_frame(40, 30);
    TracedPrimaryStage stage;
    const FrameResult r = stage.render(f.scene, f.settings);
    EXPECT_EQ(r.stats.counters.rays[int(RayKind::Primary)], 40u * 30u);
    EXPECT_EQ(r.stats.rasterized_rays, 0u);
    EXPECT_EQ(r.stats.traced_rays(), r.stats.counters.total_rays());
    EXPECT_EQ(r.stats.raster_ms, 0.0);
    EXPECT_GT(r.stats.trace_ms, 0.0);
    EXPECT_EQ(r.extra["passes"], (std::vector<std::string>{"camera_rays", "trace", "shade", "shadow", "resolve"}));
}

TEST(GpuStageStats, PhasesAddUpToTheStatsTimes) {
    FrameStats s;
    gpu::GpuStage::add_phase_times({{"upload", 1}, {"build", 2}, {"raster", 4}, {"trace", 8}, {"shadow", 16},
                                    {"shade", 32}, {"resolve", 64}, {"camera_rays", 128}, {"sort", 256}},
                                   s);
    EXPECT_EQ(s.upload_ms, 1.0);
    EXPECT_EQ(s.build_ms, 2.0);
    EXPECT_EQ(s.raster_ms, 4.0);
    EXPECT_EQ(s.trace_ms, 8.0 + 16.0);
    EXPECT_EQ(s.shade_ms, 32.0 + 64.0 + 128.0);
    EXPECT_EQ(s.compile_ms, 0.0) << "compilation is wall clock, never a GPU phase";
}

// A still scene (Scene::still_id) stays on the GPU: its next frames upload none of it and equal a fresh upload's,
// a moved camera included (the viewer hands over the same scene with another camera); a scene not marked still, or
// marked with another id, is uploaded again.
TEST(GpuStageStats, AStillSceneStaysOnTheGpuAndGivesAFreshUploadsFrame) {
    gpu::test_context();
    Frame f = whitted_frame(40, 30);
    f.settings.record_hits = true;
    f.scene.still_id = 7;
    HybridRenderer stage;
    const auto scene_bytes = [](const FrameResult& r) { return r.extra.at("upload_bytes").at("scene").get<std::size_t>(); };
    const FrameResult first = stage.render(f.scene, f.settings);
    EXPECT_GT(scene_bytes(first), 0u);
    Scene moved = f.scene;
    moved.camera.position += 0.25f * moved.camera.right;
    const FrameResult resident = stage.render(moved, f.settings);
    EXPECT_EQ(scene_bytes(resident), 0u);
    Scene fresh = moved;
    fresh.still_id = 0;
    const FrameResult uploaded = HybridRenderer().render(fresh, f.settings);
    expect_same_frame(resident, uploaded, "resident scene, moved camera");
    EXPECT_NE(first.image.pixels, resident.image.pixels);   // the camera did move

    EXPECT_GT(scene_bytes(stage.render(fresh, f.settings)), 0u);   // not still: uploaded every frame
    EXPECT_GT(scene_bytes(stage.render(fresh, f.settings)), 0u);
    Scene other = f.scene;
    other.still_id = 8;
    EXPECT_GT(scene_bytes(stage.render(other, f.settings)), 0u);   // another still scene
    EXPECT_EQ(scene_bytes(stage.render(other, f.settings)), 0u);
}

// What a whitted frame asks of the GPU (common/gpu/gl/gl_counters.h), pinned so that a change to it shows here; the
// second frame finds the still scene resident and uploads none of it.
TEST(GpuStageStats, WhittedFrameCountsWhatItAsksOfTheGpu) {
    HybridRenderer stage;
    const auto counts = gpu::whitted_frame_counts(stage);
    EXPECT_EQ(counts[0], (gpu::FrameCounts{66, 12, 4, 550456, 128}));
    EXPECT_EQ(counts[1], (gpu::FrameCounts{66, 12, 4, 0, 128}));
}

}  // namespace
}  // namespace rt
