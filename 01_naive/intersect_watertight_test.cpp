// Watertightness of the ray/triangle tests (intersect.h) in stage 01's brute-force tracer: rays aimed exactly at shared
// vertices and edges of closed meshes never slip through with the watertight test (Woop, Benthin & Wald 2013);
// Moller-Trumbore's misses there are counted and printed; away from edges the two agree. The rays come from
// common/trace/hard_cases.h, shared with the GLSL suite (common/gpu/glsl_twins/hard_cases_glsl_test.cpp). Run
// build/tests/unit_tests_01_naive --gtest_filter='Watertight*' to see the rates.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "01_naive/brute_force_tracer.h"
#include "common/trace/hard_cases.h"
#include "common/trace/intersect.h"

namespace rt {
namespace {

using namespace hard_cases;   // the meshes, rays and placements shared with the GLSL suite

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

}  // namespace
}  // namespace rt
