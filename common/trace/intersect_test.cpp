// Ray/triangle intersection basics for both methods and both precisions. The hard cases: degenerate and NaN input in
// intersect_inputs_test.cpp; shared edges and vertices, through stage 01's brute-force tracer, in
// 01_naive/intersect_watertight_test.cpp.
#include <gtest/gtest.h>

#include "intersect.h"

namespace rt {
namespace {

template <class T>
class IntersectTest : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(IntersectTest, Scalars);

TYPED_TEST(IntersectTest, BothMethodsAgreeOnAPlainHit) {
    using T = TypeParam;
    const Vec3<T> a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    Ray<T> ray;
    ray.origin = Vec3<T>(0.25, 0.25, 1);
    ray.direction = Vec3<T>(0, 0, -1);
    for (IntersectMethod m : {IntersectMethod::Moller, IntersectMethod::Watertight}) {
        T t = 0, u = 0, v = 0;
        ASSERT_TRUE(intersect_triangle(m, ray, a, b, c, t, u, v));
        EXPECT_NEAR(double(t), 1.0, 1e-6);
        EXPECT_NEAR(double(u), 0.25, 1e-6);
        EXPECT_NEAR(double(v), 0.25, 1e-6);
    }
}

TYPED_TEST(IntersectTest, MissesOutsideBehindAndBeyondTmax) {
    using T = TypeParam;
    const Vec3<T> a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    for (IntersectMethod m : {IntersectMethod::Moller, IntersectMethod::Watertight}) {
        T t, u, v;
        Ray<T> outside{Vec3<T>(0.8, 0.8, 1), Vec3<T>(0, 0, -1)};
        EXPECT_FALSE(intersect_triangle(m, outside, a, b, c, t, u, v));
        Ray<T> behind{Vec3<T>(0.2, 0.2, -1), Vec3<T>(0, 0, -1)};
        EXPECT_FALSE(intersect_triangle(m, behind, a, b, c, t, u, v));
        Ray<T> short_ray{Vec3<T>(0.2, 0.2, 1), Vec3<T>(0, 0, -1), T(0.5)};
        EXPECT_FALSE(intersect_triangle(m, short_ray, a, b, c, t, u, v));
    }
}

TYPED_TEST(IntersectTest, BackFacesAreHitToo) {
    using T = TypeParam;
    const Vec3<T> a(0, 0, 0), b(0, 1, 0), c(1, 0, 0);   // clockwise seen from +z
    Ray<T> ray{Vec3<T>(0.2, 0.2, 1), Vec3<T>(0, 0, -1)};
    for (IntersectMethod m : {IntersectMethod::Moller, IntersectMethod::Watertight}) {
        T t, u, v;
        EXPECT_TRUE(intersect_triangle(m, ray, a, b, c, t, u, v));
    }
}

}  // namespace
}  // namespace rt
