// The environment on the GPU (environment.glsl, environment_texture.h):
//  - the GLSL lookup is the C++ one's twin, bit for bit (like glsl_twins_test.cpp: RT_GLSL_TWIN_ULPS loosens it on a
//    GPU without IEEE division and sqrt), at the seam (u = 0 / 1), the poles, texel borders and under rotation;
//  - the map is uploaded once, not once per frame, and a map larger than GL_MAX_TEXTURE_SIZE is refused.
// That it costs nothing when unused (no RT_ENVIRONMENT define, no environment texture, the same programs) is checked
// on a frame as stage 02 renders it: 02_raster_hybrid/environment_frame_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>

#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "common/trace/environment.h"
#include "common/trace/shading.h"
#include "common/gpu/testing/glsl_test_harness.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/pipeline/wavefront.h"

namespace rt::gpu {
namespace {

std::int64_t ulp_bound() {
    const char* env = std::getenv("RT_GLSL_TWIN_ULPS");
    return env ? std::atoll(env) : 0;
}

std::int64_t ulp_diff(float a, float b) {
    if (a == b) return 0;
    if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0 : INT64_MAX;
    std::int32_t ia, ib;
    std::memcpy(&ia, &a, 4);
    std::memcpy(&ib, &b, 4);
    const auto ordered = [](std::int32_t i) { return i < 0 ? std::int64_t(INT32_MIN) - i : std::int64_t(i); };
    return std::llabs(ordered(ia) - ordered(ib));
}

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

Scene scene_with(std::shared_ptr<const Environment> environment) {
    Scene scene = flatten(make_builtin_scene("diffuse"), {});
    scene.environment = std::move(environment);
    return scene;
}

// Directions to test: random ones, the axes, the seam (+Z, a hair either side), the poles and near them.
std::vector<glm::vec3> directions() {
    std::vector<glm::vec3> d = {{0, 0, -1}, {0, 0, 1},      {1, 0, 0},       {-1, 0, 0},     {0, 1, 0},
                                {0, -1, 0}, {1e-7f, 0, 1},  {-1e-7f, 0, 1},  {1e-7f, 1, 0},  {0, -1, 1e-7f},
                                {0, 0, 0},  {1, 1, 1},      {-3, 0.5f, 2},   {1e-30f, 0, 1}, {-1e-30f, 0.2f, 1}};
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> any(-1.0f, 1.0f);
    for (int i = 0; i < 4000; ++i) d.push_back({any(rng), any(rng), any(rng)});
    return d;
}

TEST(EnvironmentGlslTwins, LookupMatchesTheCppBitForBitAtSeamsPolesAndUnderRotation) {
    test_context();
    const std::int64_t bound = ulp_bound();
    for (const float degrees : {0.0f, 30.0f, -90.0f, 180.0f, 1234.5f}) {
        const Scene scene = scene_with(test_environment(degrees));
        GpuScene gpu;
        gpu.upload(scene);
        ASSERT_TRUE(gpu.has_environment());
        GlslTestHarness h("environment_test", R"(
#include "common/shaders/trace/scene.glsl"
#include "common/shaders/trace/environment.glsl"
void test_main() {
    const vec3 d = in_vec3(0);
    const vec2 uv = rt_environment_uv(d, rt_environment_rotation);
    out_vec2(0, uv);
    out_vec3(2, rt_sample_environment(uv));
    out_vec3(5, rt_miss_radiance(d));
    out_f(8, rt_environment_atan2(d.x, d.y));
}
)", {{"RT_ENVIRONMENT", "1"}});
        Words in;
        std::vector<float> expected;
        const std::vector<glm::vec3> dirs = directions();
        for (const glm::vec3& d : dirs) {
            in << d;
            const glm::vec2 uv = environment_uv(d, scene.environment->rotation);
            const glm::vec3 c = sample_environment(*scene.environment, uv);
            const glm::vec3 m = miss_radiance(scene, d);
            expected.insert(expected.end(), {uv.x, uv.y, c.x, c.y, c.z, m.x, m.y, m.z, environment_atan2(d.x, d.y)});
        }
        const std::vector<std::uint32_t> out = h.run(in.words, dirs.size(), 3, 9, [&] { gpu.bind(); });
        ASSERT_EQ(out.size(), expected.size());
        std::size_t failures = 0;
        for (std::size_t i = 0; i < expected.size(); ++i)
            if (ulp_diff(expected[i], word_f(out, i)) > bound && failures++ < 5)
                ADD_FAILURE() << "rotation " << degrees << ", direction " << i / 9 << " word " << i % 9 << ": cpu "
                              << expected[i] << " gpu " << word_f(out, i);
        EXPECT_EQ(failures, 0u) << "rotation " << degrees;
    }
}

// Texel borders and the seam in uv directly: every texel edge and centre in u and v, and u = 0 / 1 exactly.
TEST(EnvironmentGlslTwins, BilinearMatchesAtEveryTexelEdgeAndCentre) {
    test_context();
    const Scene scene = scene_with(test_environment(0.0f));
    GpuScene gpu;
    gpu.upload(scene);
    GlslTestHarness h("environment_sample_test", R"(
#include "common/shaders/trace/scene.glsl"
#include "common/shaders/trace/environment.glsl"
void test_main() { out_vec3(0, rt_sample_environment(in_vec2(0))); }
)", {{"RT_ENVIRONMENT", "1"}});
    Words in;
    std::vector<float> expected;
    std::size_t count = 0;
    const Environment& e = *scene.environment;
    for (int i = 0; i <= 2 * e.width; ++i)
        for (int j = 0; j <= 2 * e.height; ++j) {
            const glm::vec2 uv(float(i) / float(2 * e.width), float(j) / float(2 * e.height));
            in << uv;
            const glm::vec3 c = sample_environment(e, uv);
            expected.insert(expected.end(), {c.x, c.y, c.z});
            ++count;
        }
    const std::vector<std::uint32_t> out = h.run(in.words, count, 2, 3, [&] { gpu.bind(); });
    for (std::size_t i = 0; i < expected.size(); ++i)
        ASSERT_LE(ulp_diff(expected[i], word_f(out, i)), ulp_bound()) << "sample " << i / 3 << " channel " << i % 3;
    // The seam is continuous: u = 0 and u = 1 read the same two columns.
    EXPECT_EQ(sample_environment(e, {0.0f, 0.3f}), sample_environment(e, {1.0f, 0.3f}));
}

TEST(EnvironmentCost, TheMapIsUploadedOnceForManyFrames) {
    test_context();
    const Scene scene = scene_with(test_environment(10.0f));
    GpuScene gpu;
    for (int frame = 0; frame < 3; ++frame) gpu.upload(scene);
    EXPECT_EQ(gpu.environment().uploads(), 1);
    Scene other = scene;
    other.environment = test_environment(20.0f);   // another map: uploaded again
    gpu.upload(other);
    EXPECT_EQ(gpu.environment().uploads(), 2);
    other.environment = nullptr;                     // none: the texture goes
    gpu.upload(other);
    EXPECT_FALSE(gpu.has_environment());
}

TEST(EnvironmentCost, AMapBeyondTheTextureSizeLimitIsRefusedWithOneLine) {
    test_context();
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    auto e = std::make_shared<Environment>();
    e->file = "wide.exr";
    e->width = max_size + 1;
    e->height = 1;
    e->texels.assign(std::size_t(e->width), glm::vec4(1.0f));
    Scene scene = scene_with(e);
    GpuScene gpu;
    try {
        gpu.upload(scene);
        ADD_FAILURE() << "a map wider than GL_MAX_TEXTURE_SIZE was uploaded";
    } catch (const SceneError& error) {
        EXPECT_NE(std::string(error.what()).find("environment wide.exr: " + std::to_string(max_size + 1) +
                                                 "x1 is larger than this GPU's textures"),
                  std::string::npos)
            << error.what();
    }
    EXPECT_FALSE(gpu.has_environment());
}

}  // namespace
}  // namespace rt::gpu
