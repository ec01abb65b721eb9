// The CPU reference of ray sorting (ray_keys.h): what the key sees, and the compression round trip.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
