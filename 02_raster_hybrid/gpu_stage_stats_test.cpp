// The stats every GPU stage reports, through the shared base (common/gpu/pipeline/gpu_stage.h), on stage 02 and on a
// stage that traces its primary rays as 03 can: rasterized vs traced rays, GPU-timed phases, shader compilation
// reported apart (and only when something was compiled).
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace rt
