// The wavefront pipeline's other entry, used by stages 03-05: primary rays traced (camera_rays.comp + the trace
// pass) instead of rasterized. With stage 02's brute-force traversal it must give stage 01's image (the golden
// tolerance: 0.016 on 8-bit sRGB, at most 1% of the pixels) and exactly stage 01's ray and test counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/trace/brute_force_tracer.h"
#include "common/gpu/gpu_scene.h"
#include "common/gpu/gpu_test_context.h"
#include "common/gpu/wavefront.h"
#include "common/scene/builtin_scenes.h"
#include "common/trace/whitted.h"

namespace rt {
namespace {

TEST(Wavefront, TracedPrimaryRaysGiveStage01sImageAndCounts) {
    gpu::test_context();
    const int width = 80, height = 60;
    FlattenOptions options;
    options.aspect = float(width) / float(height);
    const Scene scene = flatten(make_builtin_scene("whitted"), options);
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.effects = analyze_effects(scene);

    gpu::GpuScene gpu_scene;
    gpu_scene.upload(scene);
    gpu::Wavefront wavefront({"common/brute_force.glsl", {}, {}});
    wavefront.begin_frame(gpu_scene, settings);
    wavefront.trace_camera_sample(glm::vec2(0.5f));
    RayCounters gpu_counters;
    const Image image = wavefront.finish_frame(gpu_counters);
    EXPECT_EQ(wavefront.passes(), (std::vector<std::string>{"camera_rays", "trace", "shade", "shadow", "resolve"}));

    // Stage 01 on the CPU.
    const BruteForceTracer<float> tracer(scene, settings.intersect);
    WhittedSettings ws;
    ws.effects = settings.effects;
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
    std::printf("traced primary rays: %zu of %d pixels beyond the golden threshold\n", failing, width * height);
    EXPECT_LE(double(failing), 0.01 * width * height);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(gpu_counters.rays[k], cpu_counters.rays[k]) << "ray kind " << k;
    EXPECT_EQ(gpu_counters.intersection_tests, cpu_counters.intersection_tests);
}

}  // namespace
}  // namespace rt
