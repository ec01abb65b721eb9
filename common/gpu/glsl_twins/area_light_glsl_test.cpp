// The GLSL twin of the area lights' sampling (common/shaders/trace/area_light.glsl) against its C++ original
// (common/trace/area_light.h): for every cell of grids of 1 x 1 to 5 x 5, with and without --light-jitter, on a
// parallelogram, a two-sided trapezoid and a textured sphere of 480 triangles, the sample (point, normal, texture
// coordinates), its emission, the point light it stands for at a surface point, that light's incidence and the
// shadow ray's tmax are the same bits (glsl_twins_test.cpp's contract: 0 ulps on llvmpipe, RT_GLSL_TWIN_ULPS
// elsewhere). And a scene without area lights compiles and uploads nothing for them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>

#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "common/trace/area_light.h"
#include "common/gpu/testing/glsl_test_harness.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/testing/pipeline_fixture.h"

namespace rt::gpu {
namespace {

std::int64_t ordered(float f) {
    std::int32_t i;
    std::memcpy(&i, &f, 4);
    return i < 0 ? std::int64_t(std::numeric_limits<std::int32_t>::min()) - i : i;
}
std::int64_t ulp_diff(float a, float b) {
    if (a == b || (std::isnan(a) && std::isnan(b))) return 0;
    if (std::isnan(a) || std::isnan(b)) return std::numeric_limits<std::int64_t>::max();
    return std::llabs(ordered(a) - ordered(b));
}
std::int64_t ulp_bound() {
    const char* env = std::getenv("RT_GLSL_TWIN_ULPS");
    return env ? std::atoll(env) : 0;
}

Primitive quad(glm::vec3 c, glm::vec3 u, glm::vec3 v, int material) {
    Primitive p;
    p.positions = {c - u - v, c + u - v, c + u + v, c - u + v};
    p.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    p.indices = {0, 1, 2, 0, 2, 3};
    p.material = material;
    return p;
}

// Three lights over a floor: a one-sided parallelogram, a double-sided trapezoid, a sphere with an emissive texture.
Scene light_scene() {
    SceneAsset a;
    Material floor;
    floor.metallic = 0.0f;
    Material panel = floor;
    panel.emissive = {6.0f, 5.0f, 4.0f};
    Material sided = panel;
    sided.double_sided = true;
    Material bulb = floor;
    bulb.emissive = glm::vec3(3.0f);
    bulb.emissive_texture = 0;
    Texture stripes;
    stripes.width = 4;
    stripes.height = 1;
    stripes.rgba8 = {255, 60, 20, 255, 255, 200, 40, 255, 30, 200, 255, 255, 0, 0, 0, 255};
    a.textures = {stripes};
    a.materials = {floor, panel, sided, bulb};
    Primitive trapezoid;
    trapezoid.positions = {{2, 3, 0}, {3, 3, 0}, {5, 3.5f, 1}, {2, 3.5f, 1}};
    trapezoid.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    trapezoid.indices = {0, 3, 1, 1, 3, 2};
    trapezoid.material = 2;
    a.meshes = {{"floor", {quad({0, 0, 0}, {8, 0, 0}, {0, 0, -8}, 0)}},
                {"panel", {quad({0.3f, 3.1f, -0.2f}, {0.7f, 0.0f, 0.1f}, {0.0f, 0.05f, 0.4f}, 1)}},
                {"trapezoid", {trapezoid}},
                {"bulb", {make_uv_sphere({-2.0f, 2.5f, 1.0f}, 0.4f, 24, 10, 3)}}};
    for (int m = 0; m < 4; ++m) {
        Node n;
        n.mesh = m;
        a.nodes.push_back(n);
        a.roots.push_back(m);
    }
    return flatten(a, {});
}

TEST(AreaLightGlslTwins, SamplesTheirLightAndShadowRaysAreBitExact) {
    test_context();
    const Scene lit = light_scene();
    ASSERT_EQ(lit.area_lights.size(), 3u);
    ASSERT_TRUE(lit.area_lights[0].parallelogram);
    ASSERT_FALSE(lit.area_lights[1].parallelogram);
    ASSERT_TRUE(lit.area_lights[1].two_sided);
    GpuScene gpu;
    gpu.upload(lit);
    GlslTestHarness h("area_light_test", R"(
#include "common/shaders/trace/area_light.glsl"
void test_main() {
    const uint light = in_u(0), n = in_u(1), cell = in_u(2), pixel = in_u(4), sample_index = in_u(5);
    const AreaLight area = rt_area_light(light - rt_light_count);
    const vec2 offset = light_grid_offset(in_u(3) != 0u, pixel, sample_index, light);
    const AreaSample s = sample_area_light(area, light_grid_point(n, cell, offset));
    out_vec3(0, s.position); out_vec3(3, s.normal); out_vec2(6, s.uv);
    const vec3 emission = area_light_emission(area, s);
    out_vec3(8, emission);
    Light point;
    const bool lights = area_sample_as_point_light(area, s, emission, n * n, in_vec3(6), point);
    out_b(11, lights);
    vec3 to_light = vec3(0.0);
    float distance = 0.0;
    const vec3 incidence = lights ? light_incidence(point, in_vec3(6), in_vec3(9), to_light, distance) : vec3(0.0);
    out_f(12, lights ? point.intensity : 0.0); out_vec3(13, lights ? point.color : vec3(0.0));
    out_vec3(16, incidence); out_vec3(19, to_light);
    const vec3 origin = offset_ray_origin(int(in_u(12)), in_vec3(6), in_vec3(9), to_light, 1e-4);
    out_f(22, area_shadow_tmax(int(in_u(12)), 1e-4, s, origin, to_light));
}
)", {{"RT_AREA_LIGHTS", "1"}, {"ENABLE_TEXTURES", "1"}});
    std::mt19937 g(5);
    std::uniform_real_distribution<float> coord(-3.0f, 3.0f), height(-0.5f, 4.5f), unit(-1.0f, 1.0f);
    Words in;
    std::vector<float> expected;
    std::size_t count = 0, lit_cells = 0;
    const std::uint32_t punctual = std::uint32_t(lit.lights.size());
    for (std::uint32_t a = 0; a < 3; ++a)
        for (int n = 1; n <= 5; ++n)
            for (int jitter = 0; jitter < 2; ++jitter)
                for (int point = 0; point < 6; ++point) {
                    const glm::vec3 p(coord(g), height(g), coord(g));
                    glm::vec3 normal(unit(g), unit(g), unit(g));
                    normal = glm::normalize(normal + glm::vec3(0.0f, 0.5f, 0.0f));
                    const PixelSample id{std::uint32_t(g() % 100000), std::uint32_t(g() % 16)};
                    const auto offset = OffsetMethod(point % 2);
                    LightGrid grid;
                    grid.n = n;
                    grid.jitter = jitter != 0;
                    for (std::uint32_t cell = 0; cell < grid.cells(); ++cell) {
                        in << (punctual + a) << std::uint32_t(n) << cell << std::uint32_t(jitter) << id.pixel
                           << id.sample << p << normal << std::uint32_t(offset);
                        const AreaLight& area = lit.area_lights[a];
                        const AreaSample s = area_light_cell(lit, grid, punctual + a, cell, id);
                        const glm::vec3 emission = area_light_emission(lit, area, s, true);
                        Light light;
                        const bool lights = area_sample_as_point_light(area, s, emission, grid.cells(), p, light);
                        glm::vec3 to_light(0.0f), incidence(0.0f);
                        float distance = 0.0f;
                        if (lights) incidence = light_incidence(light, p, normal, to_light, distance);
                        lit_cells += incidence != glm::vec3(0.0f);
                        const glm::vec3 origin = offset_ray_origin(offset, p, normal, to_light, 1e-4f);
                        float lights_word;
                        const std::uint32_t one = lights ? 1u : 0u;
                        std::memcpy(&lights_word, &one, 4);
                        expected.insert(expected.end(),
                                        {s.position.x, s.position.y, s.position.z, s.normal.x, s.normal.y, s.normal.z,
                                         s.uv.x, s.uv.y, emission.x, emission.y, emission.z, lights_word,
                                         lights ? light.intensity : 0.0f, lights ? light.color.x : 0.0f,
                                         lights ? light.color.y : 0.0f, lights ? light.color.z : 0.0f, incidence.x,
                                         incidence.y, incidence.z, to_light.x, to_light.y, to_light.z,
                                         area_shadow_tmax(offset, 1e-4f, s, origin, to_light)});
                        ++count;
                    }
                }
    EXPECT_GT(lit_cells, count / 4);   // the points see most lights
    const auto out = h.run(in.words, count, 13, 23, [&] { gpu.bind(); });
    std::int64_t worst = 0;
    std::size_t worst_at = 0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
        const std::int64_t d = ulp_diff(expected[i], word_f(out, i));
        if (d > worst) worst = d, worst_at = i;
    }
    EXPECT_LE(worst, ulp_bound()) << "record " << worst_at / 23 << " word " << worst_at % 23 << ": cpu "
                                  << expected[worst_at] << " gpu " << word_f(out, worst_at);
}

// What a scene pays for area lights: nothing without them (no define, no buffer), the define and the lights' buffer
// with them (soft_shadows: one parallelogram, 96 bytes).
TEST(AreaLightsCost, ScenesWithoutThemCompileNoCodeAndUploadNoBytes) {
    test_context();
    for (const char* name : {"whitted", "cornell", "office", "soft_shadows"}) {
        SCOPED_TRACE(name);
        const Scene scene = flatten(make_builtin_scene(name), {});
        GpuScene gpu;
        gpu.upload(scene);
        const ShaderDefines defines = compiled_defines(gpu, fixture_settings(scene, 16, 12));
        const bool area = std::string(name) == "soft_shadows";
        EXPECT_EQ(defines.count("RT_AREA_LIGHTS"), area ? 1u : 0u);
        EXPECT_EQ(gpu.area_light_count(), area ? 1u : 0u);
        std::size_t without = 0;
        for (const Buffer* b : {&gpu.positions(), &gpu.normals(), &gpu.uvs(), &gpu.material_ids(), &gpu.materials(),
                                &gpu.lights(), &gpu.textures()})
            without += b->size();
        EXPECT_EQ(gpu.bytes() - without - sizeof(GpuSceneBlock), area ? sizeof(GpuAreaLight) : 0u);
    }
}

}  // namespace
}  // namespace rt::gpu
