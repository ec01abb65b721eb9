// Alpha cut-outs on the GPU: opacity.glsl against its C++ twin (common/trace/opacity.h), bit for bit; the wavefront
// pipeline compiling and spending nothing for them on a scene without cut-outs; and the exact cut-out path (every
// hit passes the test) giving the image and hits of the plain one.
#include <gtest/gtest.h>

#include <random>

#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "common/trace/opacity.h"
#include "common/trace/whitted.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/testing/glsl_test_harness.h"
#include "common/gpu/testing/pipeline_fixture.h"

namespace rt::gpu {
namespace {

std::uint32_t bits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

// One triangle (0,0,0) (1,0,0) (0,1,0), uv = xy, MASK at cutoff 0.4 with factor alpha 0.8 and a 2 x 1 bilinear
// texture of alpha 0 and 1: opacity 0.8 * u between the texel centres, exactly the cutoff at u = 0.5.
Scene cutoff_triangle() {
    Scene s;
    s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    s.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    s.uvs = {{0, 0}, {1, 0}, {0, 1}};
    s.material_ids = {0};
    Material m;
    m.base_color.a = 0.8f;
    m.base_color_texture = 0;
    m.alpha_mode = AlphaMode::Mask;
    m.alpha_cutoff = 0.4f;
    s.materials = {m};
    Texture t;
    t.width = 2;
    t.height = 1;
    t.rgba8 = {255, 255, 255, 0, 255, 255, 255, 255};
    s.textures = {t};
    Light l;
    s.lights = {l};
    return s;
}

TEST(OpacityGlsl, TwinOfTheCppTestBitForBit) {
    test_context();
    GlslTestHarness h("opacity_test", R"(
#include "common/shaders/trace/opacity.glsl"
void test_main() {
    out_f(0, surface_opacity(in_u(0), in_f(1), in_f(2)));
    out_b(1, surface_opaque(in_u(0), in_f(1), in_f(2)));
    out_b(2, cutout_opaque(in_u(0), in_f(1), in_f(2)));
}
)", {{"ENABLE_CUTOUTS", "1"}});
    // The built-in cut-out scene (a bilinear alpha texture with round holes, MASK; a nearest one, BLEND) and the
    // triangle whose opacity reaches the cutoff exactly.
    std::size_t at_cutoff = 0;
    for (const Scene& scene : {flatten(make_builtin_scene("cutouts"), {}), cutoff_triangle()}) {
        GpuScene gpu;
        gpu.upload(scene);
        std::mt19937 rng(13);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        Words in;
        std::vector<std::uint32_t> expected;
        std::size_t count = 0, cut = 0;
        for (std::uint32_t tri = 0; tri < scene.triangle_count(); ++tri)
            for (int k = 0; k < 3000; ++k) {
                float u = unit(rng), v = unit(rng);
                if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
                if (k % 10 == 0) u = float(k % 64) / 64.0f, v = 0.0f;   // texel centres and edges
                if (k % 10 == 1) u = 0.5f, v = float(k % 32) / 64.0f;
                in << tri << u << v;
                const bool opaque = surface_opaque(scene, tri, u, v);
                const float opacity = surface_opacity(scene, tri, u, v);
                expected.insert(expected.end(), {bits(opacity), opaque ? 1u : 0u, opaque ? 1u : 0u});
                cut += opaque ? 0 : 1;
                at_cutoff += opacity == alpha_test_cutoff(scene.materials[scene.material_ids[tri]]) ? 1 : 0;
                ++count;
            }
        EXPECT_GT(cut, count / 10) << "the sample covers holes";
        const std::vector<std::uint32_t> got = h.run(in.words, count, 3, 3, [&] { gpu.bind(); });
        ASSERT_EQ(got.size(), expected.size());
        std::size_t differ = 0;
        for (std::size_t i = 0; i < got.size(); ++i) differ += got[i] != expected[i] ? 1 : 0;
        EXPECT_EQ(differ, 0u);
    }
    EXPECT_GT(at_cutoff, 100u) << "opacities exactly at the cutoff are in the sample";
}

// The frame of `scene` through the shared pipeline (the fixture's traversal), primary rays traced.
struct Frame {
    Image image;
    RayCounters counters;
    std::vector<HitRecord> hits;
    ShaderDefines defines;
    std::vector<std::string> programs;
};
Frame render(const Scene& scene, const Effects& effects) {
    RenderSettings settings = fixture_settings(scene, 64, 48);
    settings.effects = effects;
    settings.record_hits = true;
    GpuScene gpu_scene;
    gpu_scene.upload(scene);
    TracedFrame f = traced_frame(gpu_scene, settings);
    return {f.result.image, f.result.stats.counters, f.result.hits, f.defines, f.programs};
}

TEST(OpacityGlsl, SceneWithoutCutoutsCompilesNothingForThemAndEveryHitPassingGivesTheSameFrame) {
    test_context();
    FlattenOptions options;
    options.aspect = 64.0f / 48.0f;
    const Scene plain = flatten(make_builtin_scene("whitted"), options);
    const Effects effects = analyze_effects(plain);
    ASSERT_FALSE(effects.cutouts);
    const Frame a = render(plain, effects);
    EXPECT_EQ(a.defines.count("ENABLE_CUTOUTS"), 0u);
    for (const std::string& p : a.programs) EXPECT_EQ(p.find("deferred_rays"), std::string::npos) << p;

    // The same scene with every material MASK at cutoff 0: the test runs on every hit and passes, so the frame must
    // be the plain one bit for bit (image, every ray's hit, the counts).
    Scene masked = plain;
    for (Material& m : masked.materials) {
        m.alpha_mode = AlphaMode::Mask;
        m.alpha_cutoff = 0.0f;
    }
    const Effects with = analyze_effects(masked);
    ASSERT_TRUE(with.cutouts);
    const Frame b = render(masked, with);
    EXPECT_EQ(b.defines.count("ENABLE_CUTOUTS"), 1u);
    ShaderDefines only_cutouts = b.defines;
    only_cutouts.erase("ENABLE_CUTOUTS");
    EXPECT_EQ(only_cutouts, a.defines) << "cut-outs add one define and nothing else";
    ASSERT_EQ(a.image.pixels.size(), b.image.pixels.size());
    EXPECT_TRUE(a.image.pixels == b.image.pixels);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(a.counters.rays[k], b.counters.rays[k]);
    EXPECT_EQ(a.counters.intersection_tests, b.counters.intersection_tests);
    ASSERT_EQ(a.hits.size(), b.hits.size());
    for (std::size_t i = 0; i < a.hits.size(); ++i) {
        EXPECT_EQ(a.hits[i].triangle, b.hits[i].triangle) << i;
        EXPECT_EQ(a.hits[i].t, b.hits[i].t) << i;
    }
}

// Vertex colours (COLOR_0): random RGBA per vertex of a scene.
Scene with_vertex_colors(Scene scene, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    scene.colors.resize(scene.positions.size());
    for (glm::vec4& c : scene.colors) c = {unit(rng), unit(rng), unit(rng), unit(rng)};
    return scene;
}

// rt_vertex_color and the opacity with a vertex colour's alpha against surface_point's colour (whitted.h) and
// surface_opacity (opacity.h), bit for bit, on the cut-out scene with random colours.
TEST(OpacityGlsl, VertexColourAndItsAlphaInTheCutoutTestAreTheCppTwinsBitForBit) {
    test_context();
    GlslTestHarness h("vertex_color_test", R"(
#include "common/shaders/trace/opacity.glsl"
void test_main() {
    out_vec4(0, rt_vertex_color(in_u(0), in_f(1), in_f(2)));
    out_f(4, surface_opacity(in_u(0), in_f(1), in_f(2)));
}
)", {{"ENABLE_CUTOUTS", "1"}, {"RT_VERTEX_COLORS", "1"}});
    const Scene scene = with_vertex_colors(flatten(make_builtin_scene("cutouts"), {}), 5);
    GpuScene gpu;
    gpu.upload(scene);
    ASSERT_TRUE(gpu.has_vertex_colors());
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    Words in;
    std::vector<std::uint32_t> expected;
    std::size_t count = 0;
    for (std::uint32_t tri = 0; tri < scene.triangle_count(); ++tri)
        for (int k = 0; k < 500; ++k) {
            float u = unit(rng), v = unit(rng);
            if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
            in << tri << u << v;
            Ray<float> ray;
            ray.direction = glm::vec3(0, 0, -1);
            Hit<float> hit;
            hit.triangle = std::int32_t(tri);
            hit.u = u;
            hit.v = v;
            const glm::vec4 c = surface_point(scene, ray, hit).color;
            expected.insert(expected.end(), {bits(c.x), bits(c.y), bits(c.z), bits(c.w),
                                             bits(surface_opacity(scene, tri, u, v))});
            ++count;
        }
    const std::vector<std::uint32_t> got = h.run(in.words, count, 3, 5, [&] { gpu.bind(); });
    ASSERT_EQ(got.size(), expected.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < got.size(); ++i) differ += got[i] != expected[i] ? 1 : 0;
    EXPECT_EQ(differ, 0u);
}

// A scene without vertex colours compiles no code and uploads no bytes for them; white ones change no pixel and no
// hit (vertex_color gives a one-coloured triangle its colour exactly); random ones change the image.
TEST(OpacityGlsl, VertexColoursCostNothingWithoutThemAndWhiteOnesChangeNoPixel) {
    test_context();
    FlattenOptions options;
    options.aspect = 64.0f / 48.0f;
    const Scene plain = flatten(make_builtin_scene("whitted"), options);
    const Effects effects = analyze_effects(plain);
    const Frame a = render(plain, effects);
    EXPECT_EQ(a.defines.count("RT_VERTEX_COLORS"), 0u);
    GpuScene gpu;
    gpu.upload(plain);
    EXPECT_EQ(gpu.uvs().size(), plain.uvs.size() * sizeof(glm::vec2));   // texture coordinates only

    Scene white = plain;
    white.colors.assign(white.positions.size(), glm::vec4(1.0f));
    const Frame b = render(white, analyze_effects(white));
    EXPECT_EQ(b.defines.count("RT_VERTEX_COLORS"), 1u);
    EXPECT_TRUE(a.image.pixels == b.image.pixels);
    ASSERT_EQ(a.hits.size(), b.hits.size());
    for (std::size_t i = 0; i < a.hits.size(); ++i) {
        EXPECT_EQ(a.hits[i].triangle, b.hits[i].triangle) << i;
        EXPECT_EQ(a.hits[i].t, b.hits[i].t) << i;
    }
    const Frame c = render(with_vertex_colors(plain, 3), analyze_effects(plain));
    EXPECT_FALSE(a.image.pixels == c.image.pixels);
}

}  // namespace
}  // namespace rt::gpu
