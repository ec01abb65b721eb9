// The GPU scans (exclusive, inclusive, segmented) and stream compaction against std::exclusive_scan,
// std::inclusive_scan, a CPU segmented sum and a CPU filter on random arrays.
#include <gtest/gtest.h>

#include <numeric>
#include <random>

#include "common/gpu/testing/gpu_test_context.h"
#include "scan.h"
#include "common/gpu/gl/storage_limit.h"

namespace rt::gpu {
namespace {

// 7, 8, 9: one thread's run of scan_block.comp and the next; 511-513: a block's; 4095-4097: the most elements one
// work group scans whole (kScanWhole), and one more (a block pass, the block totals whole); 2097153: three levels
// (4097 block totals, too many to scan whole).
const std::size_t kSizes[] = {1, 7, 8, 9, 255, 256, 257, 511, 512, 513, 4095, 4096, 4097, 100000, 262145, 2097153};

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

TEST(GpuScan, InclusiveMatchesStd) {
    test_context();
    Scan scan;
    Buffer total(4);
    for (std::size_t n : kSizes) {
        const auto values = random_values(n, 1000, unsigned(n) + 1);
        std::vector<std::uint32_t> expected(n);
        std::inclusive_scan(values.begin(), values.end(), expected.begin());
        Buffer in = Buffer::from(values), out(n * 4);
        scan.inclusive(in, out, n, &total);
        EXPECT_EQ(out.download<std::uint32_t>(n), expected) << "n = " << n;
        EXPECT_EQ(total.download_value<std::uint32_t>(), expected.back()) << "n = " << n;
        scan.inclusive(in, in, n);
        EXPECT_EQ(in.download<std::uint32_t>(n), expected) << "in place, n = " << n;
    }
}

std::vector<std::uint32_t> cpu_segmented_inclusive(const std::vector<std::uint32_t>& values,
                                                   const std::vector<std::uint32_t>& heads) {
    std::vector<std::uint32_t> out(values.size());
    std::uint32_t sum = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (heads[i]) sum = 0;
        sum += values[i];
        out[i] = sum;
    }
    return out;
}

void expect_segmented_like_cpu(Scan& scan, const std::vector<std::uint32_t>& values,
                               const std::vector<std::uint32_t>& heads, const std::string& what) {
    const std::size_t n = values.size();
    const auto expected = cpu_segmented_inclusive(values, heads);
    Buffer in = Buffer::from(values), head_buffer = Buffer::from(heads), out(n * 4);
    scan.segmented_inclusive(in, head_buffer, out, n);
    EXPECT_EQ(out.download<std::uint32_t>(n), expected) << what << ", n = " << n;
    scan.segmented_inclusive(in, head_buffer, in, n);
    EXPECT_EQ(in.download<std::uint32_t>(n), expected) << what << ", in place, n = " << n;
}

TEST(GpuScan, SegmentedInclusiveMatchesCpu) {
    test_context();
    Scan scan;
    for (std::size_t n : kSizes) {
        const auto values = random_values(n, 0xffffffffu, unsigned(n) + 2);   // sums wrap: still exact
        auto heads = random_values(n, 40, unsigned(n) + 3);
        for (auto& h : heads) h = h == 0 ? 7u : 0u;   // about one head in 41, any nonzero value
        expect_segmented_like_cpu(scan, values, heads, "random heads");
        heads[0] = 1;
        expect_segmented_like_cpu(scan, values, heads, "a head at 0");
        expect_segmented_like_cpu(scan, values, std::vector<std::uint32_t>(n, 0), "no heads");
        expect_segmented_like_cpu(scan, values, std::vector<std::uint32_t>(n, 1), "all heads");
    }
}

void expect_exclusive_and_inclusive_like_std(Scan& scan, const std::vector<std::uint32_t>& values) {
    const std::size_t n = values.size();
    std::vector<std::uint32_t> exclusive(n), inclusive(n);
    std::exclusive_scan(values.begin(), values.end(), exclusive.begin(), 0u);
    std::inclusive_scan(values.begin(), values.end(), inclusive.begin());
    Buffer in = Buffer::from(values), out(n * 4), total(4);
    scan.exclusive(in, out, n, &total);
    EXPECT_EQ(out.download<std::uint32_t>(n), exclusive) << "n = " << n;
    EXPECT_EQ(total.download_value<std::uint32_t>(), inclusive.back()) << "n = " << n;
    scan.inclusive(in, in, n);
    EXPECT_EQ(in.download<std::uint32_t>(n), inclusive) << "in place, n = " << n;
}

// Arrays larger than a window are bound window by window; small windows make that path cheap to test.
TEST(GpuScan, WindowsSmallerThanTheArrayGiveTheSameSums) {
    test_context();
    Scan scan;
    scan.set_window_for_testing(2 * kScanBlock);
    for (std::size_t n : {std::size_t(1000), std::size_t(1024), std::size_t(300001)})
        expect_exclusive_and_inclusive_like_std(scan, random_values(n, 1000, unsigned(n) + 4));
}

// Over 2^25 elements: on llvmpipe (128 MiB storage blocks) two windows, the first of 65536 blocks of 512, one
// more than a 1D grid holds, so its block passes run on a 2D grid. (Only the exclusive scan, for the run time on
// llvmpipe: the inclusive one differs in the block shader's last line, tested above.)
TEST(GpuScan, OverTwoToThe25ElementsUseWindowsAndA2DGrid) {
    test_context();
    Scan scan;
    const std::size_t n = (std::size_t(1) << 25) + 3;
    const auto values = random_values(n, 3, 25);
    std::vector<std::uint32_t> expected(n);
    std::exclusive_scan(values.begin(), values.end(), expected.begin(), 0u);
    Buffer in = Buffer::from(values), out(n * 4), total(4);
    scan.exclusive(in, out, n, &total);
    EXPECT_EQ(out.download<std::uint32_t>(n), expected);
    EXPECT_EQ(total.download_value<std::uint32_t>(), expected.back() + values.back());
}

// The segmented scan and the compaction read or write anywhere in their arrays: one storage block at most.
TEST(GpuScan, SegmentedAndCompactionBeyondTheStorageBlockLimitAreAOneLineError) {
    test_context();
    Scan scan;
    Compaction compaction;
    Buffer small(16);
    const std::size_t n = max_storage_block_bytes() / 4 + 1;
    for (int k = 0; k < 2; ++k) {
        try {
            if (k == 0) scan.segmented_inclusive(small, small, small, n);
            else compaction.compact_indices(small, n, small, small);
            FAIL() << "no error for " << n << " elements";
        } catch (const std::length_error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE"), std::string::npos) << message;
            EXPECT_NE(message.find(std::to_string(n)), std::string::npos) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        }
    }
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
