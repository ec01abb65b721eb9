// The environment's cost on a frame as stage 02 renders it (G-buffer primaries, brute-force traversal): without a
// map nothing is compiled or bound (no RT_ENVIRONMENT define, no environment texture, the same programs) and the
// pixels that see the sky get the background; with one they get the map. The GLSL lookup and the upload:
// common/gpu/glsl_twins/environment_glsl_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <random>

#include "02_raster_hybrid/gbuffer.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "common/trace/environment.h"
#include "common/trace/shading.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/pipeline/wavefront.h"

namespace rt::gpu {
namespace {

// A small map of odd size with distinct, irregular texels (so every misplaced read shows) and a rotation.
std::shared_ptr<const Environment> test_environment(float degrees) {
    auto e = std::make_shared<Environment>();
    e->width = 13;
    e->height = 7;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> value(0.0f, 50.0f);
    for (int i = 0; i < e->width * e->height; ++i) e->texels.push_back({value(rng), value(rng), value(rng), 1.0f});
    const float radians = degrees * (kPi / 180.0f);
    e->rotation = {std::cos(radians), std::sin(radians)};
    e->rotation_degrees = degrees;
    return e;
}

// One frame as stage 02 renders it, returning the wavefront's defines and programs.
struct Frame {
    ShaderDefines defines;
    std::vector<std::string> programs;
    Image image;
};
Frame render(const Scene& scene, GpuScene& gpu_scene) {
    RenderSettings settings;
    settings.width = 40;
    settings.height = 30;
    settings.effects = analyze_effects(scene);
    gpu_scene.upload(scene);
    GBuffer gbuffer;
    GlslTraversal per_ray("02_raster_hybrid/shaders/brute_force.glsl");
    Wavefront wavefront(per_ray);
    wavefront.begin_frame(gpu_scene, settings);
    gbuffer.render(gpu_scene, scene.camera, scene.bounds, settings.width, settings.height, glm::vec2(0.5f));
    gpu_scene.bind();
    gbuffer.shade_sample(wavefront, glm::vec2(0.5f));
    RayCounters counters;
    Frame f{wavefront.defines(), wavefront.programs(), wavefront.finish_frame(counters)};
    return f;
}

TEST(EnvironmentCost, WithoutAMapNothingIsCompiledOrBoundAndMissesAreTheBackground) {
    test_context();
    Scene scene = flatten(make_builtin_scene("whitted"), {});
    GpuScene gpu_scene;
    const Frame plain = render(scene, gpu_scene);
    EXPECT_EQ(plain.defines.count("RT_ENVIRONMENT"), 0u);
    EXPECT_FALSE(gpu_scene.has_environment());
    EXPECT_EQ(gpu_scene.environment().uploads(), 0);
    // With a map: the define, the texture, the same programs (the lookup is inside them), and another image.
    scene.environment = test_environment(0.0f);
    GpuScene with_map;
    const Frame mapped = render(scene, with_map);
    EXPECT_EQ(mapped.defines.count("RT_ENVIRONMENT"), 1u);
    EXPECT_TRUE(with_map.has_environment());
    EXPECT_EQ(mapped.programs, plain.programs);
    EXPECT_NE(std::memcmp(mapped.image.pixels.data(), plain.image.pixels.data(),
                          plain.image.pixels.size() * sizeof(glm::vec3)), 0);
    // The top-left pixel sees the sky: without a map the background (through the fixed-point sum), with one the map.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(plain.image.at(0, 0)[c], scene.background[c], 1e-6f);
    EXPECT_GT(glm::length(mapped.image.at(0, 0) - scene.background), 0.1f);
}

}  // namespace
}  // namespace rt::gpu
