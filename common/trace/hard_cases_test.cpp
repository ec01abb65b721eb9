// The hard cases of the shared CPU routines: each case is a test named after it.
//
//   Watertight        rays aimed exactly at shared vertices and edges of closed meshes never slip through.
//   SelfIntersection  spawned shadow, reflection and refraction rays never re-hit the surface they leave, at
//                     coordinates from 1e-4 to 1e6 and scales from 1e-3 to 1e3; where a fixed epsilon fails.
//   Refraction, ShadingNormals   what shading_test.cpp does not cover: a whole solid, normals facing away.
//   Inputs            degenerate triangles, NaN/Inf vertices, NaN/zero ray directions: no crash, no hang, no NaN.
//   FarScene          builtin:far (the Whitted scene moved by 1e4) renders like builtin:whitted.
//
// The tests print the rates they measure (run build/tests/unit_tests_common_trace --gtest_filter='Watertight*:SelfIntersection*'
// to see them). The GLSL twins of these routines get the same cases in their own harness.
//
// Every render a test makes is checked for NaN/Inf pixels here; the golden-image tests do the same for every stage
// render: tests/run_golden.cmake renders an EXR and tests/image_compare fails on any non-finite pixel.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "01_naive/brute_force_tracer.h"
#include "common/app/image.h"
#include "common/scene/builtin_scenes.h"
#include "common/scene/effects.h"
#include "common/scene/gltf_io.h"
#include "common/scene/scene.h"
#include "hard_cases.h"
#include "intersect.h"
#include "offset.h"
#include "shading.h"
#include "whitted.h"

namespace rt {
namespace {

using namespace hard_cases;   // the meshes, rays and placements shared with the GLSL suite

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr IntersectMethod kMethods[] = {IntersectMethod::Moller, IntersectMethod::Watertight};
constexpr OffsetMethod kOffsets[] = {OffsetMethod::Epsilon, OffsetMethod::Robust};

const char* name_of(IntersectMethod m) { return m == IntersectMethod::Moller ? "moller" : "watertight"; }
const char* name_of(OffsetMethod m) { return m == OffsetMethod::Epsilon ? "epsilon" : "robust"; }
template <class T> const char* precision_name() { return sizeof(T) == sizeof(float) ? "float" : "double"; }

// ---------------------------------------------------------------------------------------------------------------
// Watertightness.

struct MissCount {
    std::size_t rays = 0;
    std::size_t outside = 0;          // rays left out: they pass outside the mesh in (near) exact arithmetic
    std::size_t misses[2] = {0, 0};   // by IntersectMethod, of the rays that do hit
    double rate(IntersectMethod m) const { return rays ? double(misses[int(m)]) / double(rays) : 0.0; }
};

// Counts the misses of both methods. Rounding the origin of a ray that starts 10^4 mesh sizes away turns its aim by
// up to an ulp of its direction, so a ray aimed at a point next to a corner may really pass outside the mesh: each
// miss is checked again with the same ray converted exactly to long double (64-bit mantissa, watertight method), and
// a ray that misses there too is left out, for both methods.
template <class T> MissCount count_misses(const Scene& s, const std::vector<Ray<T>>& rays) {
    using Exact = long double;
    const BruteForceTracer<Exact> oracle(s, IntersectMethod::Watertight);
    const BruteForceTracer<T> moller(s, IntersectMethod::Moller), watertight(s, IntersectMethod::Watertight);
    RayCounters counters;
    MissCount count;
    for (const Ray<T>& ray : rays) {
        Hit<T> hm, hw;
        const bool moller_missed = !moller.closest(ray, hm, counters);
        const bool watertight_missed = !watertight.closest(ray, hw, counters);
        if (moller_missed || watertight_missed) {
            Hit<Exact> exact;
            if (!oracle.closest(Ray<Exact>{Vec3<Exact>(ray.origin), Vec3<Exact>(ray.direction)}, exact, counters)) {
                ++count.outside;
                continue;
            }
        }
        ++count.rays;
        count.misses[int(IntersectMethod::Moller)] += moller_missed ? 1 : 0;
        count.misses[int(IntersectMethod::Watertight)] += watertight_missed ? 1 : 0;
    }
    return count;
}

// Runs the shared-vertex/edge rays in float and double; watertight must never miss, Moller's misses are reported.
// Returns Moller's misses in float (the precision the renders use).
std::size_t expect_no_watertight_misses(const char* mesh, const Scene& s, const WatertightRayCounts& counts) {
    const auto [directions_per_vertex, points_per_edge, directions_per_point] = counts;
    const MeshTopology topo = topology_of(s);
    EXPECT_TRUE(topo.closed()) << mesh << " is not closed: the case needs every edge shared by exactly two triangles";
    const MissCount f = count_misses(s, rays_at_shared_vertices_and_edges<float>(
                                            s, directions_per_vertex, points_per_edge, directions_per_point,
                                            kWatertightSeed));
    const MissCount d = count_misses(s, rays_at_shared_vertices_and_edges<double>(
                                            s, directions_per_vertex, points_per_edge, directions_per_point,
                                            kWatertightSeed));
    std::printf("[ watertight ] %s (%zu triangles, %zu shared vertices, %zu shared edges), rays aimed exactly at "
                "them:\n"
                "               float:  %zu rays, Moller misses %zu (rate %.2e), watertight misses %zu (rate %.2e)\n"
                "               double: %zu rays, Moller misses %zu (rate %.2e), watertight misses %zu (rate %.2e)\n"
                "               (left out: %zu float and %zu double rays that pass outside the mesh in long double;\n"
                "                Embree's verify test tolerates a miss rate of 2e-5; watertight must give 0)\n",
                mesh, s.triangle_count(), topo.vertices.size(), topo.edges.size(), f.rays,
                f.misses[0], f.rate(IntersectMethod::Moller), f.misses[1], f.rate(IntersectMethod::Watertight), d.rays,
                d.misses[0], d.rate(IntersectMethod::Moller), d.misses[1], d.rate(IntersectMethod::Watertight),
                f.outside, d.outside);
    EXPECT_LT(f.outside + d.outside, (f.rays + d.rays) / 100) << "too few rays left to test";
    ::testing::Test::RecordProperty("rays_float", std::to_string(f.rays));
    ::testing::Test::RecordProperty("moller_misses_float", std::to_string(f.misses[0]));
    ::testing::Test::RecordProperty("watertight_misses_float", std::to_string(f.misses[1]));
    ::testing::Test::RecordProperty("moller_misses_double", std::to_string(d.misses[0]));
    ::testing::Test::RecordProperty("watertight_misses_double", std::to_string(d.misses[1]));
    EXPECT_EQ(f.misses[int(IntersectMethod::Watertight)], 0u) << mesh << ", float";
    EXPECT_EQ(d.misses[int(IntersectMethod::Watertight)], 0u) << mesh << ", double";
    return f.misses[int(IntersectMethod::Moller)];
}

TEST(Watertight, RaysThroughSharedVerticesAndEdgesOfAClosedSphereNeverMiss) {
    const std::size_t moller_misses = expect_no_watertight_misses("UV sphere 48x24", closed_sphere(), kSphereRays);
    // The rays are hard: Moller-Trumbore, whose edge tests round differently in the two triangles of an edge, lets
    // some of them through (the count is deterministic for this seed; it only has to be non-zero).
    EXPECT_GT(moller_misses, 0u) << "the rays no longer exercise the shared edges";
}

TEST(Watertight, RaysThroughSharedVerticesAndEdgesOfACubeSplitIntoTrianglesNeverMiss) {
    const std::size_t moller_misses = expect_no_watertight_misses("cube of 12 triangles", closed_cube(), kCubeRays);
    EXPECT_GT(moller_misses, 0u) << "the rays no longer exercise the shared edges";
}

// Away from edges the two tests are the same mathematics: same triangle, same t, u, v to rounding.
template <class T> void expect_methods_agree_on_ordinary_rays(const Scene& s, int rays, unsigned seed) {
    std::mt19937 rng(seed);
    const BruteForceTracer<T> moller(s, IntersectMethod::Moller), watertight(s, IntersectMethod::Watertight);
    const double tol = sizeof(T) == sizeof(float) ? 1e-5 : 1e-12;   // relative, a few hundred ulps of the precision
    RayCounters counters;
    for (int i = 0; i < rays; ++i) {
        const auto [ray, t, b] = primary_ray_at_random_triangle<T>(s, 1.0, rng);
        Hit<T> hm, hw;
        ASSERT_TRUE(moller.closest(ray, hm, counters)) << precision_name<T>() << " ray " << i;
        ASSERT_TRUE(watertight.closest(ray, hw, counters)) << precision_name<T>() << " ray " << i;
        ASSERT_EQ(hm.triangle, std::int32_t(t));
        ASSERT_EQ(hw.triangle, std::int32_t(t));
        EXPECT_NEAR(double(hm.t), double(hw.t), tol * double(hw.t));
        EXPECT_NEAR(double(hm.u), b.y, 100 * tol);
        EXPECT_NEAR(double(hw.u), b.y, 100 * tol);
        EXPECT_NEAR(double(hm.v), b.z, 100 * tol);
        EXPECT_NEAR(double(hw.v), b.z, 100 * tol);
    }
}

TEST(Watertight, AgreesWithMollerOnOrdinaryRays) {
    const Scene sphere = closed_sphere();
    expect_methods_agree_on_ordinary_rays<float>(sphere, 2000, 11);
    expect_methods_agree_on_ordinary_rays<double>(sphere, 2000, 12);
}

// ---------------------------------------------------------------------------------------------------------------
// Self-intersection.

// A glass-like sphere of radius `scale` centred at (offset, offset, offset). Rays from outside hit it; from each hit
// point the rays Whitted spawns leave with the origin offset_ray_origin() gives them (as Whitted's spawn_origin):
//   shadow      towards a random direction above the surface   must hit nothing (the sphere is convex)
//   reflection  mirror direction                                must hit nothing
//   refraction  into the sphere                                 must reach the far side (t > scale / 4), not its
//               own surface again nor escape
//   leaving     refracted out again at the far side             must hit nothing
template <class T>
SpawnTallies spawn_from_sphere(OffsetMethod method, double offset, double scale, int primaries, unsigned seed) {
    const Scene s = sphere_at(offset, scale);
    const BruteForceTracer<T> tracer(s, IntersectMethod::Watertight);
    std::mt19937 rng(seed);
    const T eps = T(kDefaultEpsilon), eta = T(1.5);
    RayCounters counters;
    SpawnTallies tally;
    auto spawn = [&](const SurfacePoint<T>& sp, const Vec3<T>& direction) {
        Ray<T> r;
        r.direction = direction;
        r.origin = offset_ray_origin(method, sp.position, sp.geometric_normal, direction, eps);
        return r;
    };
    for (int i = 0; i < primaries; ++i) {
        const Ray<T> primary = primary_ray_at_random_triangle<T>(s, scale, rng).ray;
        Hit<T> hit;
        if (!tracer.closest(primary, hit, counters)) continue;   // cannot happen (watertight); nothing to spawn
        const SurfacePoint<T> sp = surface_point(s, primary, hit);

        Hit<T> h;
        const Ray<T> shadow = spawn(sp, direction_outside<T>({sp.geometric_normal}, T(0.1), rng));
        tally.shadow.add(tracer.closest(shadow, h = {}, counters));
        const Ray<T> mirror = spawn(sp, glm::normalize(reflect_dir(primary.direction, sp.geometric_normal)));
        tally.reflection.add(tracer.closest(mirror, h = {}, counters));

        Vec3<T> inward;
        if (!refract_dir(primary.direction, sp.geometric_normal, T(1) / eta, inward)) continue;
        const Ray<T> inside = spawn(sp, inward);
        Hit<T> far_side;
        const bool reached = tracer.closest(inside, far_side, counters) && far_side.t > T(scale / 4);
        tally.refraction_in.add(!reached);
        if (!reached) continue;
        const SurfacePoint<T> exit = surface_point(s, inside, far_side);
        Vec3<T> outward;
        if (!refract_dir(inside.direction, exit.geometric_normal, eta, outward)) continue;   // internal reflection
        tally.refraction_out.add(tracer.closest(spawn(exit, outward), h = {}, counters));
    }
    return tally;
}

TEST(SelfIntersection, SpawnedRaysNeverRehitTheirSurfaceAtAnyOffsetOrScale) {
    const auto& offsets = kPlacementOffsets;
    const auto& scales = kPlacementScales;
    const int primaries = 300;
    std::printf("[ self-hits ] failure rate of spawned shadow/reflection/refraction rays off a sphere of radius SCALE "
                "at (OFFSET, OFFSET, OFFSET), float; epsilon = %g; '-' = not representable in float\n"
                "  offset \\ scale", double(kDefaultEpsilon));
    for (double scale : scales) std::printf("  %15.0e", scale);
    std::printf("\n");
    std::map<std::pair<double, double>, SpawnTallies> epsilon_float;
    for (double offset : offsets) {
        std::printf("  %-13.0e  ", offset);
        for (double scale : scales) {
            if (!sphere_representable(offset, scale)) {
                std::printf("  %15s", "-");
                continue;
            }
            const unsigned seed = sphere_seed(offset, scale);
            for (OffsetMethod method : kOffsets) {
                const SpawnTallies f = spawn_from_sphere<float>(method, offset, scale, primaries, seed);
                const SpawnTallies d = spawn_from_sphere<double>(method, offset, scale, primaries, seed);
                if (method == OffsetMethod::Epsilon) epsilon_float[{offset, scale}] = f;
                if (method == OffsetMethod::Robust) {
                    EXPECT_EQ(f.failures(), 0u) << "robust, float, offset " << offset << ", scale " << scale
                                                << ": shadow " << f.shadow.failures << ", reflection "
                                                << f.reflection.failures << ", refraction in "
                                                << f.refraction_in.failures << ", out " << f.refraction_out.failures;
                    EXPECT_EQ(d.failures(), 0u) << "robust, double, offset " << offset << ", scale " << scale;
                    EXPECT_GT(f.refraction_out.rays, 0u);
                }
            }
            const SpawnTallies& e = epsilon_float[{offset, scale}];
            char cell[32];
            std::snprintf(cell, sizeof cell, "eps %4.1f%% rob 0", 100.0 * e.rate());
            std::printf("  %15s", cell);
        }
        std::printf("\n");
    }
    // Where the fixed epsilon is known to fail: at 1e4 a float step is 2^-10 ~ 1e-3 > 1e-4, so p + eps n rounds back
    // to p and about half the spawned rays start under the surface (acne), for every kind of ray.
    for (auto [offset, scale] : {std::pair{1e4, 1.0}, std::pair{1e6, 1e3}, std::pair{1e4, 1e3}}) {
        const SpawnTallies& e = epsilon_float.at({offset, scale});
        std::printf("[ self-hits ] epsilon at offset %g, scale %g: shadow %.1f%%, reflection %.1f%%, refraction in "
                    "%.1f%%, leaving %.1f%% of %zu rays fail\n", offset, scale, 100 * e.shadow.rate(),
                    100 * e.reflection.rate(), 100 * e.refraction_in.rate(), 100 * e.refraction_out.rate(), e.rays());
        EXPECT_GT(e.shadow.failures, 0u) << "offset " << offset << ", scale " << scale;
        EXPECT_GT(e.reflection.failures, 0u) << "offset " << offset << ", scale " << scale;
        EXPECT_GT(e.refraction_in.failures, 0u) << "offset " << offset << ", scale " << scale;
    }
    RecordProperty("epsilon_failure_rate_at_1e4", std::to_string(epsilon_float.at({1e4, 1.0}).rate()));
    // Near the origin at a human scale a fixed epsilon is fine: that is why it is taught.
    EXPECT_EQ(epsilon_float.at({1.0, 1.0}).failures(), 0u);
}

// A thin slab (a closed box 0.05 * scale thick) at (offset, offset, offset). Rays from above hit its top face; the
// ray refracted into it must be stopped by the bottom face. A fixed epsilon larger than the thickness starts that ray
// below the bottom face: it escapes, and light leaks through the wall. Counts the rays that are not.
template <class T>
Tally leaks_through_thin_wall(OffsetMethod method, double offset, double scale, int rays, unsigned seed) {
    const Scene s = thin_slab_at(offset, scale);
    float bottom = kInf, top = -kInf;
    for (const glm::vec3& p : s.positions) bottom = std::min(bottom, p.y), top = std::max(top, p.y);
    auto on_plane = [&](std::int32_t triangle, float y) {
        for (int k = 0; k < 3; ++k)
            if (s.positions[3 * std::size_t(triangle) + std::size_t(k)].y != y) return false;
        return true;
    };
    const BruteForceTracer<T> tracer(s, IntersectMethod::Watertight);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> across(-0.4, 0.4);
    RayCounters counters;
    Tally tally;
    for (int i = 0; i < rays; ++i) {
        const Vec3<T> target(T(offset + scale * across(rng)), T(top), T(offset + scale * across(rng)));
        const Vec3<T> from = direction_outside<T>({Vec3<T>(0, 1, 0)}, T(0.3), rng);
        const Ray<T> primary = ray_aimed_at(target, from, T(2 * scale));
        Hit<T> hit;
        if (!tracer.closest(primary, hit, counters) || !on_plane(hit.triangle, top)) continue;
        const SurfacePoint<T> sp = surface_point(s, primary, hit);
        Vec3<T> inward;
        if (!refract_dir(primary.direction, sp.geometric_normal, T(1) / T(1.5), inward)) continue;
        Ray<T> through;
        through.direction = inward;
        through.origin = offset_ray_origin(method, sp.position, sp.geometric_normal, inward, T(kDefaultEpsilon));
        Hit<T> other_side;
        tally.add(!(tracer.closest(through, other_side, counters) && on_plane(other_side.triangle, bottom)));
    }
    return tally;
}

TEST(SelfIntersection, RaysIntoAThinWallAreStoppedByItsOtherFace) {
    const auto& offsets = kWallOffsets;
    const auto& scales = kPlacementScales;
    std::printf("[ thin wall ] rays refracted into a slab 0.05*SCALE thick at OFFSET that escape through its far face, "
                "float; epsilon = %g; '-' = wall thinner than the robust offset: no float offset helps\n"
                "  offset \\ scale", double(kDefaultEpsilon));
    for (double scale : scales) std::printf("  %15.0e", scale);
    std::printf("\n");
    std::map<std::pair<double, double>, Tally> epsilon_leaks;
    for (double offset : offsets) {
        std::printf("  %-13.0e  ", offset);
        for (double scale : scales) {
            if (!wall_representable(offset, scale)) {
                std::printf("  %15s", "-");
                continue;
            }
            const unsigned seed = wall_seed(offset, scale);
            const Tally e = leaks_through_thin_wall<float>(OffsetMethod::Epsilon, offset, scale, 200, seed);
            const Tally r = leaks_through_thin_wall<float>(OffsetMethod::Robust, offset, scale, 200, seed);
            const Tally rd = leaks_through_thin_wall<double>(OffsetMethod::Robust, offset, scale, 200, seed);
            epsilon_leaks[{offset, scale}] = e;
            EXPECT_GT(r.rays, 100u);
            EXPECT_EQ(r.failures, 0u) << "robust, float, offset " << offset << ", scale " << scale;
            EXPECT_EQ(rd.failures, 0u) << "robust, double, offset " << offset << ", scale " << scale;
            char cell[32];
            std::snprintf(cell, sizeof cell, "eps %5.1f%% rob 0", 100.0 * e.rate());
            std::printf("  %15s", cell);
        }
        std::printf("\n");
    }
    // 0.05 mm thick at 1 mm scale: thinner than the 0.1 mm epsilon, so every refracted ray starts past the wall.
    for (double offset : {0.0, 1.0}) {
        const Tally& e = epsilon_leaks.at({offset, 1e-3});
        EXPECT_EQ(e.failures, e.rays) << "offset " << offset;
        EXPECT_GT(e.rays, 100u);
    }
    // A wall twice as thick as epsilon stops it.
    EXPECT_EQ(epsilon_leaks.at({0.0, 1e-2}).failures, 0u);
    RecordProperty("epsilon_leak_rate_at_scale_1e-3", std::to_string(epsilon_leaks.at({0.0, 1e-3}).rate()));
}

// ---------------------------------------------------------------------------------------------------------------
// Shading: refraction through a whole solid, shading normals facing away.

// A ray at height h above the axis of a unit glass sphere, refracted in and out with refract_dir. Snell at both
// interfaces and the symmetry of the sphere say: inside, sin(theta_t) = h / 1.5; it leaves at the angle it came in
// (sin = h to the exit normal), in the same plane, deviated by 2 (theta_i - theta_t).
TEST(Refraction, ARayThroughAGlassSphereLeavesAtTheAngleItEntered) {
    const double eta = 1.5;
    for (double h : {0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99}) {
        const glm::vec3 d(1, 0, 0);
        const glm::vec3 entry(float(-std::sqrt(1 - h * h)), float(h), 0);   // on the unit sphere; normal = position
        glm::vec3 inside;
        ASSERT_TRUE(refract_dir(d, entry, float(1 / eta), inside)) << h;
        const double sin_t = h / eta;
        EXPECT_NEAR(glm::length(glm::cross(inside, -entry)), sin_t, 1e-6) << h;
        // Second intersection with the sphere: |entry + s inside| = 1.
        const glm::vec3 exit = entry - 2.0f * glm::dot(entry, inside) * inside;
        glm::vec3 out;
        ASSERT_TRUE(refract_dir(inside, -exit, float(eta), out)) << "no total internal reflection in a sphere: " << h;
        EXPECT_GT(glm::dot(out, exit), 0.0f) << h;
        EXPECT_NEAR(glm::length(glm::cross(out, exit)), h, 2e-6) << h;
        EXPECT_EQ(out.z, 0.0f) << h;
        const double deviation = std::atan2(double(glm::length(glm::cross(d, out))), double(glm::dot(d, out)));
        EXPECT_NEAR(deviation, 2 * (std::asin(h) - std::asin(sin_t)), 1e-5) << h;
    }
}

// The same through a tessellated sphere with the tracer, surface_point and Whitted's choice of eta: entering, the hit
// is a front face (eta = 1/ior); leaving, a back face (eta = ior). Interpolated normals on a 96 x 48 sphere differ
// from the smooth sphere's by less than the facet angle (2 pi / 96 = 0.065 rad) squared, and the ray's path by
// about as much.
TEST(Refraction, ARayThroughATessellatedGlassSphereLeavesLikeTheSmoothOne) {
    const Scene s = flatten_without_light(asset_of({make_uv_sphere({0, 0, 0}, 1.0f, 96, 48, 0)}));
    const BruteForceTracer<float> tracer(s, IntersectMethod::Watertight);
    RayCounters counters;
    const float ior = 1.5f;
    for (float h : {0.05f, 0.3f, 0.6f, 0.85f}) {
        Ray<float> ray;
        ray.origin = glm::vec3(0.13f, h, 3.0f);   // off the seam and the pole, towards -z
        ray.direction = glm::vec3(0, 0, -1);
        const float r = std::sqrt(h * h + 0.13f * 0.13f);   // distance from the sphere's axis along the ray
        Hit<float> entry_hit, exit_hit;
        ASSERT_TRUE(tracer.closest(ray, entry_hit, counters));
        const SurfacePoint<float> entry = surface_point(s, ray, entry_hit);
        EXPECT_TRUE(entry.front_face);
        Ray<float> inside;
        const float eta_in = entry.front_face ? 1 / ior : ior;   // as Whitted chooses it
        ASSERT_TRUE(refract_dir(ray.direction, entry.shading_normal, eta_in, inside.direction));
        inside.origin =
            offset_ray_origin(OffsetMethod::Robust, entry.position, entry.geometric_normal, inside.direction);
        ASSERT_TRUE(tracer.closest(inside, exit_hit, counters));
        const SurfacePoint<float> exit = surface_point(s, inside, exit_hit);
        EXPECT_FALSE(exit.front_face) << "leaving the solid, the hit must be a back face";
        EXPECT_LT(glm::dot(exit.shading_normal, glm::normalize(exit.position)), 0.0f) << "normal must face the ray";
        glm::vec3 out;
        ASSERT_TRUE(refract_dir(inside.direction, exit.shading_normal, exit.front_face ? 1 / ior : ior, out));
        // Smooth sphere: the ray leaves at the angle it came in (sin = r to the normal) and is deviated by
        // 2 (theta_i - theta_t) towards the axis, in the plane of the ray and the centre.
        const float deviation = std::acos(std::clamp(glm::dot(out, ray.direction), -1.0f, 1.0f));
        const float expected = 2.0f * (std::asin(r) - std::asin(r / ior));
        EXPECT_NEAR(deviation, expected, 0.0065f) << "h = " << h;   // a tenth of the facet angle
        EXPECT_NEAR(glm::length(glm::cross(out, glm::normalize(exit.position))), r, 0.0065f) << "h = " << h;
    }
}

// One triangle in the z = 0 plane facing +z, lit from +z, with the given vertex normals.
Scene lit_triangle(const glm::vec3& vertex_normal) {
    Scene s;
    s.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    s.normals = {vertex_normal, vertex_normal, vertex_normal};
    s.uvs = {{0, 0}, {1, 0}, {0, 1}};
    s.material_ids = {0};
    Material white;
    white.metallic = 0.0f;
    s.materials = {white};
    Light light;
    light.position = {0, 0, 2};
    light.intensity = 8.0f;
    s.lights = {light};
    return s;
}

TEST(ShadingNormals, NormalsFacingAwayFromTheRayAreTurnedTowardsIt) {
    // Vertex normals pointing to -z, the back of a triangle seen from +z (as happens near silhouettes of meshes with
    // interpolated normals, or with normals flipped in the file).
    const Scene s = lit_triangle({0, 0, -1});
    const BruteForceTracer<float> tracer(s, IntersectMethod::Watertight);
    RayCounters counters;
    for (float side : {1.0f, -1.0f}) {
        const Ray<float> ray{{0.1f, 0.0f, 2.0f * side}, {0, 0, -side}};
        Hit<float> hit;
        ASSERT_TRUE(tracer.closest(ray, hit, counters));
        const SurfacePoint<float> sp = surface_point(s, ray, hit);
        EXPECT_EQ(sp.front_face, side > 0);
        EXPECT_EQ(sp.geometric_normal, Vec3<float>(0, 0, side)) << "the geometric normal faces the ray";
        EXPECT_EQ(sp.shading_normal, glm::vec3(0, 0, side)) << "the shading normal is turned to the ray's side";
    }
    // So the lit side of a triangle with flipped normals is lit, not left in its ambient term.
    WhittedSettings ws;
    ws.effects = analyze_effects(s);
    const Whitted<float, BruteForceTracer<float>> whitted(s, tracer, ws);
    const glm::vec3 c = whitted.radiance(Ray<float>{{0.1f, 0.0f, 2.0f}, {0, 0, -1}}, 0, glm::vec3(1), counters);
    EXPECT_GT(c.x, 10.0f * kAmbient);
    // And it shades exactly like the same triangle with correct normals.
    const Scene correct = lit_triangle({0, 0, 1});
    const BruteForceTracer<float> correct_tracer(correct, IntersectMethod::Watertight);
    const Whitted<float, BruteForceTracer<float>> correct_whitted(correct, correct_tracer, ws);
    EXPECT_EQ(c, correct_whitted.radiance(Ray<float>{{0.1f, 0.0f, 2.0f}, {0, 0, -1}}, 0, glm::vec3(1), counters));
}

// ---------------------------------------------------------------------------------------------------------------
// Inputs.

template <class T> void expect_broken_inputs_never_hit() {
    const Vec3<T> a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);   // a valid triangle
    const Ray<T> good{{0.2, 0.2, 1}, {0, 0, -1}};
    const Ray<T> diagonal{{0.5, 0.5, 1}, {0, 0, -1}};     // aimed at the degenerate triangles' line
    for (IntersectMethod m : kMethods) {
        for (const TriangleCase<T>& tri : broken_triangles<T>())
            for (const Ray<T>& ray : {good, diagonal}) {
                T t = 7, u = 7, v = 7;
                EXPECT_FALSE(intersect_triangle(m, ray, tri.a, tri.b, tri.c, t, u, v))
                    << name_of(m) << ", " << precision_name<T>() << ": " << tri.name << " gave t " << t;
            }
        for (const auto& [name, ray] : broken_rays<T>()) {
            T t = 7, u = 7, v = 7;
            EXPECT_FALSE(intersect_triangle(m, ray, a, b, c, t, u, v))
                << name_of(m) << ", " << precision_name<T>() << ": " << name << " gave t " << t;
        }
        // A NaN tmax is no length at all: Moller-Trumbore's t < tmax rejects every hit, the watertight test's
        // t >= tmax rejects none. Either answer is a usable one, as long as it is finite.
        {
            T t = 7, u = 7, v = 7;
            const Ray<T> no_length{{0.2, 0.2, 1}, {0, 0, -1}, std::numeric_limits<T>::quiet_NaN()};
            if (intersect_triangle(m, no_length, a, b, c, t, u, v)) {
                EXPECT_TRUE(std::isfinite(t) && std::isfinite(u) && std::isfinite(v) && t > T(0)) << name_of(m);
            }
        }
        // A collinear triangle of distinct points has zero area only up to rounding: a hit is allowed, but finite.
        T t = 7, u = 7, v = 7;
        if (intersect_triangle(m, diagonal, Vec3<T>(0, 0, 0), Vec3<T>(0.3, 0.3, 0), Vec3<T>(0.9, 0.9, 0), t, u, v)) {
            EXPECT_TRUE(std::isfinite(t) && std::isfinite(u) && std::isfinite(v)) << name_of(m);
            EXPECT_GT(t, T(0)) << name_of(m);
        }
    }
}

TEST(Inputs, DegenerateAndNonFiniteTrianglesAndRaysNeverHit) {
    expect_broken_inputs_never_hit<float>();
    expect_broken_inputs_never_hit<double>();
}

// A scene with every broken triangle (as a hand-made Scene would have them; flatten drops the non-finite ones) in
// front of one valid triangle.
Scene scene_with_broken_triangles() {
    Scene s = lit_triangle({0, 0, 1});
    for (const TriangleCase<float>& tri : broken_triangles<float>()) {
        for (const glm::vec3& p : {tri.a, tri.b, tri.c}) s.positions.push_back(p + glm::vec3(0, 0, 0.5f));
        s.normals.insert(s.normals.end(), {glm::vec3(0, 0, 1), glm::vec3(kNaN), glm::vec3(kInf, 0, 0)});
        s.uvs.insert(s.uvs.end(), {glm::vec2(kNaN), glm::vec2(kInf), glm::vec2(0)});
        s.material_ids.push_back(0);
    }
    return s;
}

TEST(Inputs, BruteForceTracerFindsTheValidTriangleBehindBrokenOnes) {
    const Scene s = scene_with_broken_triangles();
    for (IntersectMethod m : kMethods) {
        const BruteForceTracer<float> tracer(s, m);
        RayCounters counters;
        for (const glm::vec3 origin : {glm::vec3(0.2f, 0.3f, 2.0f), glm::vec3(0.2f, 0.2f, 2.0f), glm::vec3(0, 0, 2)}) {
            const Ray<float> ray{origin, {0, 0, -1}};
            Hit<float> hit;
            ASSERT_TRUE(tracer.closest(ray, hit, counters)) << name_of(m);
            EXPECT_EQ(hit.triangle, 0) << name_of(m);
            EXPECT_FLOAT_EQ(hit.t, 2.0f) << name_of(m);
            EXPECT_TRUE(tracer.occluded(ray, counters)) << name_of(m);
        }
        for (const auto& [name, ray] : broken_rays<float>()) {
            Hit<float> hit;
            EXPECT_FALSE(tracer.closest(ray, hit, counters)) << name_of(m) << ": " << name;
            EXPECT_FALSE(tracer.occluded(ray, counters)) << name_of(m) << ": " << name;
        }
    }
}

TEST(Inputs, WhittedGivesFinitePixelsForBrokenRaysAndTriangles) {
    // The whole integrator (shadow, reflection and refraction rays) on the Whitted scene with broken rays: the
    // background comes back, nothing hangs.
    const Scene whitted_scene = flatten(make_builtin_scene("whitted"), FlattenOptions{});
    for (IntersectMethod m : kMethods) {
        const BruteForceTracer<float> tracer(whitted_scene, m);
        WhittedSettings ws;
        ws.effects = analyze_effects(whitted_scene);
        const Whitted<float, BruteForceTracer<float>> whitted(whitted_scene, tracer, ws);
        RayCounters counters;
        for (const auto& [name, ray] : broken_rays<float>()) {
            const glm::vec3 c = whitted.radiance(ray, 0, glm::vec3(1), counters);
            EXPECT_EQ(c, whitted_scene.background) << name_of(m) << ": " << name;
        }
    }
    // Degenerate triangles and NaN/Inf vertices, normals and UVs in the scene: every pixel finite, in both precisions
    // and with every knob.
    const Scene broken = scene_with_broken_triangles();
    for (IntersectMethod m : kMethods)
        for (OffsetMethod o : kOffsets) {
            WhittedSettings ws;
            ws.offset = o;
            ws.effects = Effects{true, true, true, true};
            const BruteForceTracer<float> tf(broken, m);
            const BruteForceTracer<double> td(broken, m);
            const Whitted<float, BruteForceTracer<float>> wf(broken, tf, ws);
            const Whitted<double, BruteForceTracer<double>> wd(broken, td, ws);
            RayCounters counters;
            std::size_t non_finite = 0;
            for (int y = 0; y < 16; ++y)
                for (int x = 0; x < 16; ++x) {
                    const glm::vec3 o1(-1.2f + 0.15f * float(x), -1.2f + 0.15f * float(y), 2.0f);
                    const glm::vec3 cf = wf.radiance(Ray<float>{o1, glm::normalize(glm::vec3(0.05f, 0.02f, -1))}, 0,
                                                     glm::vec3(1), counters);
                    const glm::vec3 cd = wd.radiance(Ray<double>{o1, glm::normalize(glm::dvec3(0.05, 0.02, -1))}, 0,
                                                     glm::vec3(1), counters);
                    non_finite += !all_finite(cf) + !all_finite(cd);
                }
            EXPECT_EQ(non_finite, 0u) << name_of(m) << ", " << name_of(o);
        }
}

// Renders a flattened scene with the Whitted integrator and the brute-force tracer (two threads, pixel centres).
template <class T>
Image render(const Scene& s, const WhittedSettings& ws, IntersectMethod method, int width, int height) {
    const BruteForceTracer<T> tracer(s, method);
    const Whitted<T, BruteForceTracer<T>> whitted(s, tracer, ws);
    Image image(width, height);
    auto rows = [&](int first) {
        RayCounters counters;
        for (int y = first; y < height; y += 2)
            for (int x = 0; x < width; ++x)
                image.at(x, y) = whitted.radiance(camera_ray<T>(s.camera, width, height, T(x) + T(0.5), T(y) + T(0.5)),
                                                  0, glm::vec3(1), counters);
    };
    std::thread odd(rows, 1);
    rows(0);
    odd.join();
    return image;
}

std::string test_output_dir() {
    const std::filesystem::path dir = std::filesystem::path(RT_TEST_OUTPUT_DIR) / "hard_cases";
    std::filesystem::create_directories(dir);
    return dir.string();
}

TEST(Inputs, AGltfSceneWithDegenerateAndNonFiniteTrianglesRendersWithoutNaNOrInfPixels) {
    // The Whitted scene plus one mesh of broken triangles in front of the camera: degenerate ones (zero area: three
    // equal vertices, two equal, collinear) and ones with NaN/Inf positions, and a valid triangle with NaN/Inf
    // normals and UVs. Written as glTF, read back, flattened and rendered like any file a student might load.
    SceneAsset asset = make_builtin_scene("whitted");
    Primitive broken;
    broken.material = 1;   // glass: reflection and refraction rays through the broken triangles too
    const glm::vec3 o(0.0f, 1.2f, 2.5f);   // between the camera and the spheres
    broken.positions = {o, o, o,                                                        // three equal vertices
                        o, o + glm::vec3(0.5f, 0, 0), o + glm::vec3(0.5f, 0, 0),        // two equal
                        o, o + glm::vec3(0.3f, 0.1f, 0), o + glm::vec3(0.9f, 0.3f, 0),  // collinear
                        o, o + glm::vec3(1, 0, 0), glm::vec3(kNaN, 1, 2.5f),            // NaN position
                        o, glm::vec3(kInf, 1, 2.5f), o + glm::vec3(0, 1, 0),            // +Inf position
                        o, glm::vec3(0, -kInf, 2.5f), o + glm::vec3(0, -1, 0),          // -Inf position
                        o + glm::vec3(-1, -0.4f, 0), o + glm::vec3(-0.6f, -0.4f, 0), o + glm::vec3(-0.8f, -0.1f, 0)};
    broken.normals.assign(broken.positions.size(), glm::vec3(0, 0, 1));
    broken.uvs.assign(broken.positions.size(), glm::vec2(0.5f));
    broken.normals[18] = glm::vec3(kNaN);                // the valid triangle's normals and UVs are broken
    broken.normals[19] = glm::vec3(kInf, 0, 0);
    broken.normals[20] = glm::vec3(0.0f);
    broken.uvs[18] = glm::vec2(kNaN);
    broken.uvs[19] = glm::vec2(-kInf);
    Mesh mesh;
    mesh.name = "broken triangles";
    mesh.primitives.push_back(broken);
    asset.meshes.push_back(mesh);
    Node node;
    node.name = "broken triangles";
    node.mesh = int(asset.meshes.size() - 1);
    asset.nodes.push_back(node);
    asset.roots.push_back(int(asset.nodes.size() - 1));

    const std::string dir = test_output_dir();
    const std::string path = dir + "/broken_triangles.gltf";
    save_gltf(asset, path);
    const SceneAsset loaded = load_gltf(path);
    FlattenOptions fo;
    fo.aspect = 4.0f / 3.0f;
    std::size_t dropped = 0;
    const Scene s = flatten(loaded, fo, &dropped);
    EXPECT_EQ(dropped, 3u) << "flatten drops exactly the triangles with a non-finite vertex";
    EXPECT_EQ(s.triangle_count(), flatten(make_builtin_scene("whitted"), fo).triangle_count() + 4);

    WhittedSettings ws;
    ws.effects = analyze_effects(s);
    for (IntersectMethod m : kMethods)
        for (OffsetMethod off : kOffsets) {
            ws.offset = off;
            const Image image = render<float>(s, ws, m, 32, 24);
            EXPECT_EQ(count_non_finite(image), 0u) << name_of(m) << ", " << name_of(off);
            // Through an EXR file as the golden-image tests check it (a float image keeps NaN and Inf).
            const std::string exr = dir + "/broken_triangles_" + name_of(m) + "_" + name_of(off) + ".exr";
            write_image(exr, image);
            EXPECT_EQ(count_non_finite(read_image(exr)), 0u) << exr;
        }
    const Image d = render<double>(s, ws, IntersectMethod::Watertight, 32, 24);
    EXPECT_EQ(count_non_finite(d), 0u) << "double";
}

// ---------------------------------------------------------------------------------------------------------------
// The far scene.

// Fraction of pixels where some channel differs by more than `threshold` once both images are encoded as 8-bit sRGB,
// as the golden-image comparison does (tests/image_compare.cpp: threshold 0.016, at most 1% of pixels).
double fraction_differing(const Image& a, const Image& b, float threshold = 0.016f) {
    auto encode = [](float v) { return float(std::lround(linear_to_srgb(v) * 255.0f)) / 255.0f; };
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (std::abs(encode(a.pixels[i][c]) - encode(b.pixels[i][c])) > threshold) {
                ++differing;
                break;
            }
    return double(differing) / double(a.pixels.size());
}

constexpr int kFarWidth = 64, kFarHeight = 48;

Image render_builtin(const std::string& name, OffsetMethod offset) {
    FlattenOptions fo;
    fo.aspect = float(kFarWidth) / float(kFarHeight);
    const Scene s = flatten(make_builtin_scene(name), fo);
    WhittedSettings ws;
    ws.offset = offset;
    ws.effects = analyze_effects(s);
    Image image = render<float>(s, ws, IntersectMethod::Watertight, kFarWidth, kFarHeight);
    EXPECT_EQ(count_non_finite(image), 0u) << name << ", " << name_of(offset);
    return image;
}

const Image& whitted_reference() {
    static const Image image = render_builtin("whitted", OffsetMethod::Robust);
    return image;
}

TEST(FarScene, RendersLikeWhittedWithTheRobustOffset) {
    const double differing = fraction_differing(render_builtin("far", OffsetMethod::Robust), whitted_reference());
    std::printf("[ far ] builtin:far vs builtin:whitted, %dx%d, float, robust offset: %.2f%% of pixels differ by more "
                "than 0.016 (golden limit 1%%)\n", kFarWidth, kFarHeight, 100 * differing);
    RecordProperty("differing_percent", std::to_string(100 * differing));
    EXPECT_LT(differing, 0.01);
}

TEST(FarScene, AFixedEpsilonShowsAcneThereButNotNearTheOrigin) {
    const double far = fraction_differing(render_builtin("far", OffsetMethod::Epsilon), whitted_reference());
    const double near = fraction_differing(render_builtin("whitted", OffsetMethod::Epsilon), whitted_reference());
    std::printf("[ far ] epsilon offset, %dx%d, float: builtin:far differs from builtin:whitted in %.2f%% of pixels "
                "(acne), builtin:whitted itself in %.2f%%\n", kFarWidth, kFarHeight, 100 * far, 100 * near);
    RecordProperty("far_differing_percent", std::to_string(100 * far));
    EXPECT_GT(far, 0.05) << "at 1e4 the 1e-4 epsilon is below a float step: acne on every surface";
    EXPECT_LT(near, 0.01) << "near the origin the epsilon works";
}

}  // namespace
}  // namespace rt
