// Hostile surface-effect values rendered end to end, on the CPU (Whitted, brute force) and on the GPU (G-buffer +
// wavefront, as stage 02): an attenuation colour of 0 over the smallest float distance, a normal scale that
// overflows, zero tangents and degenerate uvs. No pixel may be NaN or infinite (docs/shading.md, "Limits").
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/app/pixel_samples.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "01_naive/brute_force_tracer.h"
#include "common/trace/whitted.h"
#include "02_raster_hybrid/gbuffer.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/pipeline/wavefront.h"

namespace rt {
namespace {

constexpr int kWidth = 40, kHeight = 30;

Scene hostile_scene(const std::string& builtin) {
    SceneAsset a = make_builtin_scene(builtin);
    for (Material& m : a.materials) {
        m.attenuation_color = {0.0f, 1e-30f, 1.0f};
        m.attenuation_distance = std::numeric_limits<float>::denorm_min();
        if (m.normal_texture >= 0) m.normal_scale = 3e38f;   // (2 texel - 1) * scale overflows for tilted texels
    }
    for (Mesh& mesh : a.meshes)
        for (Primitive& p : mesh.primitives) {
            if (!p.tangents.empty()) p.tangents.assign(p.tangents.size(), glm::vec4(0.0f));   // zero tangents
            else if (!p.uvs.empty()) p.uvs.assign(p.uvs.size(), glm::vec2(0.25f));            // zero uv area
        }
    FlattenOptions options;
    options.aspect = float(kWidth) / float(kHeight);
    return flatten(a, options);
}

std::size_t non_finite(const std::vector<glm::vec3>& pixels) {
    std::size_t n = 0;
    for (const glm::vec3& p : pixels) n += !(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    return n;
}

std::vector<glm::vec3> render_cpu(const Scene& scene) {
    const BruteForceTracer<float> tracer(scene, IntersectMethod::Watertight);
    WhittedSettings ws;
    ws.effects = analyze_effects(scene);
    const Whitted<float, BruteForceTracer<float>> whitted(scene, tracer, ws);
    RayCounters counters;
    std::vector<glm::vec3> pixels;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            pixels.push_back(whitted.radiance(camera_ray<float>(scene.camera, kWidth, kHeight, x + 0.5f, y + 0.5f),
                                              0, glm::vec3(1.0f), counters));
    return pixels;
}

std::vector<glm::vec3> render_gpu(const Scene& scene) {
    gpu::test_context();
    gpu::GpuScene gpu_scene;
    gpu_scene.upload(scene);
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.effects = analyze_effects(scene);
    gpu::GBuffer gbuffer;
    gpu::GlslTraversal per_ray("02_raster_hybrid/shaders/brute_force.glsl");
    gpu::Wavefront wavefront(per_ray);
    wavefront.begin_frame(gpu_scene, settings);
    const glm::vec2 offset = pixel_sample_offsets(1)[0];
    gbuffer.render(gpu_scene, scene.camera, scene.bounds, kWidth, kHeight, offset);
    gpu_scene.bind();
    gbuffer.shade_sample(wavefront, offset);
    FrameResult result;
    wavefront.finish_frame(result);
    return result.image.pixels;
}

TEST(SurfaceEffectsHostile, BlackAttenuationOverTheSmallestDistanceStaysFinite) {
    const Scene scene = hostile_scene("absorption");
    ASSERT_TRUE(analyze_effects(scene).absorption);
    const std::vector<glm::vec3> cpu = render_cpu(scene), gpu = render_gpu(scene);
    EXPECT_EQ(non_finite(cpu), 0u);
    EXPECT_EQ(non_finite(gpu), 0u);
    EXPECT_EQ(cpu.size(), gpu.size());
}

TEST(SurfaceEffectsHostile, OverflowingNormalScaleZeroTangentsAndDegenerateUvsStayFinite) {
    const Scene scene = hostile_scene("normal_map");
    ASSERT_TRUE(analyze_effects(scene).normal_maps);
    for (const glm::vec4& t : scene.tangents) ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.w));
    const std::vector<glm::vec3> cpu = render_cpu(scene), gpu = render_gpu(scene);
    EXPECT_EQ(non_finite(cpu), 0u);
    EXPECT_EQ(non_finite(gpu), 0u);
    EXPECT_EQ(cpu.size(), gpu.size());
}

}  // namespace
}  // namespace rt
