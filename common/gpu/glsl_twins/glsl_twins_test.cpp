// The GLSL twins in common/shaders/trace/ against their C++ originals in common/trace/, run through the GLSL test
// harness on many inputs, edge cases included (edge- and vertex-aimed rays, degenerate triangles, grazing angles, total
// internal reflection, eta = 1, texture wrap and texel borders).
//
// Accuracy contract (what these tests assert):
//  - Intersection (Moller and watertight), ray offsets, camera rays, Fresnel, reflect/refract, texture sampling,
//    surface coefficients, light incidence, Whitted coefficients and surface points: the GLSL is written operation
//    for operation like the C++ with `precise`, so it is BIT-EXACT wherever the GPU's add/mul/div/sqrt are IEEE
//    correctly rounded, as on llvmpipe (kExactUlps = 0, hit/miss decisions always equal). GLSL only promises
//    2.5 ulp for division and sqrt; on a GPU with such arithmetic, set RT_GLSL_TWIN_ULPS to loosen the bound.
//  - shade_light uses pow(), which GLSL computes as exp2(y * log2(x)): relative error <= kPowRelative (1e-4).
// Over 450 lines by choice: one job, each GLSL twin against its C++ original through the same harness and input
// generators (below); a case per twin, named after it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>

#include "common/trace/intersect.h"
#include "common/trace/offset.h"
#include "common/trace/shading.h"
#include "common/trace/whitted.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/testing/glsl_test_harness.h"

namespace rt::gpu {
namespace {

std::int64_t ulp_bound() {
    const char* env = std::getenv("RT_GLSL_TWIN_ULPS");
    return env ? std::atoll(env) : 0;   // kExactUlps
}
constexpr float kPowRelative = 1e-4f;

std::int64_t ordered(float f) {
    std::int32_t i;
    std::memcpy(&i, &f, 4);
    return i < 0 ? std::int64_t(std::numeric_limits<std::int32_t>::min()) - i : i;
}
std::int64_t ulp_diff(float a, float b) {
    if (std::isnan(a) && std::isnan(b)) return 0;
    if (a == b) return 0;                       // +0 == -0
    if (std::isnan(a) || std::isnan(b)) return std::numeric_limits<std::int64_t>::max();
    return std::llabs(ordered(a) - ordered(b));
}

// Compares word by word as floats (max_ulps) and reports the worst case.
void expect_floats(const std::vector<float>& cpu, const std::vector<std::uint32_t>& gpu, std::int64_t max_ulps,
                   const std::string& what, std::size_t stride) {
    ASSERT_EQ(cpu.size(), gpu.size()) << what;
    std::int64_t worst = 0;
    std::size_t worst_at = 0, failures = 0;
    for (std::size_t i = 0; i < cpu.size(); ++i) {
        const std::int64_t d = ulp_diff(cpu[i], word_f(gpu, i));
        if (d > worst) worst = d, worst_at = i;
        if (d > max_ulps) ++failures;
    }
    EXPECT_EQ(failures, 0u) << what << ": worst " << worst << " ulps at record " << worst_at / stride << " word "
                            << worst_at % stride << ": cpu " << cpu[worst_at] << " gpu " << word_f(gpu, worst_at);
}

float bits_f(std::uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}
float as_word(bool b) { return bits_f(b ? 1u : 0u); }
float as_word(int i) { return bits_f(std::uint32_t(i)); }

struct Rng {
    std::mt19937 g{12345};
    float uniform(float a, float b) { return std::uniform_real_distribution<float>(a, b)(g); }
    glm::vec3 vec(float a, float b) { return {uniform(a, b), uniform(a, b), uniform(a, b)}; }
    glm::vec3 unit() {
        for (;;) {
            const glm::vec3 v = vec(-1, 1);
            const float l = glm::length(v);
            if (l > 0.1f && l <= 1.0f) return v / l;
        }
    }
    int integer(int a, int b) { return std::uniform_int_distribution<int>(a, b)(g); }
};

// ---------------------------------------------------------------------------------------------------------------

TEST(GlslTwins, Intersection) {
    test_context();
    GlslTestHarness h("intersect_test", R"(
#include "common/shaders/trace/intersect.glsl"
void test_main() {
    Ray r = make_ray(in_vec3(0), in_vec3(3), in_f(6));
    float t, u, v;
    const bool m = intersect_moller(r, in_vec3(7), in_vec3(10), in_vec3(13), t, u, v);
    out_b(0, m); out_f(1, m ? t : 0.0); out_f(2, m ? u : 0.0); out_f(3, m ? v : 0.0);
    const bool w = intersect_watertight(r, watertight_ray(r.direction), in_vec3(7), in_vec3(10), in_vec3(13), t, u, v);
    out_b(4, w); out_f(5, w ? t : 0.0); out_f(6, w ? u : 0.0); out_f(7, w ? v : 0.0);
}
)");
    Rng rng;
    Words in;
    std::vector<float> expected;
    std::size_t count = 0;
    auto add = [&](const Ray<float>& ray, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
        in << ray.origin << ray.direction << ray.tmax << a << b << c;
        float t = 0, u = 0, v = 0;
        const bool m = intersect_moller(ray, a, b, c, t, u, v);
        expected.insert(expected.end(), {as_word(m), m ? t : 0.0f, m ? u : 0.0f, m ? v : 0.0f});
        t = u = v = 0;
        const bool w = intersect_watertight(ray, WatertightRay<float>(ray.direction), a, b, c, t, u, v);
        expected.insert(expected.end(), {as_word(w), w ? t : 0.0f, w ? u : 0.0f, w ? v : 0.0f});
        ++count;
    };
    const float inf = std::numeric_limits<float>::infinity();
    for (int mesh = 0; mesh < 40; ++mesh) {
        // A bumpy 4x4 grid of quads (two triangles each) placed at random scales and offsets.
        const float scale = std::pow(10.0f, rng.uniform(-3, 3));
        const glm::vec3 offset = rng.vec(-1, 1) * std::pow(10.0f, rng.uniform(-2, 4));
        const glm::vec3 ax = rng.unit(), ay = glm::normalize(glm::cross(ax, rng.unit())), az = glm::cross(ax, ay);
        auto P = [&](int i, int j) {
            const float hgt = float((i * 7 + j * 3) % 5) * 0.1f;
            return offset + scale * (float(i) * ax + float(j) * ay + hgt * az);
        };
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                const glm::vec3 a = P(i, j), b = P(i + 1, j), c = P(i + 1, j + 1), d = P(i, j + 1);
                const glm::vec3 eye = offset + scale * (rng.vec(-2, 6) + az * rng.uniform(2, 10));
                // Aimed at the shared diagonal (a-c), at the vertices and at random interior points, each tested
                // against both triangles of the quad.
                std::vector<glm::vec3> targets = {glm::mix(a, c, rng.uniform(0, 1)), a, c, glm::mix(a, b, 0.5f),
                                                  (a + b + c) / 3.0f, (a + c + d) / 3.0f};
                for (const glm::vec3& target : targets) {
                    Ray<float> ray;
                    ray.origin = eye;
                    ray.direction = glm::normalize(target - eye);
                    ray.tmax = rng.integer(0, 3) == 0 ? glm::length(target - eye) * rng.uniform(0.5f, 1.5f) : inf;
                    add(ray, a, b, c);
                    add(ray, a, c, d);
                }
                // Grazing: in the plane of the triangle, and nearly so.
                Ray<float> graze;
                graze.origin = a - (c - a);
                graze.direction = glm::normalize(c - a);
                add(graze, a, b, c);
                graze.direction = glm::normalize(c - a + az * (scale * 1e-4f));
                add(graze, a, b, c);
            }
    }
    // Degenerate triangles, NaN vertices, zero direction components.
    Ray<float> ray;
    ray.origin = {0.25f, 0.25f, 1.0f};
    ray.direction = {0, 0, -1};
    add(ray, {0, 0, 0}, {1, 1, 0}, {2, 2, 0});                              // collinear
    add(ray, {0, 0, 0}, {0, 0, 0}, {1, 0, 0});                              // repeated vertex
    add(ray, {0, 0, 0}, {1, 0, 0}, {0, std::nanf(""), 0});                  // NaN
    add(ray, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});                              // plain hit
    add(ray, {0, 0, 0}, {0, 1, 0}, {1, 0, 0});                              // other winding
    ray.origin = {0.0f, 0.0f, 1.0f};
    add(ray, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});                              // exactly at a vertex
    ray.origin = {0.5f, 0.0f, 1.0f};
    add(ray, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});                              // exactly on an edge
    add(ray, {1, 0, 0}, {0, 0, 0}, {0, -1, 0});                             // the neighbour across that edge
    const auto out = h.run(in.words, count, 16, 8);
    // Hit decisions must agree exactly.
    std::size_t hit_mismatch = 0, hits = 0;
    for (std::size_t i = 0; i < count; ++i) {
        hits += out[i * 8 + 4];
        for (int k : {0, 4})
            if (out[i * 8 + std::size_t(k)] != std::uint32_t(expected[i * 8 + std::size_t(k)] != 0.0f ? 1 : 0)) ++hit_mismatch;
    }
    EXPECT_EQ(hit_mismatch, 0u);
    EXPECT_GT(hits, count / 4);
    expect_floats(expected, out, ulp_bound(), "intersection t/u/v", 8);
    std::printf("intersection: %zu ray/triangle pairs, %zu watertight hits\n", count, hits);
}

TEST(GlslTwins, Offsets) {
    test_context();
    GlslTestHarness h("offset_test", R"(
#include "common/shaders/trace/offset.glsl"
void test_main() {
    out_vec3(0, offset_robust(in_vec3(0), in_vec3(3)));
    out_vec3(3, offset_epsilon(in_vec3(0), in_vec3(3), in_f(9)));
    out_vec3(6, offset_ray_origin(RT_OFFSET_ROBUST, in_vec3(0), in_vec3(3), in_vec3(6), in_f(9)));
    out_vec3(9, offset_ray_origin(RT_OFFSET_EPSILON, in_vec3(0), in_vec3(3), in_vec3(6), in_f(9)));
}
)");
    Rng rng;
    Words in;
    std::vector<float> expected;
    std::size_t count = 0;
    auto add = [&](glm::vec3 p, glm::vec3 n, glm::vec3 d, float eps) {
        in << p << n << d << eps;
        for (const glm::vec3& r : {offset_robust(p, n), offset_epsilon(p, n, eps),
                                   offset_ray_origin(OffsetMethod::Robust, p, n, d, eps),
                                   offset_ray_origin(OffsetMethod::Epsilon, p, n, d, eps)})
            expected.insert(expected.end(), {r.x, r.y, r.z});
        ++count;
    };
    for (int i = 0; i < 4000; ++i) {
        glm::vec3 p = rng.vec(-1, 1) * std::pow(10.0f, rng.uniform(-6, 6));
        if (i % 7 == 0) p.x = 0.0f;
        if (i % 11 == 0) p.y = (i % 2 ? 1.0f : -1.0f) / 32.0f;   // the near-origin threshold
        add(p, rng.unit(), rng.unit(), rng.integer(0, 1) ? kDefaultEpsilon : 1e-2f);
    }
    add({1, 2, 3}, {std::numeric_limits<float>::infinity(), 0, 1}, {0, 0, 1}, 1e-4f);
    const auto out = h.run(in.words, count, 10, 12);
    expect_floats(expected, out, ulp_bound(), "offsets", 12);
}

TEST(GlslTwins, CameraRays) {
    test_context();
    GlslTestHarness h("camera_test", R"(
#include "common/shaders/trace/camera.glsl"
void test_main() {
    Camera c;
    c.position = in_vec3(0); c.projection = in_i(3); c.right = in_vec3(4); c.tan_half_fov = in_f(7);
    c.up = in_vec3(8); c.aspect = in_f(11); c.forward = in_vec3(12); c.xmag = in_f(15);
    c.ymag = in_f(16); c.znear = in_f(17); c.zfar = in_f(18); c.yfov = in_f(19);
    Ray r = camera_ray(c, in_i(20), in_i(21), in_f(22), in_f(23));
    out_vec3(0, r.origin);
    out_vec3(3, r.direction);
}
)");
    Rng rng;
    Words in;
    std::vector<float> expected;
    std::size_t count = 0;
    for (int i = 0; i < 3000; ++i) {
        Camera cam;
        cam.projection = i % 4 == 0 ? Projection::Orthographic : Projection::Perspective;
        cam.yfov = rng.uniform(0.1f, 2.5f);
        cam.aspect = i % 3 == 0 ? 0.0f : rng.uniform(0.5f, 2.5f);
        cam.xmag = rng.uniform(0.1f, 10);
        cam.ymag = rng.uniform(0.1f, 10);
        cam.position = rng.vec(-100, 100);
        cam.forward = rng.unit();
        cam.right = glm::normalize(glm::cross(cam.forward, rng.unit()));
        cam.up = glm::cross(cam.right, cam.forward);
        const int w = rng.integer(1, 4000), hgt = rng.integer(1, 3000);
        const float x = rng.uniform(0, float(w)), y = rng.uniform(0, float(hgt));
        const GpuCamera g = to_gpu(cam);
        in << g.position << g.projection << g.right << g.tan_half_fov << g.up << g.aspect << g.forward << g.xmag
           << g.ymag << g.znear << g.zfar << g.yfov << std::int32_t(w) << std::int32_t(hgt) << x << y;
        const Ray<float> r = camera_ray<float>(cam, w, hgt, x, y);
        expected.insert(expected.end(), {r.origin.x, r.origin.y, r.origin.z, r.direction.x, r.direction.y, r.direction.z});
        ++count;
    }
    expect_floats(expected, h.run(in.words, count, 24, 6), ulp_bound(), "camera rays", 6);
}

TEST(GlslTwins, FresnelReflectRefract) {
    test_context();
    GlslTestHarness h("fresnel_test", R"(
#include "common/shaders/trace/shading.glsl"
void test_main() {
    const float cos_i = in_f(0), eta = in_f(1);
    out_f(0, fresnel_exact(cos_i, eta));
    out_f(1, fresnel_schlick(cos_i, eta));
    out_f(2, fresnel(RT_FRESNEL_EXACT, cos_i, eta));
    out_vec3(3, reflect_dir(in_vec3(2), in_vec3(5)));
    vec3 t;
    const bool ok = refract_dir(in_vec3(2), in_vec3(5), eta, t);
    out_b(6, ok);
    out_vec3(7, ok ? t : vec3(0.0));
}
)");
    Rng rng;
    Words in;
    std::vector<float> expected;
    std::size_t count = 0;
    const float etas[] = {1.0f, 1.5f, 1.0f / 1.5f, 1.33f, 1.0f / 1.33f, 2.4f, 1.0f / 2.4f, 0.5f};
    for (int i = 0; i < 4000; ++i) {
        const float eta = i % 10 == 9 ? rng.uniform(0.3f, 3.0f) : etas[i % 8];
        float cos_i = rng.uniform(0, 1);
        if (i % 13 == 0) cos_i = 0.0f;                  // grazing
        if (i % 17 == 0) cos_i = 1.0f;                  // normal incidence
        if (i % 19 == 0) cos_i = rng.uniform(0, 1e-3f); // nearly grazing
        if (i % 23 == 0) cos_i = -0.5f;                 // clamped
        // Incident direction d at that angle to n (d . n = -cos_i).
        const glm::vec3 n = rng.unit();
        const glm::vec3 tangent = glm::normalize(glm::cross(n, rng.unit()));
        const float c = std::clamp(cos_i, 0.0f, 1.0f);
        const glm::vec3 d = glm::normalize(-c * n + std::sqrt(1 - c * c) * tangent);
        in << cos_i << eta << d << n;
        const glm::vec3 r = reflect_dir(d, n);
        glm::vec3 t(0.0f);
        const bool ok = refract_dir(d, n, eta, t);
        expected.insert(expected.end(), {fresnel_exact(cos_i, eta), fresnel_schlick(cos_i, eta),
                                         fresnel(FresnelMode::Exact, cos_i, eta), r.x, r.y, r.z, as_word(ok),
                                         ok ? t.x : 0.0f, ok ? t.y : 0.0f, ok ? t.z : 0.0f});
        ++count;
    }
    const auto out = h.run(in.words, count, 8, 10);
    expect_floats(expected, out, ulp_bound(), "fresnel/reflect/refract", 10);
    std::size_t tir = 0;
    for (std::size_t i = 0; i < count; ++i) tir += out[i * 10 + 6] == 0;
    EXPECT_GT(tir, 100u);   // total internal reflection was exercised
}

// ambient_light in each of its three compiled variants against the C++ switch, to the bit, over normals facing every
// way (straight up and down included) and diffuse colours from 0 to 1.
TEST(GlslTwins, AmbientLightOfEveryModel) {
    test_context();
    const std::pair<AmbientModel, ShaderDefines> models[] = {{AmbientModel::Constant, {}},
                                                             {AmbientModel::Hemisphere, {{"RT_AMBIENT_HEMISPHERE", "1"}}},
                                                             {AmbientModel::None, {{"RT_AMBIENT_NONE", "1"}}}};
    for (const auto& [model, defines] : models) {
        GlslTestHarness h(std::string("ambient_") + ambient_name(model) + "_test", R"(
#include "common/shaders/trace/shading.glsl"
void test_main() { out_vec3(0, ambient_light(in_vec3(0), in_vec3(3))); }
)", defines);
        Rng rng;
        Words in;
        std::vector<float> expected;
        std::size_t count = 0;
        for (int i = 0; i < 2000; ++i) {
            glm::vec3 n = rng.unit();
            if (i == 0) n = glm::vec3(0, 1, 0);
            if (i == 1) n = glm::vec3(0, -1, 0);
            const glm::vec3 diffuse = i == 2 ? glm::vec3(0.0f) : rng.vec(0, 1);
            in << diffuse << n;
            const glm::vec3 a = ambient_light(model, diffuse, n);
            expected.insert(expected.end(), {a.x, a.y, a.z});
            ++count;
        }
        expect_floats(expected, h.run(in.words, count, 6, 3), 0, std::string("ambient ") + ambient_name(model), 3);
    }
}

TEST(GlslTwins, SurfaceCoefficientsLightsAndWhittedWeights) {
    test_context();
    GlslTestHarness h("shading_test", R"(
#include "common/shaders/testing/test_inputs.glsl"
void test_main() {
    const SurfaceCoefficients s = surface_coefficients(in_material(0u), in_vec4(16));
    out_vec3(0, s.diffuse); out_vec3(3, s.specular); out_f(6, s.shininess); out_vec3(7, s.mirror);
    out_f(10, s.smoothness); out_f(11, s.dielectric); out_f(12, s.transmission); out_vec3(13, s.base);
    out_vec3(16, s.f0_dielectric); out_vec3(19, s.emissive); out_f(22, s.ior);
    vec3 to_light;
    float distance;
    const vec3 n = in_vec3(39);
    const vec3 inc = light_incidence(in_light(20u), in_vec3(36), n, to_light, distance);
    const bool lit = inc != vec3(0.0);
    out_vec3(23, inc); out_vec3(26, lit ? to_light : vec3(0.0)); out_f(29, lit ? distance : 0.0);
    const ReflectRefract k = reflect_refract_coefficients(s, in_u(42) != 0u, in_f(43), in_f(44));
    out_vec3(30, k.reflection); out_vec3(33, k.refraction);
    // shade_light, compared with a relative tolerance (pow); a separate word range.
    out_vec3(36, lit ? shade_light(s, inc, n, to_light, in_vec3(45)) : vec3(0.0));
}
)");
    struct Dummy {};
    Rng rng;
    Words in;
    std::vector<float> expected, expected_shade;
    std::size_t count = 0;
    for (int i = 0; i < 3000; ++i) {
        Material m;
        m.base_color = glm::vec4(rng.vec(0, 1), rng.uniform(0, 1));
        m.emissive = i % 5 == 0 ? rng.vec(0, 3) : glm::vec3(0.0f);
        m.base_color_texture = -1;
        m.specular_color = i % 3 == 0 ? rng.vec(0, 1.5f) : glm::vec3(1.0f);
        m.metallic = i % 4 == 0 ? 1.0f : (i % 4 == 1 ? 0.0f : rng.uniform(-0.2f, 1.2f));
        m.roughness = i % 6 == 0 ? 0.0f : rng.uniform(-0.1f, 1.1f);
        m.transmission = i % 3 == 0 ? 1.0f : rng.uniform(0, 1);
        m.ior = i % 9 == 0 ? 1.0f : (i % 9 == 1 ? 0.0f : rng.uniform(1.0f, 2.5f));   // eta = 1 and the default
        m.specular = rng.uniform(0, 1);
        const glm::vec4 tex(rng.vec(0, 1), 1.0f);
        Light l;
        l.type = LightType(i % 3);
        l.color = rng.vec(0, 1);
        l.intensity = rng.uniform(0, 100);
        l.range = i % 2 ? 0.0f : rng.uniform(0.5f, 20);
        l.inner_cone = rng.uniform(0, 0.5f);
        l.outer_cone = i % 7 == 0 ? l.inner_cone : rng.uniform(0.5f, 1.5f);   // equal cones: the 1e-4 floor
        l.position = rng.vec(-10, 10);
        l.direction = rng.unit() * rng.uniform(0.5f, 2.0f);
        const glm::vec3 p = rng.vec(-10, 10), n = rng.unit(), eye = rng.unit();
        // Point the spot at p now and then, so the cone ramp is exercised.
        if (i % 3 == 1 && i % 2 == 0) l.direction = glm::normalize(p - l.position + rng.vec(-1, 1));
        const bool front = rng.integer(0, 1) == 1;
        const float cos_i = rng.uniform(0, 1), f = rng.uniform(0, 1);
        const GpuMaterial gm = to_gpu(m);
        const GpuLight gl = to_gpu(l);
        in << gm.base_color << gm.emissive << gm.base_color_texture << gm.specular_color << gm.metallic << gm.roughness
           << gm.transmission << gm.ior << gm.specular << tex;
        in << gl.color << gl.type << gl.position << gl.intensity << gl.direction << gl.range << gl.inner_cone
           << gl.outer_cone << gl.cos_inner << gl.cos_outer;
        in << p << n << front << cos_i << f << eye;
        const SurfaceCoefficients s = surface_coefficients(m, tex);
        glm::vec3 to_light(0.0f);
        float distance = 0.0f;
        const glm::vec3 inc = light_incidence(l, p, n, to_light, distance);
        const bool lit = inc != glm::vec3(0.0f);
        if (!lit) to_light = glm::vec3(0.0f), distance = 0.0f;
        const auto k = Whitted<float, Dummy>::coefficients(s, front, cos_i, f);
        expected.insert(expected.end(), {s.diffuse.x, s.diffuse.y, s.diffuse.z, s.specular.x, s.specular.y,
                                         s.specular.z, s.shininess, s.mirror.x, s.mirror.y, s.mirror.z, s.smoothness,
                                         s.dielectric, s.transmission, s.base.x, s.base.y, s.base.z,
                                         s.f0_dielectric.x, s.f0_dielectric.y, s.f0_dielectric.z, s.emissive.x,
                                         s.emissive.y, s.emissive.z, s.ior, inc.x, inc.y, inc.z, to_light.x,
                                         to_light.y, to_light.z, distance, k.reflection.x, k.reflection.y,
                                         k.reflection.z, k.refraction.x, k.refraction.y, k.refraction.z});
        const glm::vec3 shade = lit ? shade_light(s, inc, n, to_light, eye) : glm::vec3(0.0f);
        expected_shade.insert(expected_shade.end(), {shade.x, shade.y, shade.z});
        ++count;
    }
    const auto out = h.run(in.words, count, 48, 39);
    std::vector<std::uint32_t> exact, shade;
    for (std::size_t i = 0; i < count; ++i) {
        exact.insert(exact.end(), out.begin() + std::ptrdiff_t(i * 39), out.begin() + std::ptrdiff_t(i * 39 + 36));
        shade.insert(shade.end(), out.begin() + std::ptrdiff_t(i * 39 + 36), out.begin() + std::ptrdiff_t(i * 39 + 39));
    }
    expect_floats(expected, exact, ulp_bound(), "surface coefficients / light incidence / Whitted weights", 36);
    std::size_t lit = 0;
    float worst = 0.0f;
    for (std::size_t i = 0; i < expected_shade.size(); ++i) {
        const float c = expected_shade[i], g = word_f(shade, i);
        lit += c != 0.0f;
        const float rel = std::abs(c - g) / std::max(std::abs(c), 1e-30f);
        worst = std::max(worst, c == g ? 0.0f : rel);
    }
    EXPECT_LE(worst, kPowRelative) << "shade_light relative error";
    EXPECT_GT(lit, count / 4);
    std::printf("shade_light: worst relative error %g over %zu lit samples\n", double(worst), lit);
}

// ---------------------------------------------------------------------------------------------------------------
// Through GpuScene: texture sampling, surface points, and the buffer layouts themselves.

Scene test_scene(Rng& rng) {
    Scene scene;
    auto texture = [&](int w, int h, bool nearest, Wrap wrap_s = Wrap::Repeat, Wrap wrap_t = Wrap::Repeat) {
        Texture t;
        t.width = w;
        t.height = h;
        t.nearest = nearest;
        t.wrap_s = wrap_s;
        t.wrap_t = wrap_t;
        t.rgba8.resize(std::size_t(w * h * 4));
        for (auto& b : t.rgba8) b = std::uint8_t(rng.integer(0, 255));
        return t;
    };
    scene.textures = {texture(1, 1, false), texture(3, 5, true), texture(7, 4, false), texture(16, 16, false),
                      texture(5, 3, true),
                      // Every wrap mode on each axis, bilinear and nearest (glTF samplers' wrapS / wrapT).
                      texture(6, 5, false, Wrap::ClampToEdge, Wrap::MirroredRepeat),
                      texture(4, 7, false, Wrap::MirroredRepeat, Wrap::ClampToEdge),
                      texture(5, 4, true, Wrap::ClampToEdge, Wrap::Repeat), texture(3, 6, true, Wrap::MirroredRepeat,
                      Wrap::MirroredRepeat), texture(1, 1, false, Wrap::ClampToEdge, Wrap::ClampToEdge)};
    for (int i = 0; i < 50; ++i) {
        for (int k = 0; k < 3; ++k) {
            scene.positions.push_back(rng.vec(-5, 5));
            scene.normals.push_back(rng.unit());
            scene.uvs.push_back({rng.uniform(-2, 2), rng.uniform(-2, 2)});
        }
        scene.material_ids.push_back(std::uint32_t(i % 3));
    }
    // A degenerate triangle and a zero normal: the fallbacks of surface_point.
    scene.positions[3] = scene.positions[4] = scene.positions[5];
    scene.normals[6] = scene.normals[7] = scene.normals[8] = glm::vec3(0.0f);
    for (int i = 0; i < 3; ++i) {
        Material m;
        m.name = std::string(1, char('a' + i));   // (not "m" + to_string: GCC 12 -Wrestrict false positive)
        m.base_color = glm::vec4(rng.vec(0, 1), 1.0f);
        m.base_color_texture = i - 1;
        m.metallic = rng.uniform(0, 1);
        m.ior = 1.0f + float(i) * 0.25f;
        scene.materials.push_back(m);
    }
    Light l;
    l.type = LightType::Spot;
    l.position = {1, 2, 3};
    l.range = 7;
    scene.lights.push_back(l);
    l.type = LightType::Directional;
    scene.lights.push_back(l);
    scene.camera.position = {1, 2, 3};
    scene.camera.yfov = 0.9f;
    scene.background = {0.1f, 0.2f, 0.3f};
    return scene;
}

TEST(GlslTwins, TextureSampling) {
    test_context();
    Rng rng;
    const Scene scene = test_scene(rng);
    GpuScene gpu;
    gpu.upload(scene);
    GlslTestHarness h("texture_test", R"(
#include "common/shaders/trace/shading.glsl"
void test_main() { out_vec4(0, sample_texture(in_i(0), in_vec2(1))); }
)");
    Words in;
    std::vector<float> expected;
    std::size_t count = 0;
    for (int i = 0; i < 6000; ++i) {
        const int t = i % int(scene.textures.size());
        const Texture& tex = scene.textures[std::size_t(t)];
        glm::vec2 uv(rng.uniform(-3, 3), rng.uniform(-3, 3));
        if (i % 5 == 0) uv = glm::vec2(float(rng.integer(-8, 8)) / float(tex.width), float(rng.integer(-8, 8)) / float(tex.height));   // texel edges
        if (i % 7 == 0) uv = (glm::vec2(rng.integer(0, 20), rng.integer(0, 20)) + 0.5f) / glm::vec2(tex.width, tex.height);   // texel centres
        if (i % 97 == 0) uv = glm::vec2(1e6f + rng.uniform(0, 1), -1e5f);   // huge
        if (i == 1) uv = glm::vec2(std::nanf(""), 0.5f);
        if (i == 2) uv = glm::vec2(std::numeric_limits<float>::infinity(), 0.5f);
        if (i == 3) uv = glm::vec2(0.99999994f, 0.99999994f);   // fx rounds to the width
        in << std::int32_t(t) << uv;
        const glm::vec4 c = sample_texture(tex, uv);
        expected.insert(expected.end(), {c.x, c.y, c.z, c.w});
        ++count;
    }
    expect_floats(expected, h.run(in.words, count, 3, 4, [&] { gpu.bind(); }), ulp_bound(), "sample_texture", 4);
}

// Metallic-roughness (linear) and emissive (sRGB) textures scaling a material's factors, as the CPU does.
TEST(GlslTwins, SurfaceTexturesScaleTheFactors) {
    test_context();
    Rng rng;
    Scene scene = test_scene(rng);
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        Material& m = scene.materials[i];
        m.roughness = rng.uniform(0, 1);
        m.emissive = rng.vec(0, 3);
        m.metallic_roughness_texture = int(i) + 1;          // 1..3
        m.emissive_texture = int(i + 2) % 5;                // 2, 3, 4
        m.transmission = rng.uniform(0, 1);
        m.transmission_texture = int(i + 3) % 5;            // 3, 4, 0
    }
    scene.materials[0].metallic_roughness_texture = -1;     // one without: factors unchanged
    GpuScene gpu;
    gpu.upload(scene);
    GlslTestHarness h("surface_textures_test", R"(
#include "common/shaders/trace/shading.glsl"
void test_main() {
    const Material m = rt_materials[in_u(0)];
    const SurfaceTexels t = sample_surface_textures(m, in_vec2(1));
    const SurfaceCoefficients s = surface_coefficients(m, t);
    out_vec4(0, vec4(t.roughness, t.metallic, s.smoothness, s.dielectric));
    out_vec4(4, vec4(s.emissive, s.transmission));
}
)");
    Words in;
    std::vector<float> expected;
    std::size_t count = 0;
    for (int i = 0; i < 3000; ++i) {
        const std::uint32_t mi = std::uint32_t(i % 3);
        const glm::vec2 uv(rng.uniform(-3, 3), rng.uniform(-3, 3));
        in << mi << uv;
        const Material& m = scene.materials[mi];
        const SurfaceTexels t = sample_surface_textures(m, scene.textures, uv);
        const SurfaceCoefficients s = surface_coefficients(m, t);
        expected.insert(expected.end(), {t.roughness, t.metallic, s.smoothness, s.dielectric,
                                         s.emissive.x, s.emissive.y, s.emissive.z, s.transmission});
        ++count;
    }
    expect_floats(expected, h.run(in.words, count, 3, 8, [&] { gpu.bind(); }), ulp_bound(), "surface textures", 8);
}

TEST(GlslTwins, SurfacePointAndSceneLayout) {
    test_context();
    Rng rng;
    const Scene scene = test_scene(rng);
    GpuScene gpu;
    gpu.upload(scene);
    EXPECT_EQ(gpu.triangle_count(), scene.triangle_count());
    EXPECT_GT(gpu.bytes(), 0u);
    GlslTestHarness h("surface_point_test", R"(
#include "common/shaders/trace/shading.glsl"
void test_main() {
    const uint tri = in_u(0);
    const SurfacePoint s = surface_point(make_ray(in_vec3(1), in_vec3(4), RT_INFINITY), tri, in_f(7), in_f(8));
    out_vec3(0, s.position); out_vec3(3, s.geometric_normal); out_vec3(6, s.shading_normal); out_vec2(9, s.uv);
    out_b(11, s.front_face); out_u(12, s.material);
    // Layout checks: what the shader reads from the scene's buffers.
    const Material m = rt_materials[tri % rt_material_count];
    out_vec4(13, m.base_color); out_i(17, m.base_color_texture); out_f(18, m.metallic); out_f(19, m.ior);
    const Light l = rt_lights[tri % rt_light_count];
    out_i(20, l.type); out_vec3(21, l.position); out_f(24, l.range); out_f(25, l.cos_outer);
    out_vec3(26, rt_camera.position); out_f(29, rt_camera.tan_half_fov); out_vec3(30, rt_background);
    out_u(33, rt_triangle_count); out_u(34, rt_texture_count);
    const TextureInfo ti = rt_texture_info(int(tri % rt_texture_count));
    out_i(35, ti.width); out_i(36, ti.height); out_i(37, ti.sampler); out_f(38, rt_srgb_lut[tri % 256u]);
}
)");
    struct Dummy {};
    Words in;
    std::vector<float> expected;
    std::size_t count = 0;
    for (std::uint32_t tri = 0; tri < scene.triangle_count(); ++tri)
        for (int k = 0; k < 4; ++k) {
            Ray<float> ray;
            ray.origin = rng.vec(-10, 10);
            ray.direction = rng.unit();
            Hit<float> hit;
            hit.triangle = std::int32_t(tri);
            hit.u = rng.uniform(0, 1);
            hit.v = rng.uniform(0, 1 - hit.u);
            in << tri << ray.origin << ray.direction << hit.u << hit.v;
            const SurfacePoint<float> s = surface_point(scene, ray, hit);
            const Material& m = scene.materials[tri % scene.materials.size()];
            const GpuLight l = to_gpu(scene.lights[tri % scene.lights.size()]);
            const GpuCamera cam = to_gpu(scene.camera);
            const Texture& t = scene.textures[tri % scene.textures.size()];
            expected.insert(expected.end(),
                            {s.position.x, s.position.y, s.position.z, s.geometric_normal.x, s.geometric_normal.y,
                             s.geometric_normal.z, s.shading_normal.x, s.shading_normal.y, s.shading_normal.z, s.uv.x,
                             s.uv.y, as_word(s.front_face), as_word(int(s.material)), m.base_color.x, m.base_color.y,
                             m.base_color.z, m.base_color.w, as_word(m.base_color_texture), m.metallic, m.ior,
                             as_word(l.type), l.position.x, l.position.y, l.position.z, l.range, l.cos_outer,
                             cam.position.x, cam.position.y, cam.position.z, cam.tan_half_fov, scene.background.x,
                             scene.background.y, scene.background.z, as_word(int(scene.triangle_count())),
                             as_word(int(scene.textures.size())), as_word(t.width), as_word(t.height),
                             as_word((t.nearest ? 1 : 0) | int(t.wrap_s) << 1 | int(t.wrap_t) << 3), srgb_to_linear(float(tri % 256) / 255.0f)});
            ++count;
        }
    expect_floats(expected, h.run(in.words, count, 9, 39, [&] { gpu.bind(); }), ulp_bound(),
                  "surface_point and scene layout", 39);
}

}  // namespace
}  // namespace rt::gpu
