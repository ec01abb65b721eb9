// The numerically hard cases for the GLSL twins (common/shaders/): the same cases as the CPU suites
// (01_naive/intersect_watertight_test.cpp, offset_test.cpp, shading_hard_cases_test.cpp and
// whitted_hard_cases_test.cpp, and common/trace/intersect_inputs_test.cpp), on the same meshes and rays
// (common/trace/hard_cases.h), asserted on what the GLSL routines compute in compute shaders (the GLSL test harness;
// llvmpipe in CI). glsl_twins_test.cpp checks that GLSL and C++ agree on sample inputs; this file checks the
// properties themselves on the GPU side:
//
//   Watertight        rays aimed exactly at shared vertices and edges of closed meshes never slip through
//                     intersect_watertight (looped over every triangle of the mesh, uploaded as a GpuScene); the miss
//                     rate of intersect_moller on the same rays is printed.
//   SelfIntersection  rays spawned with offset_ray_origin (robust) off surface_point never re-hit their surface, at
//                     coordinates 1e-4..1e6 and scales 1e-3..1e3; the fixed epsilon fails at 1e4; thin walls stop
//                     refracted rays with the robust offset, and leak with the epsilon when thinner than it.
//   Inputs            degenerate and non-finite triangles and rays never hit; Fresnel, refraction, surface
//                     coefficients, light incidence and shade_light stay finite at their edges (grazing, total
//                     internal reflection, eta = 1, lights at the point, equal spot cones, ...).
//
// Run build/tests/unit_tests_common_gpu --gtest_filter='GlslHardCases.*' to see the rates they print.
// Over 450 lines by choice: the five cases share one compute-shader harness per GLSL routine (set up below) and the
// CPU suites' meshes; split by header they would each rebuild the same harnesses.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "common/trace/hard_cases.h"
#include "common/trace/intersect.h"
#include "common/trace/offset.h"
#include "common/trace/shading.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/testing/glsl_test_harness.h"

namespace rt::gpu {
namespace {

using namespace rt::hard_cases;

bool finite(float f) { return std::isfinite(f); }

// ---------------------------------------------------------------------------------------------------------------
// Watertightness.

// One ray per invocation against every triangle of the bound scene: did any triangle report a hit, for each method?
// (A ray aimed into a closed mesh hits it or misses it as a whole: any hit is enough, so each loop stops early.)
const char* kAnyHitBody = R"(
#include "common/shaders/trace/scene.glsl"
#include "common/shaders/trace/intersect.glsl"
void test_main() {
    const Ray r = make_ray(in_vec3(0), in_vec3(3), RT_INFINITY);
    const WatertightRay w = watertight_ray(r.direction);
    bool moller = false, watertight = false;
    for (uint i = 0u; i < rt_triangle_count && !(moller && watertight); ++i) {
        vec3 a, b, c;
        load_triangle(i, a, b, c);
        float t, u, v;
        if (!moller) moller = intersect_moller(r, a, b, c, t, u, v);
        if (!watertight) watertight = intersect_watertight(r, w, a, b, c, t, u, v);
    }
    out_b(0, moller);
    out_b(1, watertight);
}
)";

struct GlslMisses {
    std::size_t rays = 0, outside = 0, moller = 0, watertight = 0;
    double rate(std::size_t misses) const { return rays ? double(misses) / double(rays) : 0.0; }
};

// The CPU suite's oracle (01_naive/intersect_watertight_test.cpp asks stage 01's brute-force tracer the same): does
// the ray, converted exactly to long double (64-bit mantissa), hit any triangle of `s` with the watertight test?
bool exact_watertight_hit(const Scene& s, const Ray<float>& ray) {
    using Exact = long double;
    const Ray<Exact> r{Vec3<Exact>(ray.origin), Vec3<Exact>(ray.direction)};
    const WatertightRay<Exact> w(r.direction);
    for (std::size_t i = 0; i < s.positions.size() / 3; ++i) {
        Exact t, u, v;
        if (intersect_watertight(r, w, Vec3<Exact>(s.positions[3 * i]), Vec3<Exact>(s.positions[3 * i + 1]),
                                 Vec3<Exact>(s.positions[3 * i + 2]), t, u, v))
            return true;
    }
    return false;
}

// Runs the CPU suite's float rays for `s` through GLSL. A ray that some method misses is checked with the oracle
// above: one that misses there too passes outside the mesh (its rounded origin turned its aim) and is left out, for
// both methods, as on the CPU.
GlslMisses glsl_misses(const Scene& s, const WatertightRayCounts& counts) {
    const std::vector<Ray<float>> rays = rays_at_shared_vertices_and_edges<float>(
        s, counts.directions_per_vertex, counts.points_per_edge, counts.directions_per_point, kWatertightSeed);
    test_context();
    GpuScene gpu;
    gpu.upload(s);
    GlslTestHarness h("hard_cases_any_hit", kAnyHitBody);
    Words in;
    for (const Ray<float>& r : rays) in << r.origin << r.direction;
    const std::vector<std::uint32_t> out = h.run(in.words, rays.size(), 6, 2, [&] { gpu.bind(); });
    GlslMisses m;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const bool moller_missed = out[2 * i] == 0, watertight_missed = out[2 * i + 1] == 0;
        if ((moller_missed || watertight_missed) && !exact_watertight_hit(s, rays[i])) {
            ++m.outside;
            continue;
        }
        ++m.rays;
        m.moller += moller_missed ? 1 : 0;
        m.watertight += watertight_missed ? 1 : 0;
    }
    return m;
}

void expect_no_glsl_watertight_misses(const char* mesh, const Scene& s, const WatertightRayCounts& counts) {
    ASSERT_TRUE(topology_of(s).closed()) << mesh;
    const GlslMisses m = glsl_misses(s, counts);
    std::printf("[ glsl watertight ] %s (%zu triangles), rays aimed exactly at shared vertices and edges, GLSL float:\n"
                "                    %zu rays, intersect_moller misses %zu (rate %.2e), intersect_watertight misses "
                "%zu (rate %.2e); %zu left out (outside in long double)\n",
                mesh, s.triangle_count(), m.rays, m.moller, m.rate(m.moller), m.watertight, m.rate(m.watertight),
                m.outside);
    ::testing::Test::RecordProperty("rays", std::to_string(m.rays));
    ::testing::Test::RecordProperty("moller_misses", std::to_string(m.moller));
    ::testing::Test::RecordProperty("watertight_misses", std::to_string(m.watertight));
    EXPECT_LT(m.outside, m.rays / 100) << "too few rays left to test";
    EXPECT_EQ(m.watertight, 0u) << mesh << ": intersect_watertight let rays through";
    // As on the CPU: Moller-Trumbore lets some of these rays through, or they no longer exercise the shared edges.
    EXPECT_GT(m.moller, 0u) << mesh << ": the rays no longer exercise the shared edges";
}

TEST(GlslHardCases, WatertightRaysThroughSharedVerticesAndEdgesOfAClosedSphereNeverMiss) {
    expect_no_glsl_watertight_misses("UV sphere 48x24", closed_sphere(), kSphereRays);
}

TEST(GlslHardCases, WatertightRaysThroughSharedVerticesAndEdgesOfACubeSplitIntoTrianglesNeverMiss) {
    expect_no_glsl_watertight_misses("cube of 12 triangles", closed_cube(), kCubeRays);
}

// ---------------------------------------------------------------------------------------------------------------
// Self-intersection.

// Closest hit over every triangle of the bound scene with intersect_watertight, as the tracers do it (tmax shrinks).
const char* kClosestHit = R"(
#include "common/shaders/trace/shading.glsl"
#include "common/shaders/trace/intersect.glsl"
#include "common/shaders/trace/offset.glsl"
Hit closest(Ray r) {
    const WatertightRay w = watertight_ray(r.direction);
    Hit h = no_hit();
    for (uint i = 0u; i < rt_triangle_count; ++i) {
        vec3 a, b, c;
        load_triangle(i, a, b, c);
        float t, u, v;
        r.tmax = h.t;
        if (intersect_watertight(r, w, a, b, c, t, u, v)) {
            h.t = t; h.u = u; h.v = v; h.triangle = int(i);
        }
    }
    return h;
}
bool hits(Ray r) { return closest(r).triangle >= 0; }
Ray spawn(int method, SurfacePoint sp, vec3 direction) {
    return make_ray(offset_ray_origin(method, sp.position, sp.geometric_normal, direction, RT_DEFAULT_EPSILON),
                    direction, RT_INFINITY);
}
)";

// Per primary ray (origin, direction, a random unit vector, the sphere's radius): the primary's closest hit and
// surface_point, then for each offset method (0 epsilon, 1 robust), words 1 + 7m ..:
//   shadow hit, reflection hit, refracted in, refraction failed (no far side beyond radius / 4), refracted out,
//   leaving ray hit, (unused)
// The shadow ray leaves towards normalize(n + 0.9 r), a direction above the surface (dot with n > 0.43).
const std::string kSpawnBody = std::string(kClosestHit) + R"(
void test_main() {
    const Ray primary = make_ray(in_vec3(0), in_vec3(3), RT_INFINITY);
    const vec3 r = in_vec3(6);
    const float radius = in_f(9);
    for (uint k = 0u; k < 15u; ++k) out_u(k, 0u);
    const Hit hit = closest(primary);
    out_b(0, hit.triangle >= 0);
    if (hit.triangle < 0) return;
    const SurfacePoint sp = surface_point(primary, uint(hit.triangle), hit.u, hit.v);
    const vec3 n = sp.geometric_normal;
    precise vec3 shadow_dir = rt_normalize(n + 0.9 * r);
    const vec3 mirror_dir = rt_normalize(reflect_dir(primary.direction, n));
    vec3 inward;
    const bool enters = refract_dir(primary.direction, n, 1.0 / 1.5, inward);
    for (int m = 0; m < 2; ++m) {
        const uint k = 1u + 7u * uint(m);
        out_b(k, hits(spawn(m, sp, shadow_dir)));
        out_b(k + 1u, hits(spawn(m, sp, mirror_dir)));
        if (!enters) continue;
        out_b(k + 2u, true);
        const Ray inside = spawn(m, sp, inward);
        const Hit far_side = closest(inside);
        const bool reached = far_side.triangle >= 0 && far_side.t > radius / 4.0;
        out_b(k + 3u, !reached);
        if (!reached) continue;
        const SurfacePoint exit_point = surface_point(inside, uint(far_side.triangle), far_side.u, far_side.v);
        vec3 outward;
        if (!refract_dir(inside.direction, exit_point.geometric_normal, 1.5, outward)) continue;
        out_b(k + 4u, true);
        out_b(k + 5u, hits(spawn(m, exit_point, outward)));
    }
}
)";

// The CPU suite's primaries (spawn_from_sphere in 01_naive/offset_test.cpp): aimed at random interior points of random
// triangles of the sphere from outside. Returns the tallies of both offset methods (0 epsilon, 1 robust).
std::array<SpawnTallies, 2> glsl_spawn_from_sphere(GlslTestHarness& h, GpuScene& gpu, double offset, double scale,
                                                   int primaries, std::size_t& primary_misses) {
    const Scene s = sphere_at(offset, scale);
    gpu.upload(s);
    std::mt19937 rng(sphere_seed(offset, scale));
    Words in;
    for (int i = 0; i < primaries; ++i) {
        const Ray<float> primary = primary_ray_at_random_triangle<float>(s, scale, rng).ray;
        in << primary.origin << primary.direction << random_unit<float>(rng) << float(scale);
    }
    const std::vector<std::uint32_t> out = h.run(in.words, std::size_t(primaries), 10, 15, [&] { gpu.bind(); });
    std::array<SpawnTallies, 2> tallies;
    for (std::size_t i = 0; i < std::size_t(primaries); ++i) {
        const std::uint32_t* w = &out[15 * i];
        if (!w[0]) {
            ++primary_misses;
            continue;
        }
        for (int m = 0; m < 2; ++m) {
            const std::uint32_t* k = w + 1 + 7 * m;
            SpawnTallies& t = tallies[std::size_t(m)];
            t.shadow.add(k[0] != 0);
            t.reflection.add(k[1] != 0);
            if (k[2]) t.refraction_in.add(k[3] != 0);
            if (k[4]) t.refraction_out.add(k[5] != 0);
        }
    }
    return tallies;
}

TEST(GlslHardCases, SpawnedRaysNeverRehitTheirSurfaceAtAnyOffsetOrScale) {
    test_context();
    GlslTestHarness h("hard_cases_spawn", kSpawnBody);
    GpuScene gpu;
    const int primaries = 200;
    std::printf("[ glsl self-hits ] failure rate of spawned shadow/reflection/refraction rays off a sphere of radius "
                "SCALE at (OFFSET, OFFSET, OFFSET), GLSL float, offset_ray_origin; epsilon = %g; '-' = not "
                "representable in float\n  offset \\ scale", double(kDefaultEpsilon));
    for (double scale : kPlacementScales) std::printf("  %15.0e", scale);
    std::printf("\n");
    std::map<std::pair<double, double>, SpawnTallies> epsilon;
    std::size_t primary_misses = 0;
    for (double offset : kPlacementOffsets) {
        std::printf("  %-13.0e  ", offset);
        for (double scale : kPlacementScales) {
            if (!sphere_representable(offset, scale)) {
                std::printf("  %15s", "-");
                continue;
            }
            const auto [e, r] = glsl_spawn_from_sphere(h, gpu, offset, scale, primaries, primary_misses);
            epsilon[{offset, scale}] = e;
            EXPECT_EQ(r.failures(), 0u) << "robust, offset " << offset << ", scale " << scale << ": shadow "
                                        << r.shadow.failures << ", reflection " << r.reflection.failures
                                        << ", refraction in " << r.refraction_in.failures << ", out "
                                        << r.refraction_out.failures;
            EXPECT_GT(r.refraction_out.rays, 0u) << "offset " << offset << ", scale " << scale;
            char cell[32];
            std::snprintf(cell, sizeof cell, "eps %4.1f%% rob %zu", 100.0 * e.rate(), r.failures());
            std::printf("  %15s", cell);
        }
        std::printf("\n");
    }
    EXPECT_EQ(primary_misses, 0u) << "primaries aimed inside a triangle of a closed sphere missed it";
    // Where the fixed epsilon is known to fail: at 1e4 a float step is 2^-10 ~ 1e-3 > 1e-4 (acne).
    for (auto [offset, scale] : {std::pair{1e4, 1.0}, std::pair{1e6, 1e3}, std::pair{1e4, 1e3}}) {
        const SpawnTallies& e = epsilon.at({offset, scale});
        std::printf("[ glsl self-hits ] epsilon at offset %g, scale %g: shadow %zu, reflection %zu, refraction in %zu, "
                    "leaving %zu of %zu rays fail (%.1f%%)\n", offset, scale, e.shadow.failures, e.reflection.failures,
                    e.refraction_in.failures, e.refraction_out.failures, e.rays(), 100 * e.rate());
        EXPECT_GT(e.shadow.failures, 0u) << "offset " << offset << ", scale " << scale;
        EXPECT_GT(e.reflection.failures, 0u) << "offset " << offset << ", scale " << scale;
        EXPECT_GT(e.refraction_in.failures, 0u) << "offset " << offset << ", scale " << scale;
    }
    RecordProperty("epsilon_failures_at_1e4", std::to_string(epsilon.at({1e4, 1.0}).failures()));
    // Near the origin at a human scale the epsilon works.
    EXPECT_EQ(epsilon.at({1.0, 1.0}).failures(), 0u);
}

// Thin walls: per primary aimed at the top face of a slab (origin, direction), words: hit the top face, then for each
// offset method: refracted in, did not reach the bottom face (escaped or re-hit the top).
const std::string kThinWallBody = std::string(kClosestHit) + R"(
bool on_plane(int triangle, float y) {
    if (triangle < 0) return false;
    vec3 a, b, c;
    load_triangle(uint(triangle), a, b, c);
    return a.y == y && b.y == y && c.y == y;
}
void test_main() {
    const Ray primary = make_ray(in_vec3(0), in_vec3(3), RT_INFINITY);
    const float top = in_f(6), bottom = in_f(7);
    for (uint k = 0u; k < 5u; ++k) out_u(k, 0u);
    const Hit hit = closest(primary);
    if (!on_plane(hit.triangle, top)) return;
    out_b(0, true);
    const SurfacePoint sp = surface_point(primary, uint(hit.triangle), hit.u, hit.v);
    vec3 inward;
    if (!refract_dir(primary.direction, sp.geometric_normal, 1.0 / 1.5, inward)) return;
    for (int m = 0; m < 2; ++m) {
        out_b(1u + 2u * uint(m), true);
        out_b(2u + 2u * uint(m), !on_plane(closest(spawn(m, sp, inward)).triangle, bottom));
    }
}
)";

TEST(GlslHardCases, RaysIntoAThinWallAreStoppedByItsOtherFace) {
    test_context();
    GlslTestHarness h("hard_cases_thin_wall", kThinWallBody);
    GpuScene gpu;
    std::printf("[ glsl thin wall ] rays refracted into a slab 0.05*SCALE thick at OFFSET that escape through its far "
                "face, GLSL float; epsilon = %g; '-' = wall thinner than the robust offset\n  offset \\ scale",
                double(kDefaultEpsilon));
    for (double scale : kPlacementScales) std::printf("  %15.0e", scale);
    std::printf("\n");
    std::map<std::pair<double, double>, Tally> epsilon;
    for (double offset : kWallOffsets) {
        std::printf("  %-13.0e  ", offset);
        for (double scale : kPlacementScales) {
            if (!wall_representable(offset, scale)) {
                std::printf("  %15s", "-");
                continue;
            }
            const Scene s = thin_slab_at(offset, scale);
            gpu.upload(s);
            float bottom = std::numeric_limits<float>::infinity(), top = -bottom;
            for (const glm::vec3& p : s.positions) bottom = std::min(bottom, p.y), top = std::max(top, p.y);
            std::mt19937 rng(wall_seed(offset, scale));
            std::uniform_real_distribution<double> across(-0.4, 0.4);
            Words in;
            const int rays = 200;
            for (int i = 0; i < rays; ++i) {
                const glm::vec3 target(float(offset + scale * across(rng)), top, float(offset + scale * across(rng)));
                const glm::vec3 from = direction_outside<float>({glm::vec3(0, 1, 0)}, 0.3f, rng);
                const Ray<float> primary = ray_aimed_at(target, from, float(2 * scale));
                in << primary.origin << primary.direction << top << bottom;
            }
            const std::vector<std::uint32_t> out = h.run(in.words, rays, 8, 5, [&] { gpu.bind(); });
            Tally e, r;
            for (std::size_t i = 0; i < std::size_t(rays); ++i) {
                const std::uint32_t* w = &out[5 * i];
                if (!w[0]) continue;
                if (w[1]) e.add(w[2] != 0);
                if (w[3]) r.add(w[4] != 0);
            }
            epsilon[{offset, scale}] = e;
            EXPECT_GT(r.rays, 100u) << "offset " << offset << ", scale " << scale;
            EXPECT_EQ(r.failures, 0u) << "robust, offset " << offset << ", scale " << scale;
            char cell[32];
            std::snprintf(cell, sizeof cell, "eps %5.1f%% rob %zu", 100.0 * e.rate(), r.failures);
            std::printf("  %15s", cell);
        }
        std::printf("\n");
    }
    // 0.05 mm thick at 1 mm scale: thinner than the 0.1 mm epsilon, so every refracted ray starts past the wall.
    for (double offset : {0.0, 1.0}) {
        const Tally& e = epsilon.at({offset, 1e-3});
        EXPECT_EQ(e.failures, e.rays) << "offset " << offset;
        EXPECT_GT(e.rays, 100u);
    }
    EXPECT_EQ(epsilon.at({0.0, 1e-2}).failures, 0u) << "a wall twice as thick as epsilon stops it";
}

// ---------------------------------------------------------------------------------------------------------------
// Inputs.

TEST(GlslHardCases, DegenerateAndNonFiniteInputsNeverHitOrProduceNaN) {
    test_context();
    // Intersection: each record is a ray (origin, direction, tmax) and a triangle; both methods' answers.
    GlslTestHarness h("hard_cases_broken_intersect", R"(
#include "common/shaders/trace/intersect.glsl"
void test_main() {
    const Ray r = make_ray(in_vec3(0), in_vec3(3), in_f(6));
    float t, u, v;
    const bool m = intersect_moller(r, in_vec3(7), in_vec3(10), in_vec3(13), t, u, v);
    out_b(0, m); out_f(1, t); out_f(2, u); out_f(3, v);
    const bool w = intersect_watertight(r, watertight_ray(r.direction), in_vec3(7), in_vec3(10), in_vec3(13), t, u, v);
    out_b(4, w); out_f(5, w ? t : 0.0); out_f(6, w ? u : 0.0); out_f(7, w ? v : 0.0);
}
)");
    struct Case {
        std::string name;
        Ray<float> ray;
        glm::vec3 a, b, c;
        bool may_hit;   // a hit is allowed (then it must be finite, t > 0)
    };
    std::vector<Case> cases;
    const glm::vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);   // a valid triangle
    const Ray<float> good{{0.2f, 0.2f, 1}, {0, 0, -1}};
    const Ray<float> diagonal{{0.5f, 0.5f, 1}, {0, 0, -1}};   // aimed at the degenerate triangles' line
    for (const TriangleCase<float>& tri : broken_triangles<float>())
        for (const Ray<float>& ray : {good, diagonal})
            cases.push_back({tri.name, ray, tri.a, tri.b, tri.c, false});
    for (const auto& [name, ray] : broken_rays<float>()) cases.push_back({name, ray, a, b, c, false});
    // A NaN tmax: either answer is usable, as long as it is finite; a collinear triangle of distinct points has zero
    // area only up to rounding: a hit is allowed, but finite.
    cases.push_back({"NaN tmax", Ray<float>{{0.2f, 0.2f, 1}, {0, 0, -1}, std::nanf("")}, a, b, c, true});
    cases.push_back({"collinear", diagonal, {0, 0, 0}, {0.3f, 0.3f, 0}, {0.9f, 0.9f, 0}, true});
    cases.push_back({"valid (control)", good, a, b, c, true});
    Words in;
    for (const Case& k : cases) in << k.ray.origin << k.ray.direction << k.ray.tmax << k.a << k.b << k.c;
    const std::vector<std::uint32_t> out = h.run(in.words, cases.size(), 16, 8);
    for (std::size_t i = 0; i < cases.size(); ++i)
        for (int m = 0; m < 2; ++m) {
            const std::size_t k = 8 * i + 4 * std::size_t(m);
            const char* method = m == 0 ? "moller" : "watertight";
            const float t = word_f(out, k + 1), u = word_f(out, k + 2), v = word_f(out, k + 3);
            if (!cases[i].may_hit) {
                EXPECT_EQ(out[k], 0u) << method << ": " << cases[i].name << " gave t " << t;
            } else if (out[k]) {
                EXPECT_TRUE(finite(t) && finite(u) && finite(v) && t > 0.0f) << method << ": " << cases[i].name;
            }
        }
    EXPECT_EQ(out[8 * (cases.size() - 1)], 1u) << "the valid control triangle must be hit (moller)";
    EXPECT_EQ(out[8 * (cases.size() - 1) + 4], 1u) << "the valid control triangle must be hit (watertight)";

    // Shading at its edges: Fresnel (both), reflect/refract, and the Whitted weights at every cos_i and eta of
    // interest; surface coefficients, light incidence and shade_light for edge materials and lights.
    GlslTestHarness f("hard_cases_fresnel_edges", R"(
#include "common/shaders/trace/shading.glsl"
void test_main() {
    const float cos_i = in_f(0), eta = in_f(1);
    const vec3 d = in_vec3(2), n = in_vec3(5);
    out_f(0, fresnel_exact(cos_i, eta));
    out_f(1, fresnel_schlick(cos_i, eta));
    out_vec3(2, reflect_dir(d, n));
    vec3 t;
    out_b(5, refract_dir(d, n, eta, t));
    out_vec3(6, t);
}
)");
    struct FresnelCase {
        float cos_i, eta;
    };
    std::vector<FresnelCase> fc;
    const float etas[] = {1.0f, 1.5f, 1.0f / 1.5f, 2.4f, 1.0f / 2.4f, 1.0001f, 0.9999f};
    const float cosines[] = {0.0f, 1e-7f, 1e-3f, 0.3f, std::cos(std::asin(1.0f / 1.5f)), 0.5f, 0.9999999f, 1.0f};
    for (float eta : etas)
        for (float cos_i : cosines) fc.push_back({cos_i, eta});
    Words fin;
    for (const FresnelCase& k : fc) {
        const glm::vec3 n(0, 1, 0);
        const float sin_i = std::sqrt(std::max(0.0f, 1 - k.cos_i * k.cos_i));
        fin << k.cos_i << k.eta << glm::vec3(sin_i, -k.cos_i, 0) << n;
    }
    const std::vector<std::uint32_t> fo = f.run(fin.words, fc.size(), 8, 9);
    std::size_t tir = 0;
    for (std::size_t i = 0; i < fc.size(); ++i) {
        float w[9];
        for (std::size_t k = 0; k < 9; ++k) w[k] = word_f(fo, 9 * i + k);
        const std::string at = "cos_i " + std::to_string(fc[i].cos_i) + ", eta " + std::to_string(fc[i].eta);
        for (int k : {0, 1}) EXPECT_TRUE(finite(w[k]) && w[k] >= 0.0f && w[k] <= 1.0f) << at << ": F = " << w[k];
        for (int k : {2, 3, 4}) EXPECT_TRUE(finite(w[k])) << at << ": reflect";
        const bool refracted = fo[9 * i + 5] != 0;
        for (int k : {6, 7, 8}) EXPECT_TRUE(finite(w[k])) << at << ": refract";
        if (refracted) {
            const glm::vec3 t(w[6], w[7], w[8]);
            EXPECT_NEAR(glm::length(t), 1.0f, 1e-6f) << at;
            EXPECT_LE(t.y, 0.0f) << at << ": the refracted ray goes through the surface";
        } else {
            ++tir;
            // Only leaving a denser medium, or with eta = 1 so close to grazing that 1 - cos_i^2 rounds to 1.
            EXPECT_TRUE(fc[i].eta > 1.0f || (fc[i].eta == 1.0f && fc[i].cos_i < 1e-3f))
                << at << ": total internal reflection";
            EXPECT_EQ(w[0], 1.0f) << at << ": exact Fresnel under total internal reflection";
            if (fc[i].eta > 1.0f) {
                EXPECT_EQ(w[1], 1.0f) << at << ": Schlick under total internal reflection";
            }
        }
        if (fc[i].eta == 1.0f && fc[i].cos_i >= 0.01f) {   // as shading_test.cpp; nearer grazing F grows
            EXPECT_NEAR(w[0], 0.0f, 1e-6f) << at << ": eta = 1 reflects nothing";
            EXPECT_NEAR(w[1], 0.0f, 1e-6f) << at << ": eta = 1 reflects nothing";
            EXPECT_NEAR(w[6], fc[i].cos_i < 1.0f ? std::sqrt(1 - fc[i].cos_i * fc[i].cos_i) : 0.0f, 1e-6f) << at;
        }
        if (fc[i].cos_i == 1.0f && (fc[i].eta == 1.5f || fc[i].eta == 1.0f / 1.5f)) {
            EXPECT_NEAR(w[0], 0.04f, 1e-6f) << at << ": normal incidence on glass";
            if (fc[i].eta < 1.0f) { EXPECT_NEAR(w[1], 0.04f, 1e-6f) << at; }
        }
        if (fc[i].cos_i == 0.0f && fc[i].eta < 1.0f) {
            EXPECT_NEAR(w[0], 1.0f, 1e-6f) << at << ": grazing incidence reflects everything";
            EXPECT_NEAR(w[1], 1.0f, 1e-6f) << at << ": grazing incidence reflects everything";
        }
    }
    EXPECT_GT(tir, 5u) << "total internal reflection was exercised";

    GlslTestHarness sh("hard_cases_shading_edges", R"(
#include "common/shaders/testing/test_inputs.glsl"
void test_main() {
    const SurfaceCoefficients s = surface_coefficients(in_material(0u), vec4(1.0));
    out_vec3(0, s.diffuse); out_vec3(3, s.specular); out_f(6, s.shininess); out_vec3(7, s.mirror);
    out_f(10, s.smoothness); out_f(11, s.dielectric); out_f(12, s.transmission); out_f(13, s.ior);
    const vec3 p = in_vec3(32), n = in_vec3(35), to_eye = in_vec3(38);
    vec3 to_light;
    float distance;
    const vec3 inc = light_incidence(in_light(16u), p, n, to_light, distance);
    out_vec3(14, inc); out_vec3(17, to_light);
    out_vec3(20, inc != vec3(0.0) ? shade_light(s, inc, n, to_light, to_eye) : vec3(0.0));
    const float cos_i = in_f(41);
    const ReflectRefract k = reflect_refract_coefficients(s, in_u(42) != 0u, cos_i, fresnel_exact(cos_i, in_f(43)));
    out_vec3(23, k.reflection); out_vec3(26, k.refraction);
}
)");
    std::vector<Material> materials;
    for (float metallic : {-0.2f, 0.0f, 1.0f, 1.2f})
        for (float roughness : {-0.1f, 0.0f, 1.0f, 1.1f})
            for (float ior : {0.0f, 1.0f, 1.5f}) {
                Material m;
                m.base_color = glm::vec4(0.8f, 0.5f, 0.2f, 1.0f);
                m.metallic = metallic;
                m.roughness = roughness;
                m.ior = ior;
                m.transmission = ior == 1.5f ? 1.0f : 0.0f;
                materials.push_back(m);
            }
    const glm::vec3 p(0.5f, 0.25f, 0.0f), n(0, 0, 1);
    std::vector<Light> lights;
    {
        Light l;   // a point light exactly at the shaded point: d2 = 0
        l.type = LightType::Point;
        l.position = p;
        lights.push_back(l);
        l.position = p + glm::vec3(0, 0, 2);   // straight above, eye along the mirror direction (n . h = 1)
        lights.push_back(l);
        l.position = p + glm::vec3(2, 0, 1e-7f);   // grazing
        lights.push_back(l);
        l.position = p + glm::vec3(0, 0, -2);   // behind the surface
        lights.push_back(l);
        l.position = p + glm::vec3(0, 0, 2);
        l.range = 1.0f;   // beyond its range
        lights.push_back(l);
        l.range = 2.0f;   // exactly at its range
        lights.push_back(l);
        l.range = 0.0f;
        l.type = LightType::Spot;   // equal cones (the 1e-4 floor), pointed at p and away
        l.direction = glm::vec3(0, 0, -1);
        l.inner_cone = l.outer_cone = 0.3f;
        lights.push_back(l);
        l.direction = glm::vec3(0, 0, 1);
        lights.push_back(l);
        l.type = LightType::Directional;   // normal and grazing
        l.direction = glm::vec3(0, 0, -1);
        lights.push_back(l);
        l.direction = glm::vec3(1, 0, -1e-7f);
        lights.push_back(l);
    }
    // Eyes on the normal's side (Whitted turns normals to the ray's side), grazing ones included, and one below the
    // surface, exactly opposite the directional light at normal incidence: there the half vector is zero.
    const glm::vec3 eyes[] = {{0, 0, 1}, glm::normalize(glm::vec3(1, 0, 1)), {1, 0, 0}, {-1, 0, 0}, {0, 0, -1}};
    Words sw;
    std::size_t count = 0;
    for (const Material& m : materials)
        for (const Light& l : lights)
            for (const glm::vec3& eye : eyes) {
                const GpuMaterial gm = to_gpu(m);
                const GpuLight gl = to_gpu(l);
                sw << gm.base_color << gm.emissive << gm.base_color_texture << gm.specular_color << gm.metallic
                    << gm.roughness << gm.transmission << gm.ior << gm.specular;
                sw << gl.color << gl.type << gl.position << gl.intensity << gl.direction << gl.range
                    << gl.inner_cone << gl.outer_cone << gl.cos_inner << gl.cos_outer;
                const float cos_i = float(count % 3) * 0.5f;   // grazing, 60 degrees, normal
                sw << p << n << eye << cos_i << std::uint32_t(count % 2) << (count % 4 < 2 ? 1.5f : 1.0f);
                ++count;
            }
    const std::vector<std::uint32_t> so = sh.run(sw.words, count, 44, 29);
    std::size_t non_finite = 0, lit = 0;
    for (std::size_t i = 0; i < count; ++i) {
        for (std::size_t k = 0; k < 29; ++k)
            if (!finite(word_f(so, 29 * i + k))) {
                ++non_finite;
                ADD_FAILURE() << "record " << i << " word " << k << " = " << word_f(so, 29 * i + k);
                break;
            }
        lit += word_f(so, 29 * i + 14) > 0.0f;
    }
    EXPECT_EQ(non_finite, 0u);
    EXPECT_GT(lit, count / 4) << "the lit cases were exercised";
    std::printf("[ glsl inputs ] %zu broken ray/triangle pairs, %zu Fresnel/refraction edge cases (%zu total internal "
                "reflection), %zu material/light/eye edge combinations (%zu lit): no hit, no NaN or Inf\n",
                cases.size(), fc.size(), tir, count, lit);
}

}  // namespace
}  // namespace rt::gpu
