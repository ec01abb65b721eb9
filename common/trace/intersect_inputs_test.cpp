// The ray/triangle tests (intersect.h) on input that must not break them: degenerate and non-finite triangles and
// NaN/zero ray directions never hit, a NaN tmax and a collinear triangle give finite answers. The same cases through
// the brute-force tracer and the whole integrator are 01_naive/whitted_hard_cases_test.cpp's; the GLSL twin's are
// common/gpu/glsl_twins/hard_cases_glsl_test.cpp's.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "hard_cases.h"
#include "intersect.h"

namespace rt {
namespace {

using namespace hard_cases;   // the broken triangles and rays shared with the other suites

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

}  // namespace
}  // namespace rt
