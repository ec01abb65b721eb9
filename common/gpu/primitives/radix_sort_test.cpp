// The GPU radix sort against std::stable_sort of (key, value) pairs by the sorted bits of the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <string>

#include "common/gpu/testing/gpu_test_context.h"
#include "radix_sort.h"

namespace rt::gpu {
namespace {

struct Pairs {
    std::vector<std::uint32_t> keys, values;
};

// values[i] = i, so the values show where each key came from (and that equal keys kept their order).
Pairs with_index_values(std::vector<std::uint32_t> keys) {
    Pairs p{std::move(keys), {}};
    p.values.resize(p.keys.size());
    std::iota(p.values.begin(), p.values.end(), 0u);
    return p;
}

std::vector<std::uint32_t> random_keys(std::size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::vector<std::uint32_t> v(n);
    for (auto& x : v) x = std::uint32_t(rng());
    return v;
}

Pairs cpu_stable_sort(const Pairs& in, unsigned key_bits) {
    const std::uint32_t mask = key_bits >= 32 ? 0xffffffffu : (1u << key_bits) - 1u;
    struct Element {
        std::uint32_t sort_key, key, value;
    };
    std::vector<Element> elements(in.keys.size());
    for (std::size_t i = 0; i < elements.size(); ++i) elements[i] = {in.keys[i] & mask, in.keys[i], in.values[i]};
    std::stable_sort(elements.begin(), elements.end(),
                     [](const Element& a, const Element& b) { return a.sort_key < b.sort_key; });
    Pairs out;
    out.keys.reserve(elements.size());
    out.values.reserve(elements.size());
    for (const Element& e : elements) out.keys.push_back(e.key), out.values.push_back(e.value);
    return out;
}

Pairs gpu_sort(RadixSort& sort, const Pairs& in, unsigned key_bits) {
    const std::size_t n = in.keys.size();
    Buffer keys = Buffer::from(in.keys), values = Buffer::from(in.values);
    sort.sort(keys, values, n, key_bits);
    return {keys.download<std::uint32_t>(n), values.download<std::uint32_t>(n)};
}

void expect_sorted_like_std(RadixSort& sort, const Pairs& in, unsigned key_bits, const std::string& what) {
    const Pairs expected = cpu_stable_sort(in, key_bits);
    const Pairs got = gpu_sort(sort, in, key_bits);
    EXPECT_EQ(got.keys, expected.keys) << what << ", n = " << in.keys.size() << ", key_bits = " << key_bits;
    EXPECT_EQ(got.values, expected.values) << what << ", n = " << in.keys.size() << ", key_bits = " << key_bits;
}

// Lengths around the work group (64 threads), 256 and tile (kSortTile = 4096) sizes, many tiles with a partial last
// one, and around the most tiles whose counts the scatter scans itself (kScatterScanTiles; above it, the scan's pass).
const std::size_t kLengths[] = {2, 3, 63, 64, 65, 255, 256, 257, 4095, 4096, 4097, 100003,
                                kScatterScanTiles * kSortTile, kScatterScanTiles * kSortTile + 1};

TEST(GpuRadixSort, RandomKeysMatchStdStableSort) {
    test_context();
    RadixSort sort;
    for (std::size_t n : kLengths)
        expect_sorted_like_std(sort, with_index_values(random_keys(n, unsigned(n))), 32, "random");
}

TEST(GpuRadixSort, AllEqualSortedAndReverseSortedKeys) {
    test_context();
    RadixSort sort;
    for (std::size_t n : {std::size_t(4097), std::size_t(70001)}) {
        expect_sorted_like_std(sort, with_index_values(std::vector<std::uint32_t>(n, 0xdeadbeefu)), 32, "all equal");
        std::vector<std::uint32_t> ascending(n);
        for (std::size_t i = 0; i < n; ++i) ascending[i] = std::uint32_t(i * 2654435761u % 0xfffffffbu);   // distinct
        std::sort(ascending.begin(), ascending.end());
        expect_sorted_like_std(sort, with_index_values(ascending), 32, "sorted");
        std::reverse(ascending.begin(), ascending.end());
        expect_sorted_like_std(sort, with_index_values(ascending), 32, "reverse sorted");
    }
}

// key_bits < 32 sorts by the low bits only: the high bits ride along and equal low bits keep their order. Counts of
// bits that are not a multiple of kRadixBits (6) make the last pass narrower, and an odd count of passes (1, 3, 5)
// ends in the scratch buffers.
TEST(GpuRadixSort, KeyBitsSortOnlyTheLowBits) {
    test_context();
    RadixSort sort;
    const Pairs in = with_index_values(random_keys(50001, 5));
    for (unsigned key_bits : {1u, 3u, 4u, 6u, 7u, 8u, 12u, 17u, 30u, 31u})
        expect_sorted_like_std(sort, in, key_bits, "random high bits");
    // Keys using only some bits, sorted by all 32.
    Pairs few = in;
    for (auto& k : few.keys) k &= 0x00f000f0u;
    expect_sorted_like_std(sort, few, 32, "keys in bits 4-7 and 20-23");
}

TEST(GpuRadixSort, LengthsZeroAndOneAndKeyBitsZeroLeaveTheBuffers) {
    test_context();
    RadixSort sort;
    Buffer keys = Buffer::from(std::vector<std::uint32_t>{7, 3});
    Buffer values = Buffer::from(std::vector<std::uint32_t>{1, 2});
    sort.sort(keys, values, 0);
    sort.sort(keys, values, 1);
    sort.sort(keys, values, 2, 0);
    EXPECT_EQ(keys.download<std::uint32_t>(2), (std::vector<std::uint32_t>{7, 3}));
    EXPECT_EQ(values.download<std::uint32_t>(2), (std::vector<std::uint32_t>{1, 2}));
    sort.sort(keys, values, 2);
    EXPECT_EQ(keys.download<std::uint32_t>(2), (std::vector<std::uint32_t>{3, 7}));
    EXPECT_EQ(values.download<std::uint32_t>(2), (std::vector<std::uint32_t>{2, 1}));
    EXPECT_THROW(sort.sort(keys, values, 3), std::out_of_range);
    EXPECT_THROW(sort.sort(keys, values, 2, 33), std::invalid_argument);
    EXPECT_THROW(sort.sort(keys, keys, 2), std::invalid_argument);
}

// Arrays larger than a window are bound window by window; small windows make that path cheap to test.
TEST(GpuRadixSort, WindowsSmallerThanTheArrayGiveTheSameOrder) {
    test_context();
    RadixSort sort;
    sort.set_window_for_testing(2 * kSortTile);
    for (std::size_t n : {std::size_t(4 * kSortTile), std::size_t(10 * kSortTile + 5)})
        expect_sorted_like_std(sort, with_index_values(random_keys(n, 9)), 32, "windows of two tiles");
}

// With the count on the GPU (n only a bound), the first `count` elements come out as std::stable_sort orders them,
// whatever the elements after them hold: counts of 0, 1, inside the first tile, on tile and window edges, and n.
// The keys after the count are 0: had they taken part, they would have come first. Both ways of placing the keys:
// windows of two tiles (the scan's pass), and one window of 5 tiles (the scatter sums the counts itself).
TEST(GpuRadixSort, CountOnTheGpuSortsOnlyThatPrefix) {
    test_context();
    RadixSort sort;
    const std::size_t n = 5 * kSortTile + 17;
    const Pairs all = with_index_values(random_keys(n, 11));
    for (std::size_t window : {2 * kSortTile, std::size_t(0)}) {
        sort.set_window_for_testing(window);
        const std::string how = window ? "windows of 2 tiles" : "one window";
        for (std::size_t count : {std::size_t(0), std::size_t(1), std::size_t(300), kSortTile, 2 * kSortTile + 1,
                                  4 * kSortTile - 1, n}) {
            for (unsigned key_bits : {32u, 7u}) {
                Pairs in = all;
                for (std::size_t i = count; i < n; ++i) in.keys[i] = 0u;   // would come first if sorted
                Buffer keys = Buffer::from(in.keys), values = Buffer::from(in.values);
                const Buffer gpu_count = Buffer::from(std::vector<std::uint32_t>{std::uint32_t(count)});
                sort.sort(keys, values, n, gpu_count, key_bits);
                const Pairs prefix{{in.keys.begin(), in.keys.begin() + std::ptrdiff_t(count)},
                                   {in.values.begin(), in.values.begin() + std::ptrdiff_t(count)}};
                const Pairs expected = cpu_stable_sort(prefix, key_bits);
                std::vector<std::uint32_t> got_keys = keys.download<std::uint32_t>(n);
                std::vector<std::uint32_t> got_values = values.download<std::uint32_t>(n);
                got_keys.resize(count);
                got_values.resize(count);
                const std::string what =
                    how + ", count " + std::to_string(count) + " of " + std::to_string(n) + ", key_bits " +
                    std::to_string(key_bits);
                EXPECT_EQ(got_keys, expected.keys) << what;
                EXPECT_EQ(got_values, expected.values) << what;
            }
        }
    }
    Buffer keys = Buffer::from(all.keys), values = Buffer::from(all.values);
    EXPECT_THROW(sort.sort(keys, values, n, Buffer(), 32), std::out_of_range);
}

// Arrays of at most one tile are sorted by one work group in one dispatch (radix_tile.comp), every pass there: the
// same order as std::stable_sort for every key width (an odd number of passes ends in the scratch buffers and is
// copied back; a last pass narrower than 6 bits), at the tile's edge and below, and with the count on the GPU.
TEST(GpuRadixSort, OneTileIsSortedByOneWorkGroupInEveryPass) {
    test_context();
    RadixSort sort;
    for (std::size_t n : {std::size_t(2), std::size_t(1000), kSortTile - 1, kSortTile})
        for (unsigned key_bits : {1u, 5u, 6u, 7u, 12u, 18u, 29u, 30u, 31u, 32u})
            expect_sorted_like_std(sort, with_index_values(random_keys(n, unsigned(n) + key_bits)), key_bits,
                                   "one tile");
    // Many equal keys in one tile: their order is their runs' order across the group's threads.
    std::vector<std::uint32_t> few(kSortTile);
    for (std::size_t i = 0; i < few.size(); ++i) few[i] = std::uint32_t(i * 7919u % 5u);
    expect_sorted_like_std(sort, with_index_values(few), 32, "five keys");
    const std::size_t n = kSortTile;
    const Pairs all = with_index_values(random_keys(n, 23));
    for (std::size_t count : {std::size_t(0), std::size_t(1), std::size_t(300), n - 1, n}) {
        for (unsigned key_bits : {32u, 7u}) {
            Pairs in = all;
            for (std::size_t i = count; i < n; ++i) in.keys[i] = 0u;   // would come first if sorted
            Buffer keys = Buffer::from(in.keys), values = Buffer::from(in.values);
            sort.sort(keys, values, n, Buffer::from(std::vector<std::uint32_t>{std::uint32_t(count)}), key_bits);
            const Pairs expected = cpu_stable_sort({{in.keys.begin(), in.keys.begin() + std::ptrdiff_t(count)},
                                                    {in.values.begin(), in.values.begin() + std::ptrdiff_t(count)}},
                                                   key_bits);
            std::vector<std::uint32_t> got_keys = keys.download<std::uint32_t>(n);
            std::vector<std::uint32_t> got_values = values.download<std::uint32_t>(n);
            got_keys.resize(count);
            got_values.resize(count);
            const std::string what = "count " + std::to_string(count) + ", key_bits " + std::to_string(key_bits);
            EXPECT_EQ(got_keys, expected.keys) << what;
            EXPECT_EQ(got_values, expected.values) << what;
        }
    }
}

// Over 2^25 elements: on llvmpipe (128 MiB storage blocks) the arrays are two windows of the real limit. One pass
// (key_bits 4) keeps the run time reasonable on llvmpipe; the windows' other paths are tested above.
TEST(GpuRadixSort, OverTwoToThe25Elements) {
    test_context();
    RadixSort sort;
    const std::size_t n = (std::size_t(1) << 25) + 3;
    expect_sorted_like_std(sort, with_index_values(random_keys(n, 25)), 4, "2^25 + 3");
}

}  // namespace
}  // namespace rt::gpu
