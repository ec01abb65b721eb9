// The CPU reference of ray sorting (ray_keys.h): what the key sees, and the compression round trip.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "ray_keys.h"

namespace rt {
namespace {

gpu::WavefrontRay make_ray(glm::vec3 origin, glm::vec3 direction, std::uint32_t kind = 2, std::uint32_t light = 0) {
    gpu::WavefrontRay r{};
    r.origin = origin;
    r.direction = direction;
    r.depth_kind = 1u | (kind << 16);
    r.light = light;
    return r;
}

const RayKeyLayout kLayout = make_key_layout({-1, -1, -1}, {1, 1, 1}, 30, 12, 1);

TEST(RayKeys, LayoutSplitsTheBitsAndLeavesRoomForTheGroups) {
    EXPECT_EQ(kLayout.origin_bits, glm::uvec3(6, 6, 6));
    EXPECT_EQ(kLayout.direction_bits, glm::uvec2(6, 6));
    EXPECT_EQ(kLayout.group_count, 4u);   // primary, reflection, refraction, shadow towards light 0
    EXPECT_EQ(kLayout.hash_bits, 30u);
    EXPECT_EQ(kLayout.sort_bits, 32u);
    const RayKeyLayout many_lights = make_key_layout({-1, -1, -1}, {1, 1, 1}, 30, 12, 100);   // 103 groups: 7 bits
    EXPECT_EQ(many_lights.hash_bits, 25u);
    EXPECT_EQ(many_lights.hash_drop, 5u);
    EXPECT_EQ(many_lights.sort_bits, 32u);
    EXPECT_THROW(make_key_layout({0, 0, 0}, {1, 1, 1}, 33, 12, 1), std::invalid_argument);
    EXPECT_THROW(make_key_layout({0, 0, 0}, {1, 1, 1}, 10, 12, 1), std::invalid_argument);
}

// Reis's code took its azimuth from atan2(d.x, d.x): rays differing only in d.y got the same key. Here every single
// coordinate of the origin and of the direction, moved alone, changes the key.
TEST(RayKeys, EachOriginAndDirectionCoordinateAloneChangesTheKey) {
    const glm::vec3 origin{0.1f, 0.2f, 0.3f};
    const glm::vec3 direction{0.3f, 0.4f, 0.5f};
    const std::uint32_t base = ray_key(make_ray(origin, direction), kLayout);
    for (int a = 0; a < 3; ++a) {
        glm::vec3 o = origin;
        o[a] += 0.5f;
        EXPECT_NE(ray_key(make_ray(o, direction), kLayout), base) << "origin axis " << a;
        glm::vec3 d = direction;
        d[a] = -d[a];   // the other hemisphere, or the other side of the diamond
        EXPECT_NE(ray_key(make_ray(origin, d), kLayout), base) << "direction axis " << a << " flipped";
        d = direction;
        d[a] *= 1.5f;   // the same signs, a different angle
        EXPECT_NE(ray_key(make_ray(origin, d), kLayout), base) << "direction axis " << a << " scaled";
    }
}

TEST(RayKeys, DirectionsOfOneCellAreScaleInvariantAndCoverAllCells) {
    // Scaling a direction by a power of two scales every step exactly: the same key.
    const gpu::WavefrontRay r = make_ray({0, 0, 0}, {0.3f, -0.4f, -0.5f});
    EXPECT_EQ(ray_key(make_ray(r.origin, r.direction * 8.0f), kLayout), ray_key(r, kLayout));
    // Directions spread over the sphere reach every one of the 4 x 4 octahedral cells of a 4-bit layout.
    const RayKeyLayout coarse = make_key_layout({-1, -1, -1}, {1, 1, 1}, 4, 4, 1);
    std::vector<bool> seen(16, false);
    std::mt19937 rng(7);
    std::normal_distribution<float> normal;
    for (int i = 0; i < 4000; ++i)
        seen[ray_key(make_ray({0, 0, 0}, {normal(rng), normal(rng), normal(rng)}), coarse) & 15u] = true;
    EXPECT_EQ(std::count(seen.begin(), seen.end(), true), 16);
}

TEST(RayKeys, OriginsOutsideTheBoxClampToTheBorderCells) {
    EXPECT_EQ(quantize_axis(-5.0f, 0.0f, 4.0f, 2), 0u);
    EXPECT_EQ(quantize_axis(0.99f, 0.0f, 4.0f, 2), 3u);
    EXPECT_EQ(quantize_axis(1.0f, 0.0f, 4.0f, 2), 3u);   // the box's far face
    EXPECT_EQ(quantize_axis(7.0f, 0.0f, 4.0f, 2), 3u);
    EXPECT_EQ(quantize_axis(std::nanf(""), 0.0f, 4.0f, 2), 0u);
    EXPECT_EQ(quantize_axis(0.3f, 0.0f, 4.0f, 0), 0u);
}

TEST(RayKeys, GroupsTakeTheTopBitsInQueueOrder) {
    const glm::vec3 o{0.5f, 0.5f, 0.5f}, d{0, 0, 1};
    const std::uint32_t primary = ray_key(make_ray(o, d, 0), kLayout);
    const std::uint32_t reflection = ray_key(make_ray(o, d, 2), kLayout);
    const std::uint32_t refraction = ray_key(make_ray(o, d, 3), kLayout);
    const std::uint32_t shadow = ray_key(make_ray(o, d, 1, 0), kLayout);
    EXPECT_EQ(primary >> 30, 0u);
    EXPECT_EQ(reflection >> 30, 1u);
    EXPECT_EQ(refraction >> 30, 2u);
    EXPECT_EQ(shadow >> 30, 3u);
    EXPECT_EQ(primary & 0x3fffffffu, shadow & 0x3fffffffu);
}

// The origin grid's cells are cubes: one cell size on every axis, each axis as many bits as its extent needs.
TEST(RayKeys, OriginCellsAreCubesAndEachAxisGetsTheBitsItsExtentNeeds) {
    // Extents 4 : 1 : 2 and 26 origin bits: b_x = b_y + 2 = b_z + 1, 3 b_x - 3 <= 26, so b_x = 9 and c = 4 / 2^9.
    const RayKeyLayout L = make_key_layout({0, 0, 0}, {4, 1, 2}, 30, 4, 1, KeyOrder::direction_first);
    EXPECT_EQ(L.origin_bits, glm::uvec3(9, 7, 8));
    EXPECT_EQ(L.origin_total, 24u);   // a finer cube (2^-8) would need 27 bits
    EXPECT_EQ(L.cell_size, 1.0 / 128);
    EXPECT_EQ(L.origin_scale, 128.0f);
    EXPECT_EQ(L.key_bits, 28u);       // 24 origin + 4 direction bits: the 2 left over are not used
    // One cell size on every axis: a step of one cell moves each axis' index by one.
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(quantize_axis(0.5f / 128, 0.0f, L.origin_scale, L.origin_bits[a]), 0u);
        EXPECT_EQ(quantize_axis(1.5f / 128, 0.0f, L.origin_scale, L.origin_bits[a]), 1u);
        EXPECT_EQ(quantize_axis(100.5f / 128, 0.0f, L.origin_scale, L.origin_bits[a]), 100u);
    }
    // A cube's axes get equal bits; the 4 : 1 : 2 box's do not (equal bits would make its cells 4 x 1 x 2 cubes).
    const RayKeyLayout cube = make_key_layout({-1, -1, -1}, {1, 1, 1}, 30, 12, 1);
    EXPECT_EQ(cube.origin_bits, glm::uvec3(6, 6, 6));
    EXPECT_EQ(cube.cell_size, 2.0 / 64);
}

TEST(RayKeys, AFlatAxisGetsNoBitsAndAThinOneFew) {
    const RayKeyLayout flat = make_key_layout({0, 3, 0}, {8, 3, 8}, 30, 4, 1);   // y flat: 26 bits over x and z
    EXPECT_EQ(flat.origin_bits, glm::uvec3(13, 0, 13));
    EXPECT_EQ(flat.cell_size, 8.0 / 8192);
    // A scene like builtin:spheres:N: wide in x and z, thin in y.
    const RayKeyLayout thin = make_key_layout({-10, 0, -10}, {10, 0.25f, 10}, 30, 4, 1);
    EXPECT_LT(thin.origin_bits.y + 5, thin.origin_bits.x);
    EXPECT_EQ(thin.origin_bits.x, thin.origin_bits.z);
    EXPECT_LE(thin.origin_total, 26u);
    EXPECT_GT(thin.origin_total + 3, 26u) << "the finest cubic grid that fits";
    // Origins differing only along the flat axis share their cell.
    const RayKeyLayout& L = flat;
    EXPECT_EQ(origin_code({1, 3, 1}, L), origin_code({1, -100, 1}, L));
    EXPECT_NE(origin_code({1, 3, 1}, L), origin_code({1.01f, 3, 1}, L));
}

TEST(RayKeys, APointLikeBoxGivesEveryRayOriginCellZero) {
    const RayKeyLayout L = make_key_layout({1, 2, 3}, {1, 2, 3}, 30, 4, 1, KeyOrder::direction_first);
    EXPECT_EQ(L.origin_bits, glm::uvec3(0));
    EXPECT_EQ(L.origin_total, 0u);
    EXPECT_EQ(L.origin_scale, 0.0f);
    EXPECT_EQ(L.key_bits, 4u);
    EXPECT_EQ(origin_code({5, -7, 1e30f}, L), 0u);
    // The direction still sorts; an empty hash leaves the group alone.
    EXPECT_NE(ray_key(make_ray({1, 2, 3}, {1, 0, 0}), L), ray_key(make_ray({1, 2, 3}, {-1, 0, 0}), L));
    const RayKeyLayout none = make_key_layout({1, 2, 3}, {1, 2, 3}, 4, 0, 1);
    EXPECT_EQ(none.key_bits, 0u);
    EXPECT_EQ(none.sort_bits, 2u);
    EXPECT_EQ(ray_key(make_ray({0, 0, 0}, {1, 1, 1}, 1), none), 3u);
}

// Whatever the box, the layout keeps shifts below 32, the scale a normal float (or 0) and the key's cells in range.
TEST(RayKeys, AbsurdBoxesGiveAUsableLayout) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float big = std::numeric_limits<float>::max();
    struct Box {
        glm::vec3 lo, hi;
        const char* what;
    };
    const Box boxes[] = {{{-big, -big, -big}, {big, big, big}, "the largest floats"},
                         {{-1e20f, 0, 0}, {1e20f, 1, 1}, "huge in x"},
                         {{0, 0, 0}, {1e-30f, 1e-30f, 1e-30f}, "tiny"},
                         {{0, 0, 0}, {1e-40f, 1e-40f, 1e-40f}, "subnormal"},
                         {{1e-40f, 0, 0}, {1, 1, 1}, "subnormal corner"},
                         {{1e6f, 1e6f, 1e6f}, {1e6f + 1, 1e6f + 1, 1e6f + 1}, "far from the origin"},
                         {{-inf, 0, 0}, {inf, 1, 1}, "infinite in x"},
                         {{nan, 0, 0}, {1, 1, nan}, "NaN"},
                         {{1, 1, 1}, {-1, -1, -1}, "inverted (empty)"},
                         {{0, 0, 0}, {1, 0, 0}, "a segment"}};
    const gpu::WavefrontRay rays[] = {make_ray({0.5f, 0.5f, 0.5f}, {1, 2, 3}), make_ray({nan, inf, -inf}, {nan, 0, 1}),
                                      make_ray({big, -big, 0}, {inf, -inf, 0}), make_ray({1e-40f, 0, 0}, {0, 0, 0})};
    for (const Box& b : boxes)
        for (auto [key_bits, direction_bits] : {std::pair{30u, 4u}, {32u, 0u}, {1u, 0u}, {32u, 32u}}) {
            for (KeyOrder order : {KeyOrder::origin_first, KeyOrder::direction_first}) {
                const RayKeyLayout L = make_key_layout(b.lo, b.hi, key_bits, direction_bits, 1, order);
                SCOPED_TRACE(std::string(b.what) + ", key bits " + std::to_string(key_bits));
                for (int a = 0; a < 3; ++a) {
                    EXPECT_LE(L.origin_bits[a], 24u);
                    EXPECT_TRUE(std::isfinite(L.box_min[a]));
                    EXPECT_NE(std::fpclassify(L.box_min[a]), FP_SUBNORMAL);
                }
                EXPECT_LE(L.origin_total, key_bits - direction_bits);
                EXPECT_EQ(L.origin_total, L.origin_bits.x + L.origin_bits.y + L.origin_bits.z);
                EXPECT_LE(L.sort_bits, 32u);
                if (L.origin_total > 0) {
                    EXPECT_GE(L.origin_scale, 0x1p-100f);
                    EXPECT_LE(L.origin_scale, 0x1p100f);
                    EXPECT_GT(L.cell_size, 0.0);
                } else {
                    EXPECT_EQ(L.origin_scale, 0.0f);
                }
                for (const gpu::WavefrontRay& r : rays) {
                    if (L.origin_total < 32) {
                        EXPECT_LT(origin_code(r.origin, L), 1u << L.origin_total);
                    }
                    if (L.sort_bits < 32) {
                        EXPECT_LT(ray_key(r, L), 1u << L.sort_bits);
                    }
                }
            }
        }
    // Non-finite and huge axes count as flat; the finite ones keep their bits.
    EXPECT_EQ(make_key_layout({-inf, 0, 0}, {inf, 1, 1}, 30, 4, 1).origin_bits, glm::uvec3(0, 13, 13));
    EXPECT_EQ(make_key_layout({nan, 0, 0}, {1, 1, 1}, 30, 4, 1).origin_bits, glm::uvec3(0, 13, 13));
    EXPECT_EQ(make_key_layout({-big, -big, -big}, {big, big, big}, 30, 4, 1).origin_total, 0u);
    EXPECT_EQ(make_key_layout({-1e20f, 0, 0}, {1e20f, 1, 1}, 30, 4, 1).origin_bits, glm::uvec3(24, 0, 0));
    EXPECT_EQ(make_key_layout({0, 0, 0}, {1, 0, 0}, 32, 0, 1).origin_bits, glm::uvec3(24, 0, 0));
}

// Shadow keys: the origin cell first (the direction, if it has bits, below it). Reflection and refraction keys: a
// coarse direction cell first, the origin cell below it.
TEST(RayKeys, ShadowKeysAreOriginFirstAndTraceKeysDirectionFirst) {
    const glm::vec3 lo{0, 0, 0}, hi{1, 1, 1};
    const RayKeyLayout shadow = make_key_layout(lo, hi, 30, 6, 1, KeyOrder::origin_first);
    const RayKeyLayout trace = make_key_layout(lo, hi, 30, 4, 1, KeyOrder::direction_first);
    EXPECT_FALSE(shadow.direction_major);
    EXPECT_TRUE(trace.direction_major);
    EXPECT_STREQ(key_order_name(KeyOrder::origin_first), "origin first");
    EXPECT_STREQ(key_order_name(KeyOrder::direction_first), "direction first");
    const glm::vec3 o1{0.1f, 0.2f, 0.3f}, o2{0.9f, 0.8f, 0.7f};
    const glm::vec3 d1{0.3f, 0.4f, 0.5f}, d2{-0.3f, 0.4f, -0.5f};
    for (std::uint32_t kind : {2u, 3u}) {   // reflection, refraction
        const std::uint32_t a = ray_key(make_ray(o1, d1, kind), trace), b = ray_key(make_ray(o2, d1, kind), trace),
                            c = ray_key(make_ray(o1, d2, kind), trace);
        EXPECT_LT(a ^ b, 1u << trace.origin_total) << "the same direction cell: only the low (origin) bits differ";
        EXPECT_GE(a ^ c, 1u << trace.origin_total) << "another direction cell: the high bits differ";
        EXPECT_EQ(a & ((1u << trace.origin_total) - 1), origin_code(o1, trace));
        EXPECT_EQ(trace.direction_total, 4u);
        EXPECT_EQ(trace.direction_bits, glm::uvec2(2, 2));
    }
    const std::uint32_t a = ray_key(make_ray(o1, d1, 1), shadow), b = ray_key(make_ray(o2, d1, 1), shadow),
                        c = ray_key(make_ray(o1, d2, 1), shadow);
    EXPECT_LT(a ^ c, 1u << shadow.direction_total) << "the same origin cell: only the low (direction) bits differ";
    EXPECT_GE(a ^ b, 1u << shadow.direction_total) << "another origin cell: the high bits differ";
    EXPECT_EQ((a >> shadow.direction_total) & ((1u << shadow.origin_total) - 1), origin_code(o1, shadow));
    // Without direction bits a shadow key is the group and the origin cell alone.
    const RayKeyLayout origin_only = make_key_layout(lo, hi, 30, 0, 1);
    EXPECT_EQ(ray_key(make_ray(o1, d1, 1), origin_only), ray_key(make_ray(o1, d2, 1), origin_only));
    EXPECT_EQ(ray_key(make_ray(o1, d1, 1), origin_only), (3u << 30) | origin_code(o1, origin_only));
}

// Morton order over cubic cells: the 8 children of a cell follow each other, whatever the bits per axis.
TEST(RayKeys, MortonOrderKeepsEachCubeOfCellsTogether) {
    const RayKeyLayout L = make_key_layout({0, 0, 0}, {4, 1, 2}, 30, 4, 1);   // bits 9, 7, 8; cell 1/128
    const float c = 1.0f / 128;
    for (glm::vec3 corner : {glm::vec3{0, 0, 0}, glm::vec3{64 * c, 32 * c, 10 * c}, glm::vec3{300 * c, 2 * c, 200 * c}}) {
        std::vector<std::uint32_t> codes;
        for (int i = 0; i < 8; ++i)
            codes.push_back(origin_code(corner + c * (glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1) + 0.5f), L));
        std::sort(codes.begin(), codes.end());
        EXPECT_EQ(codes.back() - codes.front(), 7u);
        EXPECT_EQ(codes.front() % 8, 0u);
    }
}

TEST(RayKeys, CompressionSortAndDecompressionEqualAStableSort) {
    std::mt19937 rng(3);
    std::vector<std::uint32_t> keys(1000);
    for (auto& k : keys) k = rng() % 37;   // many runs of equal keys, many repeats
    for (std::size_t i = 100; i < 200; ++i) keys[i] = 5;
    const RayChunks chunks = compress(keys);
    EXPECT_EQ(std::accumulate(chunks.sizes.begin(), chunks.sizes.end(), 0u), 1000u);
    for (std::size_t c = 1; c < chunks.keys.size(); ++c) EXPECT_NE(chunks.keys[c], chunks.keys[c - 1]);
    std::vector<std::uint32_t> expected(keys.size());
    std::iota(expected.begin(), expected.end(), 10u);
    std::stable_sort(expected.begin(), expected.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return keys[a - 10] < keys[b - 10]; });
    EXPECT_EQ(sorted_order(keys, 10), expected);
    EXPECT_TRUE(sorted_order({}, 0).empty());
}

}  // namespace
}  // namespace rt
