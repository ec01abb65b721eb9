// The GLSL twins of the surface effects (absorption.glsl, texture_transform.glsl, normal_map.glsl) against their
// C++ originals, and what a scene without them pays: nothing (no define, no tangent bytes on the GPU).
//
// Accuracy contract: rt_transform_uv and normal_mapped are written operation for operation with `precise`, so they
// are bit-exact on llvmpipe (0 ulps, as glsl_twins_test.cpp's kExactUlps). transmittance uses GLSL's exp, which is
// not correctly rounded: its relative error is bounded by kExpRelative.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "common/trace/absorption.h"
#include "common/trace/normal_map.h"
#include "common/trace/texture_transform.h"
#include "common/gpu/testing/glsl_test_harness.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/gl/shader.h"
#include "common/gpu/testing/pipeline_fixture.h"

namespace rt::gpu {
namespace {

constexpr float kExpRelative = 1e-5f;

float f(const std::vector<std::uint32_t>& w, std::size_t i) { return word_f(w, i); }

TEST(SurfaceGlslTwins, TransmittanceMatchesWithinExpAccuracy) {
    test_context();
    GlslTestHarness h("transmittance_test", R"(
#include "common/shaders/trace/absorption.glsl"
void test_main() { out_vec3(0, transmittance(in_vec3(0), in_f(3))); }
)");
    std::mt19937 g(7);
    std::uniform_real_distribution<float> sigma(0.0f, 20.0f), t(0.0f, 2.0f);
    Words in;
    std::vector<glm::vec3> expected;
    for (int i = 0; i < 512; ++i) {
        const glm::vec3 s(sigma(g), sigma(g) * 0.1f, i % 7 == 0 ? std::numeric_limits<float>::max() : 0.0f);
        const float d = i % 11 == 0 ? 0.0f : t(g);
        in << s << d;
        expected.push_back(transmittance(s, d));
    }
    const auto out = h.run(in.words, expected.size(), 4, 3);
    float worst = 0.0f;
    for (std::size_t i = 0; i < expected.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const float cpu = expected[i][c], gpu = f(out, 3 * i + std::size_t(c));
            ASSERT_TRUE(std::isfinite(gpu)) << i;
            if (cpu == 0.0f || cpu == 1.0f) {   // no medium, or everything absorbed
                ASSERT_EQ(gpu, cpu) << i;
            }
            worst = std::max(worst, std::abs(gpu - cpu) / cpu);
        }
    EXPECT_LE(worst, kExpRelative);
    std::printf("transmittance: worst relative error %g\n", double(worst));
}

TEST(SurfaceGlslTwins, TextureTransformIsBitExact) {
    test_context();
    GlslTestHarness h("transform_uv_test", R"(
#include "common/shaders/trace/texture_transform.glsl"
void test_main() { out_vec2(0, rt_transform_uv(in_vec4(0), in_vec2(4), in_vec2(6))); }
)");
    std::mt19937 g(9);
    std::uniform_real_distribution<float> any(-10.0f, 10.0f);
    Words in;
    std::vector<glm::vec2> expected;
    for (int i = 0; i < 256; ++i) {
        TextureTransform t;
        if (i % 4 != 0) t = {{any(g), any(g)}, any(g), {any(g), any(g)}};   // every 4th: the identity
        const glm::vec2 uv(any(g), any(g));
        in << uv_matrix(t) << t.offset << uv;
        expected.push_back(transform_uv(t, uv));
    }
    const auto out = h.run(in.words, expected.size(), 8, 2);
    for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(f(out, 2 * i), expected[i].x) << i;
        EXPECT_EQ(f(out, 2 * i + 1), expected[i].y) << i;
    }
}

TEST(SurfaceGlslTwins, NormalMappedIsBitExactOnTheNormalMapScene) {
    test_context();
    const Scene scene = flatten(make_builtin_scene("normal_map"), {});
    ASSERT_EQ(scene.tangents.size(), scene.positions.size());
    GpuScene gpu;
    gpu.upload(scene);
    GlslTestHarness h("normal_mapped_test", R"(
#include "common/shaders/trace/normal_map.glsl"
void test_main() {
    const uint tri = in_u(0);
    const Material m = rt_materials[rt_material_ids[tri]];
    out_vec3(0, normal_mapped(tri, in_f(1), in_f(2), in_f(3), in_vec2(4), in_vec3(6), in_vec3(9), m));
}
)");
    std::mt19937 g(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    Words in;
    std::vector<glm::vec3> expected;
    std::size_t mapped = 0;
    for (std::uint32_t tri = 0; tri < scene.triangle_count(); tri += 3) {
        const float u = unit(g), v = unit(g) * (1.0f - u), w = 1.0f - u - v;
        const glm::vec2 uv(unit(g) * 4.0f - 1.0f, unit(g) * 4.0f - 1.0f);
        const glm::vec3 ng = glm::normalize(glm::cross(scene.positions[3 * tri + 1] - scene.positions[3 * tri],
                                                       scene.positions[3 * tri + 2] - scene.positions[3 * tri]));
        const glm::vec3 facing = tri % 2 ? ng : -ng;   // front and back hits
        const glm::vec3 shading = facing;
        in << tri << w << u << v << uv << facing << shading;
        const Material& m = scene.materials[scene.material_ids[tri]];
        expected.push_back(normal_mapped(scene, tri, w, u, v, uv, facing, shading, m));
        if (expected.back() != shading) ++mapped;
    }
    EXPECT_GT(mapped, expected.size() / 2);   // the map did bend most of them
    const auto out = h.run(in.words, expected.size(), 12, 3, [&] { gpu.bind(); });
    for (std::size_t i = 0; i < expected.size(); ++i)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(f(out, 3 * i + std::size_t(c)), expected[i][c]) << i << " " << c;
}

// What the wavefront compiles and uploads for a scene: the effect defines, and the normals buffer's bytes.
struct Variant {
    ShaderDefines defines;
    std::size_t normal_bytes;
};
Variant variant(const std::string& builtin) {
    test_context();
    const Scene scene = flatten(make_builtin_scene(builtin), {});
    GpuScene gpu;
    gpu.upload(scene);
    return {compiled_defines(gpu, fixture_settings(scene, 16, 12)), gpu.normals().size()};
}

TEST(SurfaceEffectsCost, ScenesWithoutThemCompileNoCodeAndUploadNoTangents) {
    for (const char* name : {"whitted", "cornell", "office"}) {
        SCOPED_TRACE(name);
        const Variant v = variant(name);
        EXPECT_EQ(v.defines.count("ENABLE_ABSORPTION"), 0u);
        EXPECT_EQ(v.defines.count("ENABLE_NORMAL_MAPS"), 0u);
        const Scene scene = flatten(make_builtin_scene(name), {});
        EXPECT_EQ(v.normal_bytes, scene.positions.size() * sizeof(glm::vec4));   // normals only
    }
    const Variant absorption = variant("absorption");
    EXPECT_EQ(absorption.defines.count("ENABLE_ABSORPTION"), 1u);
    EXPECT_EQ(absorption.defines.count("ENABLE_NORMAL_MAPS"), 0u);
    const Variant normal_map = variant("normal_map");
    EXPECT_EQ(normal_map.defines.count("ENABLE_NORMAL_MAPS"), 1u);
    EXPECT_EQ(normal_map.defines.count("ENABLE_ABSORPTION"), 0u);
    const Scene scene = flatten(make_builtin_scene("normal_map"), {});
    EXPECT_EQ(normal_map.normal_bytes, 2 * scene.positions.size() * sizeof(glm::vec4));   // normals, then tangents
}

}  // namespace
}  // namespace rt::gpu
