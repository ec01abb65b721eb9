// The GPU exclusive scan and stream compaction against std::exclusive_scan / a CPU filter on random arrays.
#include <gtest/gtest.h>

#include <numeric>
#include <random>

#include "gpu_test_context.h"
#include "scan.h"

namespace rt::gpu {
namespace {

const std::size_t kSizes[] = {1, 255, 256, 257, 511, 512, 513, 100000, 262145};   // 262145: three levels

std::vector<std::uint32_t> random_values(std::size_t n, std::uint32_t max, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::uint32_t> d(0, max);
    std::vector<std::uint32_t> v(n);
    for (auto& x : v) x = d(rng);
    return v;
}

TEST(GpuScan, ExclusiveMatchesStd) {
    test_context();
    Scan scan;
    Buffer total(8);
    for (std::size_t n : kSizes) {
        const auto values = random_values(n, 1000, unsigned(n));
        std::vector<std::uint32_t> expected(n);
        std::exclusive_scan(values.begin(), values.end(), expected.begin(), 0u);
        Buffer in = Buffer::from(values), out(n * 4);
        scan.exclusive(in, out, n, &total, 4);
        EXPECT_EQ(out.download<std::uint32_t>(n), expected) << "n = " << n;
        EXPECT_EQ(total.download_value<std::uint32_t>(1), expected.back() + values.back()) << "n = " << n;
        // In place.
        scan.exclusive(in, in, n);
        EXPECT_EQ(in.download<std::uint32_t>(n), expected) << "in place, n = " << n;
    }
}

TEST(GpuScan, WrapsLikeUint32AndHandlesZeroLength) {
    test_context();
    Scan scan;
    std::vector<std::uint32_t> values(1000, 0x01000000u);   // sums wrap past 2^32
    std::vector<std::uint32_t> expected(values.size());
    std::exclusive_scan(values.begin(), values.end(), expected.begin(), 0u);
    Buffer in = Buffer::from(values), out(values.size() * 4), total(4);
    scan.exclusive(in, out, values.size(), &total);
    EXPECT_EQ(out.download_all<std::uint32_t>(), expected);
    total.clear_u32(99);
    scan.exclusive(in, out, 0, &total);
    EXPECT_EQ(total.download_value<std::uint32_t>(), 0u);
}

TEST(GpuCompaction, IndicesAndValuesMatchCpuFilter) {
    test_context();
    Compaction compaction;
    Buffer count(4);
    for (std::size_t n : kSizes) {
        const auto values = random_values(n, 0xffffffffu, unsigned(n) + 7);
        std::vector<std::uint32_t> flags(n);
        for (std::size_t i = 0; i < n; ++i) flags[i] = (values[i] % 3 == 0) ? (values[i] | 1u) : 0u;   // any nonzero
        std::vector<std::uint32_t> expected_indices, expected_values;
        for (std::size_t i = 0; i < n; ++i)
            if (flags[i]) expected_indices.push_back(std::uint32_t(i)), expected_values.push_back(values[i]);
        Buffer flag_buffer = Buffer::from(flags), value_buffer = Buffer::from(values), out(n * 4);
        compaction.compact_indices(flag_buffer, n, out, count);
        const auto k = count.download_value<std::uint32_t>();
        ASSERT_EQ(k, expected_indices.size()) << "n = " << n;
        EXPECT_EQ(out.download<std::uint32_t>(k), expected_indices) << "n = " << n;
        compaction.compact_values(value_buffer, flag_buffer, n, out, count);
        EXPECT_EQ(out.download<std::uint32_t>(count.download_value<std::uint32_t>()), expected_values) << "n = " << n;
    }
}

}  // namespace
}  // namespace rt::gpu
