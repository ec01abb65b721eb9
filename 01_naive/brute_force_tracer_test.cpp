// The reference tracer's contract (exercises 01.closest_hit and 01.any_hit grade against it): the nearest hit with
// t < tmax, ties at equal t to the lowest id (the exact hit checks between stages, tests/compare_hits.cpp, rely on
// it), one test per triangle for a closest-hit ray, and for a shadow ray only the tests made up to its first hit.
#include <gtest/gtest.h>

#include "brute_force_tracer.h"
#include "common/trace/hard_cases.h"

namespace rt {
namespace {

void add_triangle(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    s.positions.insert(s.positions.end(), {a, b, c});
}

TEST(BruteForceTracer, TiesAtEqualTGoToTheLowestTriangleId) {
    Scene s;
    add_triangle(s, {-1, -1, -3}, {1, -1, -3}, {0, 1, -3});   // 0: behind the others
    add_triangle(s, {-1, -1, -2}, {1, -1, -2}, {0, 1, -2});   // 1: the nearest plane
    add_triangle(s, {0, 1, -2}, {-1, -1, -2}, {1, -1, -2});   // 2: the same triangle, vertices rotated
    add_triangle(s, {-1, -1, -2}, {0, 1, -2}, {1, -1, -2});   // 3: the same triangle, opposite winding
    for (IntersectMethod m : {IntersectMethod::Moller, IntersectMethod::Watertight}) {
        const BruteForceTracer<float> tracer(s, m);
        RayCounters counters;
        for (float x : {0.0f, 0.1f, -0.3f, 0.37f}) {
            Hit<float> hit;
            ASSERT_TRUE(tracer.closest(Ray<float>{{x, -0.2f, 0.0f}, {0, 0, -1}}, hit, counters));
            EXPECT_EQ(hit.triangle, 1) << "x " << x;
            EXPECT_EQ(hit.t, 2.0f);
        }
    }
}

// Parallel squares facing +z at the given depths (z = -depth), in that order; a ray down -z through (x, y) hits all.
Scene planes(std::initializer_list<float> depths) {
    Scene s;
    for (float d : depths) {
        add_triangle(s, {-1, -1, -d}, {1, -1, -d}, {1, 1, -d});
        add_triangle(s, {-1, -1, -d}, {1, 1, -d}, {-1, 1, -d});
    }
    return s;
}

constexpr IntersectMethod kBoth[] = {IntersectMethod::Moller, IntersectMethod::Watertight};

TEST(BruteForceTracer, ClosestFindsTheNearestWhateverTheTrianglesOrder) {
    // The nearest plane first, last and in the middle of the list.
    const std::pair<Scene, int> cases[] = {{planes({1, 2, 3, 4}), 0}, {planes({4, 3, 2, 1}), 6}, {planes({3, 1, 4, 2}), 2}};
    for (IntersectMethod m : kBoth)
        for (const auto& [scene, nearest] : cases) {
            const BruteForceTracer<float> tracer(scene, m);
            RayCounters counters;
            Hit<float> hit;
            ASSERT_TRUE(tracer.closest(Ray<float>{{0.3f, -0.6f, 0.0f}, {0, 0, -1}}, hit, counters));
            EXPECT_EQ(hit.triangle, nearest);
            EXPECT_EQ(hit.t, 1.0f);
            EXPECT_GT(hit.u + hit.v, 0.0f);
        }
}

TEST(BruteForceTracer, ClosestCountsOneTestPerTriangleForEveryRay) {
    const Scene s = planes({1, 2, 3});
    for (IntersectMethod m : kBoth) {
        const BruteForceTracer<float> tracer(s, m);
        RayCounters counters;
        Hit<float> hit;
        tracer.closest(Ray<float>{{0.2f, 0.1f, 0.0f}, {0, 0, -1}}, hit, counters);   // hits all six
        EXPECT_EQ(counters.intersection_tests, 6u);
        Hit<float> miss;
        EXPECT_FALSE(tracer.closest(Ray<float>{{5.0f, 0.1f, 0.0f}, {0, 0, -1}}, miss, counters));   // misses all
        EXPECT_EQ(counters.intersection_tests, 12u) << "a miss tests every triangle too";
        EXPECT_EQ(miss.triangle, -1);
        EXPECT_EQ(counters.total_rays(), 0u) << "the tracer counts tests; the caller counts rays";
    }
}

TEST(BruteForceTracer, ClosestIgnoresHitsAtOrBeyondTmaxAndBehindTheOrigin) {
    const Scene s = planes({1, 2, 3});
    for (IntersectMethod m : kBoth) {
        const BruteForceTracer<float> tracer(s, m);
        RayCounters counters;
        Hit<float> hit;
        ASSERT_TRUE(tracer.closest(Ray<float>{{0.2f, 0.1f, -1.5f}, {0, 0, -1}}, hit, counters));
        EXPECT_EQ(hit.t, 0.5f) << "the plane behind the origin is not hit";
        Ray<float> short_ray{{0.2f, 0.1f, 0.0f}, {0, 0, -1}};
        short_ray.tmax = 0.75f;
        Hit<float> none;
        EXPECT_FALSE(tracer.closest(short_ray, none, counters)) << "every plane lies beyond tmax";
        short_ray.tmax = 2.5f;
        Hit<float> first;
        ASSERT_TRUE(tracer.closest(short_ray, first, counters));
        EXPECT_EQ(first.t, 1.0f);
    }
}

TEST(BruteForceTracer, OccludedStopsAtTheFirstHitAndCountsTheTestsMade) {
    const Scene s = planes({5, 1, 2});   // triangles 0-1 at 5, 2-3 at 1, 4-5 at 2
    for (IntersectMethod m : kBoth) {
        const BruteForceTracer<float> tracer(s, m);
        RayCounters counters;
        // (0.5, -0.5) lies in the first triangle of each plane: triangle 0 blocks a long ray at once.
        EXPECT_TRUE(tracer.occluded(Ray<float>{{0.5f, -0.5f, 0.0f}, {0, 0, -1}}, counters));
        EXPECT_EQ(counters.intersection_tests, 1u) << "the first triangle hit ends the search";
        // With tmax 3 the plane at 5 is out of reach: triangle 2 (at 1) blocks, after 3 tests.
        Ray<float> shorter{{0.5f, -0.5f, 0.0f}, {0, 0, -1}};
        shorter.tmax = 3.0f;
        counters = {};
        EXPECT_TRUE(tracer.occluded(shorter, counters));
        EXPECT_EQ(counters.intersection_tests, 3u);
        // With tmax 0.5 nothing blocks: every triangle was tested.
        shorter.tmax = 0.5f;
        counters = {};
        EXPECT_FALSE(tracer.occluded(shorter, counters));
        EXPECT_EQ(counters.intersection_tests, 6u);
        // A ray pointing away is not blocked by what lies behind it.
        counters = {};
        EXPECT_FALSE(tracer.occluded(Ray<float>{{0.5f, -0.5f, 0.0f}, {0, 0, 1}}, counters));
        EXPECT_EQ(counters.intersection_tests, 6u);
        EXPECT_EQ(counters.total_rays(), 0u);
    }
}

TEST(BruteForceTracer, OccludedAgreesWithClosestOnEveryRayOfAFan) {
    const Scene s = planes({1, 2, 3});
    const BruteForceTracer<float> tracer(s, IntersectMethod::Watertight);
    for (int i = 0; i < 64; ++i) {
        const float a = 0.05f * float(i);
        Ray<float> ray{{0.0f, 0.0f, 0.5f}, glm::normalize(glm::vec3(std::cos(a), std::sin(a), -1.0f + 0.02f * float(i)))};
        ray.tmax = 0.5f + 0.05f * float(i);
        RayCounters counters;
        Hit<float> hit;
        EXPECT_EQ(tracer.occluded(ray, counters), tracer.closest(ray, hit, counters)) << "ray " << i;
    }
}

// --intersect chooses the test of every ray, shadow rays included: on rays aimed exactly at the shared edges and
// vertices of a closed sphere, Moller-Trumbore lets some through and the watertight test none, and a shadow ray must
// be blocked exactly where a closest-hit ray with the same test hits (an occluded() that always tested watertight
// passed every other test).
TEST(BruteForceTracer, OccludedUsesTheChosenTestAsClosestDoes) {
    const Scene s = hard_cases::closed_sphere();
    const auto [per_vertex, per_edge, per_point] = hard_cases::kSphereRays;
    const std::vector<Ray<float>> rays = hard_cases::rays_at_shared_vertices_and_edges<float>(
        s, per_vertex, per_edge, per_point, hard_cases::kWatertightSeed);
    std::size_t moller_misses = 0;
    for (IntersectMethod m : kBoth) {
        const BruteForceTracer<float> tracer(s, m);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            RayCounters counters;
            Hit<float> hit;
            const bool hits = tracer.closest(rays[i], hit, counters);
            moller_misses += m == IntersectMethod::Moller && !hits ? 1 : 0;
            ASSERT_EQ(tracer.occluded(rays[i], counters), hits)
                << (m == IntersectMethod::Moller ? "moller" : "watertight") << ", ray " << i;
        }
    }
    EXPECT_GT(moller_misses, 0u) << "the rays no longer slip through Moller-Trumbore's edges";
}

}  // namespace
}  // namespace rt
