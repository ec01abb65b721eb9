// The reference tracer's tie rule: of triangles hit at the same t, the lowest id wins (the exact hit checks between
// stages, tests/compare_hits.cpp, rely on it).
#include <gtest/gtest.h>

#include "brute_force_tracer.h"

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

}  // namespace
}  // namespace rt
