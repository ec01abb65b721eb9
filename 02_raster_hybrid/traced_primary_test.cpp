// The wavefront pipeline's other entry, used by stage 03 with --primary trace: primary rays traced (camera_rays.comp +
// the trace pass) instead of rasterized. With stage 02's brute-force traversal it must give stage 01's image (the
// golden tolerance: 0.016 on 8-bit sRGB, at most 1% of the pixels) and exactly stage 01's ray and test counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "01_naive/brute_force_tracer.h"
#include "common/trace/hard_cases.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/pipeline/wavefront.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "common/trace/whitted.h"
#include "tests/hit_compare.h"
#include "tests/stage_test_fixture.h"

namespace rt {
namespace {

// The GPU frame of --fresnel `fresnel`, checked against stage 01's radiance pixel by pixel and its counts.
Image traced_primary_frame_like_stage01s(FresnelMode fresnel) {
    const int width = 80, height = 60;
    const Scene scene = builtin_scene_for("whitted", width, height);
    RenderSettings settings = test_frame_settings(scene, width, height);
    settings.record_hits = false;   // the image and the counts
    settings.fresnel = fresnel;

    gpu::GpuScene gpu_scene;
    gpu_scene.upload(scene);
    gpu::GlslTraversal per_ray("02_raster_hybrid/shaders/brute_force.glsl");
    gpu::Wavefront wavefront(per_ray);
    wavefront.begin_frame(gpu_scene, settings);
    wavefront.trace_camera_sample(glm::vec2(0.5f));
    RayCounters gpu_counters;
    const Image image = wavefront.finish_frame(gpu_counters);
    EXPECT_EQ(wavefront.passes(), (std::vector<std::string>{"camera_rays", "trace", "shade", "shadow", "resolve"}));

    // Stage 01 on the CPU.
    const BruteForceTracer<float> tracer(scene, settings.intersect);
    WhittedSettings ws;
    ws.effects = settings.effects;
    ws.fresnel = fresnel;
    const Whitted<float, BruteForceTracer<float>> whitted(scene, tracer, ws);
    RayCounters cpu_counters;
    std::size_t failing = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const Ray<float> ray = camera_ray<float>(scene.camera, width, height, float(x) + 0.5f, float(y) + 0.5f);
            cpu_counters.rays[int(RayKind::Primary)]++;
            const glm::vec3 expected = whitted.radiance(ray, 0, glm::vec3(1.0f), cpu_counters);
            const glm::vec3 got = image.at(x, y);
            float worst = 0.0f;
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(linear_to_srgb(got[c]) - linear_to_srgb(expected[c])));
            if (worst > 0.016f) ++failing;
        }
    std::printf("traced primary rays, %s Fresnel: %zu of %d pixels beyond the golden threshold\n",
                fresnel == FresnelMode::Exact ? "exact" : "Schlick", failing, width * height);
    EXPECT_LE(double(failing), 0.01 * width * height);
    for (int k = 0; k < kRayKinds; ++k) EXPECT_EQ(gpu_counters.rays[k], cpu_counters.rays[k]) << "ray kind " << k;
    EXPECT_EQ(gpu_counters.intersection_tests, cpu_counters.intersection_tests);
    return image;
}

// Both Fresnel formulas (--fresnel): each frame as stage 01's, and the glass sphere's differ between them (a shader
// that ignored the mode, the exact formula always, gave Schlick's frame the exact one's within the tolerance).
TEST(Wavefront, TracedPrimaryRaysGiveStage01sImageAndCounts) {
    gpu::test_context();
    const Image exact = traced_primary_frame_like_stage01s(FresnelMode::Exact);
    const Image schlick = traced_primary_frame_like_stage01s(FresnelMode::Schlick);
    std::size_t differing = 0;
    for (std::size_t i = 0; i < exact.pixels.size(); ++i) differing += exact.pixels[i] != schlick.pixels[i] ? 1 : 0;
    EXPECT_GT(differing, 0u) << "--fresnel schlick rendered the exact formula's frame";
}

// Traced primary rays, brute force in GLSL, against stage 01's brute force ray by ray: the same triangle for every
// closest hit (ties at equal t to the lowest id, as the CPU tracer's), the same answer for every shadow ray through
// the cut-outs' holes (a hole does not block), the same rays spawned.
TEST(Wavefront, TracedRaysHitWhatStage01HitsOnCoincidentTrianglesAndCutouts) {
    gpu::test_context();
    const int width = 64, height = 48;
    for (const bool coincident : {false, true}) {
        Scene scene = builtin_scene_for("cutouts", width, height);
        if (coincident) scene = hard_cases::with_coincident_copies(scene);
        const RenderSettings settings = test_frame_settings(scene, width, height);
        ASSERT_TRUE(settings.effects.cutouts && settings.effects.shadows);

        gpu::GpuScene gpu_scene;
        gpu_scene.upload(scene);
        gpu::GlslTraversal per_ray("02_raster_hybrid/shaders/brute_force.glsl");
        gpu::Wavefront wavefront(per_ray);
        wavefront.begin_frame(gpu_scene, settings);
        wavefront.trace_camera_sample(glm::vec2(0.5f));
        FrameResult gpu;
        wavefront.finish_frame(gpu);

        // As stage 01 does: BLEND as coverage for the closest hits, the cut-out for shadow rays (opacity.h).
        const BruteForceTracer<float> tracer(scene, settings.intersect, true, settings.effects.blend);
        const BruteForceTracer<float> shadow_tracer(scene, settings.intersect, true, false);
        WhittedSettings ws;
        ws.effects = settings.effects;
        const Whitted<float, BruteForceTracer<float>> whitted(scene, tracer, ws, &shadow_tracer);
        std::vector<HitRecord> cpu;
        RayCounters counters;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const HitLog log{&cpu, 0, std::uint32_t(y * width + x)};
                const Ray<float> ray = camera_ray<float>(scene.camera, width, height, float(x) + 0.5f, float(y) + 0.5f);
                whitted.radiance(ray, 0, glm::vec3(1.0f), counters, &log);
            }
        HitCompareOptions bounds;
        bounds.ray_ulps = 64;   // float on both sides, not the same arithmetic (tests/hits.cmake)
        bounds.t_ulps = 64;
        const HitComparison c = compare_hits(gpu.hits, cpu, bounds);
        EXPECT_TRUE(c.passed(bounds)) << (coincident ? "coincident copies: " : "cutouts: ") << c.report(bounds);
        EXPECT_GT(c.count_a[int(RayKind::Shadow)], 100u);
        EXPECT_GT(c.count_a[int(RayKind::Transparency)], 10u) << "the BLEND pane's transparency rays";
    }
}

}  // namespace
}  // namespace rt
