// Stage 02 with alpha cut-outs: the G-buffer cannot know where a MASK or BLEND surface is transparent, so a pixel
// whose closest candidate is such a surface has its camera ray traced instead (Wavefront::shade_sample, docs/gpu.md
// "Cut-outs in stage 02"). A pixel that looks through a hole must get the hit behind it, exactly stage 01's.
#include <gtest/gtest.h>

#include "common/gpu/testing/gpu_test_context.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "01_naive/brute_force_tracer.h"
#include "hybrid_renderer.h"
#include "tests/stage_test_fixture.h"

namespace rt {
namespace {

TEST(CutoutDeferral, PixelsSeeingThroughAHoleGetStage01sHitBehindIt) {
    gpu::test_context();
    const int width = 80, height = 60;
    const Scene scene = builtin_scene_for("cutouts", width, height);
    const RenderSettings settings = test_frame_settings(scene, width, height);
    HybridRenderer stage;
    const FrameResult frame = stage.render(scene, settings);
    const auto& passes = frame.extra["passes"];
    EXPECT_NE(std::find(passes.begin(), passes.end(), "deferred_rays"), passes.end()) << passes.dump();

    const BruteForceTracer<float> cut(scene, settings.intersect, true, settings.effects.blend),
        solid(scene, settings.intersect, false);
    std::size_t primaries = 0, holes = 0, same = 0;
    for (const HitRecord& r : frame.hits) {
        if (r.path != 1 || ray_kind(r.kind_light) != RayKind::Primary) continue;
        ++primaries;
        const int x = int(r.pixel) % width, y = int(r.pixel) / width;
        const Ray<float> ray = camera_ray<float>(scene.camera, width, height, float(x) + 0.5f, float(y) + 0.5f);
        RayCounters c;
        Hit<float> through, surface;
        cut.closest(ray, through, c);
        solid.closest(ray, surface, c);
        if (surface.triangle < 0 || through.triangle == surface.triangle) continue;
        ++holes;   // the rasterizer sees the cut-out surface here; the ray goes through it
        if (r.triangle == through.triangle && r.t == float(through.t)) ++same;
    }
    EXPECT_EQ(primaries, std::size_t(width * height)) << "one primary record per pixel, deferred or not";
    // The fence's holes (137 pixels at this size); the BLEND pane's faint stripes are coverage, not holes.
    EXPECT_GT(holes, 100u);
    EXPECT_EQ(same, holes);
}

}  // namespace
}  // namespace rt
