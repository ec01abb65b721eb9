// The exact cross-stage check (hit_compare.h) on synthetic dumps, and the hit file round trip.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "common/app/hit_file.h"
#include "hit_compare.h"

namespace rt {
namespace {

HitRecord ray(std::uint32_t pixel, std::uint32_t path, RayKind kind, std::int32_t triangle, float t,
              std::uint32_t light = 0) {
    HitRecord r;
    r.pixel = pixel;
    r.path = path;
    r.kind_light = pack_kind_light(kind, light);
    r.triangle = triangle;
    r.t = t;
    r.origin[0] = 0.5f * float(pixel);
    r.origin[2] = 3.0f;   // the largest component: the ray ulp bound is in its ulps
    r.direction[2] = -1.0f;
    return r;
}

// Two pixels: primary, a shadow ray per light (2 lights), a reflection from pixel 0.
std::vector<HitRecord> scene_dump() {
    return {ray(0, 1, RayKind::Primary, 3, 1.5f),  ray(0, 1, RayKind::Shadow, -1, 0.0f, 0),
            ray(0, 1, RayKind::Shadow, 1, 0.0f, 1), ray(0, 2, RayKind::Reflection, 7, 2.25f),
            ray(1, 1, RayKind::Primary, 4, 1.75f), ray(1, 1, RayKind::Shadow, -1, 0.0f, 0),
            ray(1, 1, RayKind::Shadow, -1, 0.0f, 1)};
}

float ulps_above(float x, int n) {
    for (int i = 0; i < n; ++i) x = std::nextafter(x, INFINITY);
    return x;
}

TEST(HitCompare, IdenticalDumpsInAnyOrderMatch) {
    std::vector<HitRecord> b = scene_dump();
    std::reverse(b.begin(), b.end());
    const HitComparison c = compare_hits(scene_dump(), b, {});
    EXPECT_TRUE(c.passed({}));
    EXPECT_EQ(c.differences(), 0u);
    EXPECT_EQ(c.compared, 5u);
    EXPECT_EQ(c.count_a, (std::array<std::uint64_t, kRayKinds>{2, 4, 1, 0, 0}));
    EXPECT_EQ(c.count_a, c.count_b);
}

TEST(HitCompare, ADifferentTriangleFails) {
    std::vector<HitRecord> b = scene_dump();
    b[3].triangle = 8;
    const HitComparison c = compare_hits(scene_dump(), b, {});
    EXPECT_EQ(c.different_triangle, 1u);
    EXPECT_FALSE(c.passed({}));
    HitCompareOptions lenient;
    lenient.fraction = 0.2;   // 1 of 5
    EXPECT_TRUE(c.passed(lenient));
}

TEST(HitCompare, AShadowAnswerThatDiffersIsADifferentTriangle) {
    std::vector<HitRecord> b = scene_dump();
    b[2].triangle = -1;   // occluded in A, not in B
    EXPECT_EQ(compare_hits(scene_dump(), b, {}).different_triangle, 1u);
}

TEST(HitCompare, AMissingRayIsReportedOnItsSide) {
    std::vector<HitRecord> b = scene_dump();
    b.erase(b.begin() + 5);   // pixel 1's shadow ray to light 0
    const HitComparison c = compare_hits(scene_dump(), b, {});
    EXPECT_EQ(c.only_a, 1u);
    EXPECT_EQ(c.only_b, 0u);
    EXPECT_EQ(c.count_b[std::size_t(RayKind::Shadow)], 3u);
    EXPECT_FALSE(c.passed({}));
    const HitComparison reversed = compare_hits(b, scene_dump(), {});
    EXPECT_EQ(reversed.only_b, 1u);
}

TEST(HitCompare, TAndRayAreComparedWithinTheUlpBound) {
    std::vector<HitRecord> b = scene_dump();
    b[3].t = ulps_above(b[3].t, 3);
    b[1].origin[2] = ulps_above(b[1].origin[2], 2);
    HitCompareOptions options;
    options.t_ulps = 2;
    options.ray_ulps = 2;
    HitComparison c = compare_hits(scene_dump(), b, options);
    EXPECT_EQ(c.t_beyond, 1u);
    EXPECT_EQ(c.different_ray, 0u);
    options.t_ulps = 3;
    options.ray_ulps = 1;
    c = compare_hits(scene_dump(), b, options);
    EXPECT_EQ(c.t_beyond, 0u);
    EXPECT_EQ(c.different_ray, 1u);
    options.ray_ulps = 2;
    EXPECT_TRUE(compare_hits(scene_dump(), b, options).passed(options));
}

// A hit 0.0075 along a ray from x = 0.27: t's ulps are tiny, the point's are those of 0.27. --point-ulps measures the
// difference there (a GPU's t differed by 55 ulps of t and 1 ulp of the point); 0 still means t bit for bit.
TEST(HitCompare, PointUlpsMeasureTAtTheHitPointInUnitsOfItsCoordinates) {
    HitRecord a = ray(0, 2, RayKind::Reflection, 7, 0.0075f);
    a.origin[0] = 0.27f;
    a.origin[2] = 0.0f;
    a.direction[0] = 0.6f;
    a.direction[2] = -0.8f;
    HitRecord b = a;
    b.t = ulps_above(a.t, 55);
    const float point_ulp = std::nextafter(0.2745f, INFINITY) - 0.2745f;   // of the largest coordinate, x
    ASSERT_LE(double(b.t - a.t) * 0.8, double(point_ulp));
    EXPECT_TRUE(same_hit_point(a, a.t, b.t, 1));
    EXPECT_FALSE(same_hit_point(a, a.t, b.t, 0));
    EXPECT_TRUE(same_hit_point(a, a.t, a.t, 0));
    b.t = a.t + 3.0f * point_ulp / 0.8f;   // 3 ulps of the point apart (t's step along z, the largest direction)
    EXPECT_FALSE(same_hit_point(a, a.t, b.t, 2));
    EXPECT_TRUE(same_hit_point(a, a.t, b.t, 4));
    b.t = NAN;
    EXPECT_FALSE(same_hit_point(a, a.t, b.t, 64));

    HitCompareOptions options;
    options.point_ulps = 1;
    std::vector<HitRecord> dump_a{ray(0, 1, RayKind::Primary, 3, 1.5f), a};
    std::vector<HitRecord> dump_b{ray(0, 1, RayKind::Primary, 3, 1.5f), a};
    dump_b[1].t = ulps_above(a.t, 55);
    EXPECT_TRUE(compare_hits(dump_a, dump_b, options).passed(options));
    options.t_ulps = 54;   // not used with point_ulps
    options.point_ulps.reset();
    const HitComparison c = compare_hits(dump_a, dump_b, options);
    EXPECT_EQ(c.t_beyond, 1u);
    EXPECT_FALSE(c.passed(options));
}

TEST(HitCompare, ADifferingPrimaryExcludesItsTreeWithinThePrimaryFraction) {
    std::vector<HitRecord> b = scene_dump();
    b[0].triangle = 9;                                      // pixel 0 sees another triangle (a shared edge) ...
    b[3] = ray(0, 3, RayKind::Refraction, 2, 1.0f);   // ... so its tree differs
    HitCompareOptions options;
    HitComparison c = compare_hits(scene_dump(), b, options);
    EXPECT_EQ(c.differing_primaries, 1u);
    EXPECT_EQ(c.excluded, 6u);    // A: 2 shadow + reflection; B: 2 shadow + refraction
    EXPECT_EQ(c.differences(), 0u);
    EXPECT_FALSE(c.passed(options));
    options.primary_fraction = 0.5;   // 1 of 2 primaries
    EXPECT_TRUE(c.passed(options));
}

TEST(HitCompare, AnEmptyDumpNeverPasses) {
    HitCompareOptions anything;
    anything.primary_fraction = anything.fraction = 1.0;
    EXPECT_FALSE(compare_hits(scene_dump(), {}, anything).passed(anything));
    EXPECT_FALSE(compare_hits({}, {}, anything).passed(anything));
}

TEST(HitCompare, UlpDistance) {
    EXPECT_EQ(ulp_distance(1.0f, 1.0f), 0u);
    EXPECT_EQ(ulp_distance(0.0f, -0.0f), 0u);
    EXPECT_EQ(ulp_distance(1.0f, ulps_above(1.0f, 5)), 5u);
    EXPECT_EQ(ulp_distance(-std::nextafter(0.0f, 1.0f), std::nextafter(0.0f, 1.0f)), 2u);
    EXPECT_EQ(ulp_distance(NAN, 1.0f), UINT64_MAX);
}

TEST(HitFile, RoundTripAndTruncationIsAnError) {
    const std::string path = std::string(RT_TEST_OUTPUT_DIR) + "/round_trip.hits";
    std::filesystem::create_directories(RT_TEST_OUTPUT_DIR);
    write_hit_file(path, scene_dump());
    const std::vector<HitRecord> back = read_hit_file(path);
    ASSERT_EQ(back.size(), scene_dump().size());
    EXPECT_EQ(compare_hits(back, scene_dump(), {}).differences(), 0u);
    EXPECT_EQ(std::filesystem::file_size(path), 8 + 48 * back.size());
    std::filesystem::resize_file(path, 8 + 48 * back.size() - 1);
    EXPECT_THROW(read_hit_file(path), std::runtime_error);
}

}  // namespace
}  // namespace rt
