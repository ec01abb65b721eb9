// The GPU ray sorting (ray_sort.h) against the CPU reference (ray_keys.h): keys bit for bit, and the sorted order
// of compression + radix sort + decompression.
#include <gtest/gtest.h>

#include <array>
#include <algorithm>
#include <limits>
#include <numeric>
#include <random>

#include "common/gpu/testing/gpu_test_context.h"
#include "ray_sort.h"

namespace rt {
namespace {

using gpu::Buffer;

// Random rays of every group: origins partly outside the box, directions of every octant and the axes.
std::vector<gpu::WavefrontRay> random_rays(std::size_t n, unsigned seed, unsigned lights) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1.5f, 1.5f);
    std::normal_distribution<float> normal;
    std::vector<gpu::WavefrontRay> rays(n);
    for (std::size_t i = 0; i < n; ++i) {
        gpu::WavefrontRay& r = rays[i];
        r.origin = {pos(rng), pos(rng), pos(rng)};
        r.direction = {normal(rng), normal(rng), normal(rng)};
        if (i % 7 == 0) r.direction = {0, 0, 0};
        if (i % 7 == 1) r.direction[int(i % 3)] = (i % 2 ? -0.0f : 0.0f);
        const std::uint32_t kind = std::uint32_t(rng() % 4);
        r.depth_kind = 1u | (kind << 16);
        r.light = std::uint32_t(rng() % (lights + 1));   // one more than there are: clamped into the last group
        r.pixel = std::uint32_t(i);
    }
    return rays;
}

std::vector<std::uint32_t> cpu_keys(const std::vector<gpu::WavefrontRay>& rays, const RayKeyLayout& layout,
                                    std::size_t first, std::size_t count) {
    std::vector<std::uint32_t> keys;
    for (std::size_t i = first; i < first + count; ++i) keys.push_back(ray_key(rays[i], layout));
    return keys;
}

TEST(RaySorter, KeysEqualTheCpuKeysBitForBit) {
    gpu::test_context();
    RaySorter sorter;
    const std::vector<gpu::WavefrontRay> rays = random_rays(5000, 1, 3);
    const Buffer buffer = Buffer::from(rays);
    for (auto [key_bits, direction_bits] : {std::pair{30u, 12u}, {32u, 16u}, {20u, 0u}, {16u, 16u}, {7u, 5u}}) {
        for (bool direction_major : {false, true}) {
            sorter.layout = make_key_layout({-1, -0.5f, -1}, {1, 0.5f, 1.25f}, key_bits, direction_bits, 3);
            sorter.layout.direction_major = direction_major;
            sorter.compute_keys(buffer, 123, 4321);
            EXPECT_EQ(sorter.keys().download<std::uint32_t>(4321), cpu_keys(rays, sorter.layout, 123, 4321))
                << "key bits " << key_bits << ", direction bits " << direction_bits << ", direction major "
                << direction_major;
        }
    }
}

// Rays a key must survive: NaN, infinite, zero and subnormal directions and origins, origins far outside the box,
// on its faces and on the cell borders of the layouts below.
std::vector<gpu::WavefrontRay> adversarial_rays(unsigned lights) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float big = std::numeric_limits<float>::max(), sub = 1e-40f;
    const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 0.25f, 1.25f, -0.5f, 3.0f / 128, 1e-7f, sub, -sub, big,
                            -big, inf, -inf, nan, 1e6f, 0.1f, 0.999999f};
    std::mt19937 rng(17);
    std::vector<gpu::WavefrontRay> rays;
    const std::size_t n = std::size(values);
    for (std::size_t i = 0; i < 6000; ++i) {
        gpu::WavefrontRay r{};
        for (int a = 0; a < 3; ++a) {
            r.origin[a] = values[rng() % n];
            r.direction[a] = values[rng() % n];
        }
        r.depth_kind = 1u | (std::uint32_t(rng() % 4) << 16);
        r.light = std::uint32_t(rng() % (lights + 1));
        rays.push_back(r);
    }
    return rays;
}

// Cubic cells, both orders, and the boxes the layout has to cope with: the GPU keys equal the CPU's bit for bit.
TEST(RaySorter, CubicKeysOfEveryOrderAndAbsurdBoxesEqualTheCpuKeys) {
    gpu::test_context();
    RaySorter sorter;
    const float inf = std::numeric_limits<float>::infinity(), big = std::numeric_limits<float>::max();
    struct Box {
        glm::vec3 lo, hi;
    };
    const Box boxes[] = {{{-1, -0.5f, -1}, {1, 0.5f, 1.25f}},   // the random rays' box
                         {{-10, 0, -10}, {10, 0.25f, 10}},      // thin in y
                         {{0, 0.5f, 0}, {1, 0.5f, 1}},          // flat in y
                         {{0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}},   // a point
                         {{0, 0, 0}, {1e-30f, 1e-30f, 1e-30f}},      // tiny: scale 2^100
                         {{1e-40f, 0, 0}, {1, 1, 1}},                // a subnormal corner
                         {{1e6f, 1e6f, 1e6f}, {1e6f + 1, 1e6f + 1, 1e6f + 1}},   // far from the origin
                         {{-1e20f, 0, 0}, {1e20f, 1, 1}},                         // huge in x
                         {{-big, -big, -big}, {big, big, big}},
                         {{-inf, 0, 0}, {inf, 1, 1}}};
    for (unsigned lights : {1u, 40u}) {   // 40 lights: 6 group bits, the hash's low bits give way
        std::vector<gpu::WavefrontRay> rays = adversarial_rays(lights);
        const std::vector<gpu::WavefrontRay> more = random_rays(4000, 9, lights);
        rays.insert(rays.end(), more.begin(), more.end());
        const Buffer buffer = Buffer::from(rays);
        for (const Box& b : boxes)
            for (auto [key_bits, direction_bits] : {std::pair{30u, 4u}, {30u, 0u}, {32u, 6u}, {9u, 3u}, {32u, 32u}})
                for (KeyOrder order : {KeyOrder::origin_first, KeyOrder::direction_first}) {
                    sorter.layout = make_key_layout(b.lo, b.hi, key_bits, direction_bits, lights, order);
                    sorter.compute_keys(buffer, 0, rays.size());
                    ASSERT_EQ(sorter.keys().download<std::uint32_t>(rays.size()),
                              cpu_keys(rays, sorter.layout, 0, rays.size()))
                        << "box " << b.lo.x << " " << b.lo.y << " " << b.lo.z << " .. " << b.hi.x << " " << b.hi.y
                        << " " << b.hi.z << ", key bits " << key_bits << ", direction bits " << direction_bits
                        << ", " << key_order_name(order) << ", lights " << lights;
                }
    }
}

std::vector<std::uint32_t> gpu_order(RaySorter& sorter, const std::vector<std::uint32_t>& keys, unsigned sort_bits,
                                     std::uint32_t first) {
    const Buffer buffer = Buffer::from(keys);
    Buffer order;
    sorter.sort_keys(buffer, keys.size(), sort_bits, first, order);
    EXPECT_EQ(buffer.download<std::uint32_t>(keys.size()), keys) << "the keys were changed";
    return order.download<std::uint32_t>(keys.size());
}

void expect_round_trip(const std::vector<std::uint32_t>& keys, const std::string& what) {
    RaySorter sorter;
    const std::uint32_t first = 17;
    const std::vector<std::uint32_t> order = gpu_order(sorter, keys, 32, first);
    EXPECT_EQ(order, sorted_order(keys, first)) << what << ", n = " << keys.size();
    EXPECT_EQ(sorter.chunk_count(), compress(keys).keys.size()) << what << ", n = " << keys.size();
    std::vector<std::uint32_t> seen = order;   // a permutation of first .. first + n - 1
    std::sort(seen.begin(), seen.end());
    for (std::size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], first + i) << what << ", n = " << keys.size();
}

// Lengths around the work group (256), one scan block (512) and a radix tile (4096), and several scan levels.
const std::size_t kLengths[] = {1, 2, 255, 257, 511, 513, 4097, 100003};

TEST(RaySorter, RandomKeysRoundTripLikeTheCpu) {
    gpu::test_context();
    std::mt19937 rng(11);
    for (std::size_t n : kLengths) {
        std::vector<std::uint32_t> keys(n);
        for (auto& k : keys) k = rng() % 64 == 0 ? std::uint32_t(rng()) : std::uint32_t(rng() % 50);
        for (std::size_t i = 0; i + 1 < n; i += 3) keys[i + 1] = keys[i];   // runs: chunks of several rays
        expect_round_trip(keys, "random");
    }
}

TEST(RaySorter, AllEqualKeysAreOneChunkInQueueOrder) {
    gpu::test_context();
    for (std::size_t n : kLengths) expect_round_trip(std::vector<std::uint32_t>(n, 0xabcdef12u), "all equal");
}

TEST(RaySorter, AllDistinctKeysAreOneChunkEach) {
    gpu::test_context();
    for (std::size_t n : kLengths) {
        std::vector<std::uint32_t> keys(n);
        for (std::size_t i = 0; i < n; ++i) keys[i] = std::uint32_t((n - i) * 2654435761u);   // distinct, unordered
        expect_round_trip(keys, "all distinct");
    }
}

TEST(RaySorter, RaysSortLikeTheCpuAndEachGroupKeepsItsQueueRange) {
    gpu::test_context();
    RaySorter sorter;
    sorter.layout = make_key_layout({-1, -1, -1}, {1, 1, 1}, 30, 12, 4);
    // A queue as the wavefront pipeline fills it: reflections, refractions, then shadow rays light by light; rays
    // come in runs of three equal ones (the coherence compression exploits).
    std::vector<gpu::WavefrontRay> rays = random_rays(20000, 5, 4);
    std::stable_sort(rays.begin(), rays.end(), [&](const auto& a, const auto& b) {
        return ray_group(a, sorter.layout) < ray_group(b, sorter.layout);
    });
    for (std::size_t i = 0; i < rays.size(); ++i)
        if (i % 3 != 0) rays[i] = rays[i - 1];
    const Buffer buffer = Buffer::from(rays);
    Buffer order;
    sorter.sort(buffer, 1000, 18000, order);
    const std::vector<std::uint32_t> got = order.download<std::uint32_t>(18000);
    const std::vector<std::uint32_t> keys = cpu_keys(rays, sorter.layout, 1000, 18000);
    EXPECT_EQ(got, sorted_order(keys, 1000));
    for (std::size_t i = 0; i < got.size(); ++i)
        ASSERT_EQ(ray_group(rays[got[i]], sorter.layout), ray_group(rays[1000 + i], sorter.layout)) << "slot " << i;
    EXPECT_EQ(sorter.chunk_count(), compress(keys).keys.size());
    EXPECT_LE(sorter.chunk_count(), std::size_t(6001));
}

// A sort reads nothing back (the chunk count stays on the GPU: the radix sort and the decompression read it there),
// and the chunk counts add up on the GPU in the tally slot of each sort, read once. Stale sizes and chunks past the
// count, left by a longer sort before, change nothing.
TEST(RaySorter, SortsReadNothingBackAndTallyTheirChunksOnTheGpu) {
    gpu::test_context();
    RaySorter sorter;
    std::mt19937 rng(3);
    std::array<std::uint64_t, RaySorter::kTallySlots> expected{};
    for (std::size_t n : {std::size_t(100003), std::size_t(5000), std::size_t(257), std::size_t(0), std::size_t(1)}) {
        std::vector<std::uint32_t> keys(n);
        for (auto& k : keys) k = std::uint32_t(rng() % 300);
        const Buffer buffer = Buffer::from(keys);
        Buffer order;
        sorter.tally_slot = n % RaySorter::kTallySlots;
        sorter.sort_keys(buffer, n, 32, 5, order);
        EXPECT_EQ(sorter.syncs, 0u) << "n = " << n << ": a sort read something back";
        if (n > 0) {
            EXPECT_EQ(order.download<std::uint32_t>(n), sorted_order(keys, 5)) << "n = " << n;
        }
        expected[n % RaySorter::kTallySlots] += compress(keys).keys.size();
    }
    EXPECT_EQ(sorter.chunk_tally(), expected);
    EXPECT_EQ(sorter.syncs, 1u);
    sorter.reset_tally();
    EXPECT_EQ(sorter.syncs, 0u) << "reset_tally() starts the count of read-backs again";
    EXPECT_EQ(sorter.chunk_tally(), (std::array<std::uint64_t, RaySorter::kTallySlots>{}));
    sorter.tally_slot = RaySorter::kTallySlots;
    const Buffer one = Buffer::from(std::vector<std::uint32_t>{1});
    Buffer order;
    EXPECT_THROW(sorter.sort_keys(one, 1, 32, 0, order), std::out_of_range);
}

}  // namespace
}  // namespace rt
