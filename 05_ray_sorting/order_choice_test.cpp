// --sort auto's choice (order_choice.h): the GPU's width sums against the CPU twin's, and the order it leaves.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <tuple>

#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/pipeline/wavefront.h"
#include "order_choice.h"

namespace rt {
namespace {

using gpu::Buffer;

std::vector<OrderRay> order_rays(const std::vector<gpu::WavefrontRay>& rays) {
    std::vector<OrderRay> out;
    for (const gpu::WavefrontRay& r : rays) out.push_back({r.origin, r.direction, r.tmax});
    return out;
}

gpu::WavefrontRay ray(glm::vec3 origin, glm::vec3 direction, float tmax) {
    gpu::WavefrontRay r{};
    r.origin = origin;
    r.direction = direction;
    r.tmax = tmax;
    return r;
}

struct Case {
    std::string name;
    std::vector<gpu::WavefrontRay> rays;   // the whole queue; the batch is [first, first + count)
    std::size_t first = 0;
    std::vector<std::uint32_t> sorted;     // the batch's sorted order (queue indices)
};

// Two clusters far apart, interleaved in the queue: sorting them apart makes every node tight.
Case interleaved_clusters() {
    Case c{"interleaved clusters", {}, 5, {}};
    for (int i = 0; i < 5; ++i) c.rays.push_back(ray({9, 9, 9}, {1, 0, 0}, 1.0f));   // before the batch
    for (int i = 0; i < 64; ++i)
        c.rays.push_back(ray(i % 2 ? glm::vec3(-1 + 0.001f * i, 0, 0) : glm::vec3(1, 0.001f * i, 0),
                             i % 2 ? glm::vec3(0, 1, 0) : glm::vec3(0, -1, 0.1f), INFINITY));
    for (std::uint32_t i = 0; i < 64; i += 2) c.sorted.push_back(std::uint32_t(c.first) + i);
    for (std::uint32_t i = 1; i < 64; i += 2) c.sorted.push_back(std::uint32_t(c.first) + i);
    return c;
}

// A coherent queue (a row of parallel rays) and a "sorted" order that scatters it: the queue's order stays.
Case scrambled_row() {
    Case c{"scrambled row", {}, 0, {}};
    for (int i = 0; i < 1000; ++i) c.rays.push_back(ray({0.01f * i, 0, 0}, {0, 0, 1}, 2.0f));
    c.sorted.resize(1000);
    std::iota(c.sorted.begin(), c.sorted.end(), 0u);
    std::mt19937 rng(3);
    std::shuffle(c.sorted.begin(), c.sorted.end(), rng);
    return c;
}

// Adversarial rays: zero, NaN and infinite directions and origins, huge and tiny scales, negative and NaN tmax,
// a count that leaves a last node of fewer than B rays; the "sorted" order reversed.
Case adversarial() {
    Case c{"adversarial", {}, 3, {}};
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = INFINITY;
    std::mt19937 rng(7);
    std::normal_distribution<float> normal;
    for (int i = 0; i < 3 + 1001; ++i) {
        glm::vec3 o{normal(rng), normal(rng), normal(rng)}, d{normal(rng), normal(rng), normal(rng)};
        float tmax = i % 3 ? inf : std::abs(normal(rng));
        switch (i % 11) {
            case 0: d = {0, 0, 0}; break;
            case 1: d.x = nan; break;
            case 2: o.y = inf; break;
            case 3: o *= 1e30f; break;
            case 4: d *= 1e-30f; break;
            case 5: tmax = -1.0f; break;
            case 6: tmax = nan; break;
            case 7: d *= 1e30f; tmax = 1e30f; break;
            default: break;
        }
        c.rays.push_back(ray(o, d, tmax));
    }
    for (std::uint32_t i = 0; i < 1001; ++i) c.sorted.push_back(std::uint32_t(c.first) + 1000 - i);
    return c;
}

// The GPU's sums equal the CPU twin's up to the rounding of sin (GPU and CPU may differ in the last ulp, which can
// move a node's width across a unit: at most one unit per node), and the order it leaves is the one the twin
// chooses wherever the two sums are further apart than that.
TEST(GpuOrderChoice, SumsAndChoiceMatchTheCpuTwin) {
    gpu::test_context();
    GpuOrderChoice choice;
    for (const Case& c : {interleaved_clusters(), scrambled_row(), adversarial()}) {
        for (int branching : {4, 8, 16}) {
            for (float diagonal : {1.0f, 3.0f, 1e-3f}) {
                const std::size_t n = c.sorted.size();
                const std::vector<gpu::WavefrontRay> batch(c.rays.begin() + std::ptrdiff_t(c.first),
                                                           c.rays.begin() + std::ptrdiff_t(c.first + n));
                std::vector<std::uint32_t> local(n);
                for (std::size_t i = 0; i < n; ++i) local[i] = c.sorted[i] - std::uint32_t(c.first);
                const std::uint64_t queue = order_cost(order_rays(batch), {}, branching, diagonal);
                const std::uint64_t sorted = order_cost(order_rays(batch), local, branching, diagonal);

                const Buffer rays = Buffer::from(c.rays);
                Buffer order = Buffer::from(c.sorted);
                choice.choose({}, rays, c.first, n, order, nullptr, branching, diagonal, 0);
                const auto [gpu_queue, gpu_sorted, unused] = choice.last_costs();
                const std::uint64_t nodes = (n + std::size_t(branching) - 1) / std::size_t(branching);
                const std::string what = c.name + ", B " + std::to_string(branching) + ", diagonal " +
                                         std::to_string(diagonal);
                EXPECT_LE(std::max(gpu_queue, queue) - std::min(gpu_queue, queue), nodes) << what;
                EXPECT_LE(std::max(gpu_sorted, sorted) - std::min(gpu_sorted, sorted), nodes) << what;
                std::vector<std::uint32_t> queue_order(n);
                std::iota(queue_order.begin(), queue_order.end(), std::uint32_t(c.first));
                const std::vector<std::uint32_t> left = order.download<std::uint32_t>(n);
                EXPECT_EQ(left, keep_sorted_order(gpu_queue, gpu_sorted) ? c.sorted : queue_order) << what;
                if (std::max(queue, sorted) - std::min(queue, sorted) > 2 * nodes) {
                    EXPECT_EQ(keep_sorted_order(gpu_queue, gpu_sorted), keep_sorted_order(queue, sorted)) << what;
                }
            }
        }
    }
}

// The cases are what they claim: interleaved clusters are sorted apart, a scrambled row keeps the queue's order.
TEST(GpuOrderChoice, KeepsATighterSortAndRefusesAWiderOne) {
    gpu::test_context();
    GpuOrderChoice choice;
    for (auto [c, keep] : {std::pair{interleaved_clusters(), true}, {scrambled_row(), false}}) {
        const Buffer rays = Buffer::from(c.rays);
        Buffer order = Buffer::from(c.sorted);
        choice.reset_tally();
        choice.choose({}, rays, c.first, c.sorted.size(), order, nullptr, 4, 3.0f, 1);
        const auto [queue, sorted, unused] = choice.last_costs();
        EXPECT_EQ(sorted < queue, keep) << c.name << ": queue " << queue << ", sorted " << sorted;
        EXPECT_EQ(choice.tally().kept[1].batches, keep ? 1u : 0u) << c.name;
        EXPECT_EQ(choice.tally().kept[1].rays, keep ? c.sorted.size() : 0u) << c.name;
        EXPECT_EQ(choice.tally().kept[0].batches, 0u) << c.name << ": the trace batches' tally is apart";
    }
}

// Two sorted orders (a reflection batch's coarse and fine direction cells): the tightest wins if it beats the queue by
// the margin, whichever it is; the order left in `order` is that one, and the tally says which.
TEST(GpuOrderChoice, OfTwoSortedOrdersTheTighterIsKept) {
    gpu::test_context();
    GpuOrderChoice choice;
    const Case clusters = interleaved_clusters();
    const std::size_t n = clusters.sorted.size();
    std::vector<std::uint32_t> queue_order(n), reversed(clusters.sorted.rbegin(), clusters.sorted.rend());
    std::iota(queue_order.begin(), queue_order.end(), std::uint32_t(clusters.first));
    std::vector<std::uint32_t> scrambled = queue_order;
    std::shuffle(scrambled.begin(), scrambled.end(), std::mt19937(5));
    const Buffer rays = Buffer::from(clusters.rays);
    struct Try {
        std::vector<std::uint32_t> coarse, fine;
        int expected;   // -1: either sorted order (both tight)
    };
    for (const Try& t : {Try{scrambled, clusters.sorted, 2}, Try{clusters.sorted, scrambled, 1},
                         Try{clusters.sorted, reversed, -1}}) {
        Buffer order = Buffer::from(t.coarse);
        const Buffer fine = Buffer::from(t.fine);
        choice.reset_tally();
        choice.choose({}, rays, clusters.first, n, order, &fine, 4, 3.0f, 0);
        const auto [queue, coarse, fine_cost] = choice.last_costs();
        const int expected = choose_order(queue, coarse, fine_cost);
        if (t.expected >= 0) {
            EXPECT_EQ(expected, t.expected);
        }
        EXPECT_NE(expected, 0) << "a clustered order beats the interleaved queue";
        EXPECT_EQ(order.download<std::uint32_t>(n), expected == 0 ? queue_order : expected == 1 ? t.coarse : t.fine);
        EXPECT_EQ(choice.tally().kept[0].fine_batches, expected == 2 ? 1u : 0u);
        EXPECT_EQ(choice.tally().kept[0].batches, expected == 0 ? 0u : 1u);
    }
    EXPECT_EQ(choose_order(100, 50, 40), 2);
    EXPECT_EQ(choose_order(100, 40, 40), 1) << "a tie goes to the coarse key";
    EXPECT_EQ(choose_order(100, 99, 98), 0) << "neither beats the queue by the margin";
    EXPECT_EQ(choose_order(100, 50), 1);
}

// The check's rule: a sort stays only where the pairs it saved exceed its cost, batch_cost + ray_cost x rays.
TEST(OrderChoice, ASortStaysOnlyWhereThePairsItSavesPayForIt) {
    EXPECT_TRUE(sort_pays(1000, 999, 500, 0, 0)) << "no cost: any saving";
    EXPECT_FALSE(sort_pays(1000, 1000, 500, 0, 0)) << "a tie is no saving";
    EXPECT_FALSE(sort_pays(999, 1000, 500, 0, 0)) << "a loss";
    EXPECT_FALSE(sort_pays(10000, 4000, 1000, 4000, 2)) << "saves 6000, costs 4000 + 2 x 1000";
    EXPECT_TRUE(sort_pays(10000, 3999, 1000, 4000, 2)) << "saves 6001";
    EXPECT_FALSE(sort_pays(10000, 3999, 1001, 4000, 2)) << "one ray more costs 2 more";
    EXPECT_FALSE(sort_pays(0, 0, 0, 0, 0));
    EXPECT_FALSE(sort_pays(UINT64_MAX, 0, 0, UINT64_MAX, 0)) << "the largest saving against the largest cost";
    EXPECT_TRUE(sort_pays(UINT64_MAX, 0, 0, UINT64_MAX - 1, 0));
}

// Equal sums, and a sort tighter by 1/32 or less, keep the queue's order (a sort that gains that little is not worth
// its passes); huge sums compare exactly.
TEST(OrderChoice, ATieOrASmallGainKeepsTheQueuesOrder) {
    EXPECT_FALSE(keep_sorted_order(3200, 3200));
    EXPECT_FALSE(keep_sorted_order(3200, 3100));   // exactly 1/32 tighter
    EXPECT_TRUE(keep_sorted_order(3200, 3099));
    EXPECT_FALSE(keep_sorted_order(3099, 3200));
    EXPECT_FALSE(keep_sorted_order(0, 0));
    const std::uint64_t big = std::uint64_t(1) << 45;
    EXPECT_FALSE(keep_sorted_order(big * 32, big * 31));
    EXPECT_TRUE(keep_sorted_order(big * 32, big * 31 - 1));
}

// Widths: empty nodes 0, every direction and NaN the widest, a ray's length cut to the diagonal.
TEST(OrderChoice, WidthsOfEmptyAllDirectionAndLongNodes) {
    RhNode empty;
    EXPECT_EQ(order_fixed_width(empty, 1.0f, 1.0f), 0u);
    RhNode all;
    all.sphere = {0, 0, 0, 0};
    all.cone = {1, 0, 0, 3.14159274f};
    EXPECT_EQ(order_fixed_width(all, 1.0f, 1.0f), std::uint32_t(kOrderMaxWidth * kOrderWidthUnits));
    RhNode nan_radius;
    nan_radius.sphere = {0, 0, 0, 0};
    nan_radius.cone = {1, 0, 0, std::numeric_limits<float>::quiet_NaN()};
    EXPECT_EQ(order_fixed_width(nan_radius, 1.0f, 1.0f), std::uint32_t(kOrderMaxWidth * kOrderWidthUnits));
    RhNode narrow;
    narrow.sphere = {0, 0, 0, 0.5f};
    narrow.cone = {1, 0, 0, 0.0f};
    EXPECT_EQ(order_fixed_width(narrow, INFINITY, 2.0f), 1024u);   // 0.5 of a diagonal of 2: a quarter
    narrow.cone.w = 0.1f;
    const float reach = kOrderReach * 2.0f;
    EXPECT_EQ(order_fixed_width(narrow, 1e30f, 2.0f), order_fixed_width(narrow, reach, 2.0f)) << "cut to the reach";
    EXPECT_LT(order_fixed_width(narrow, 0.5f * reach, 2.0f), order_fixed_width(narrow, reach, 2.0f))
        << "a short ray is narrower";
}

// The cap: the leaves' mean diameter in width units, each radius rounded down; empty and NaN spheres count 0, a
// huge one at most kOrderMaxWidth; no leaves, no cap.
TEST(OrderChoice, TheWidthCapIsTheLeavesMeanDiameter) {
    EXPECT_EQ(order_width_cap(std::vector<glm::vec4>{}, 1.0f), kOrderNoCap);
    EXPECT_EQ(order_width_cap(0, 0), kOrderNoCap);
    // Radii of 1/64 and 3/64 of a diagonal of 2 (64 and 192 units): mean diameter 256.
    EXPECT_EQ(order_width_cap({{0, 0, 0, 1.0f / 32}, {5, 0, 0, 3.0f / 32}}, 2.0f), 256u);
    EXPECT_EQ(order_radius_units(-1.0f, 1.0f), 0u);
    EXPECT_EQ(order_radius_units(std::numeric_limits<float>::quiet_NaN(), 1.0f), 0u);
    EXPECT_EQ(order_radius_units(1e30f, 1.0f), kOrderNoCap);
    EXPECT_EQ(order_width_cap({{0, 0, 0, -1.0f}, {0, 0, 0, 0.25f}}, 1.0f), 1024u) << "an empty leaf counts 0";
    EXPECT_EQ(order_width_cap({{0, 0, 0, 1e30f}}, 1.0f), kOrderNoCap);
}

// Leaf spheres of `radius` (the scene's clusters or triangles), one every `stride` vec4s as in the hierarchy's buffers.
std::vector<glm::vec4> leaf_buffer(std::size_t count, std::uint32_t stride, float radius,
                                   std::vector<glm::vec4>* spheres) {
    std::vector<glm::vec4> data(count * stride, glm::vec4(7.0f));   // the other words of a node: never read
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.5f, 1.5f);
    for (std::size_t i = 0; i < count; ++i) {
        data[i * stride] = glm::vec4(float(i), 0.0f, 0.0f, radius * u(rng));
        spheres->push_back(data[i * stride]);
    }
    return data;
}

// With leaves set, the GPU measures their cap once and caps every node's width: its cap and sums are the CPU twin's
// (up to one unit per leaf radius and per node for the GPU's division and sin), and the choice follows. Interleaved
// clusters: the queue's nodes are wide, the sorted ones tight; against leaves as large as the clusters' gap the sort
// is kept, against tiny leaves (every node wider than them: each is split into its rays at once) the widths are all
// capped alike and the queue's order stays.
TEST(GpuOrderChoice, NodesCountOnlyUpToTheLeavesDiameter) {
    gpu::test_context();
    const Case c = interleaved_clusters();
    const std::size_t n = c.sorted.size();
    const std::vector<gpu::WavefrontRay> batch(c.rays.begin() + std::ptrdiff_t(c.first),
                                               c.rays.begin() + std::ptrdiff_t(c.first + n));
    std::vector<std::uint32_t> local(n);
    for (std::size_t i = 0; i < n; ++i) local[i] = c.sorted[i] - std::uint32_t(c.first);
    const float diagonal = 3.0f;
    for (auto [radius, stride, keep] : {std::tuple{1.0f, 4u, true}, {1e-3f, 1u, false}, {1e-3f, 4u, false}}) {
        std::vector<glm::vec4> spheres;
        const Buffer leaves = Buffer::from(leaf_buffer(1000, stride, radius, &spheres));
        GpuOrderChoice choice;
        choice.set_leaves(leaves, 1000, stride);
        const Buffer rays = Buffer::from(c.rays);
        Buffer order = Buffer::from(c.sorted);
        choice.choose({}, rays, c.first, n, order, nullptr, 4, diagonal, 1);
        const std::uint32_t cap = order_width_cap(spheres, diagonal);
        const std::string what = "leaf radius " + std::to_string(radius) + ", stride " + std::to_string(stride);
        EXPECT_LE(std::max(choice.width_cap(), cap) - std::min(choice.width_cap(), cap), 2u) << what;
        const auto [gpu_queue, gpu_sorted, unused] = choice.last_costs();
        const std::uint64_t queue = order_cost(order_rays(batch), {}, 4, diagonal, cap);
        const std::uint64_t sorted = order_cost(order_rays(batch), local, 4, diagonal, cap);
        const std::uint64_t nodes = (n + 3) / 4;
        EXPECT_LE(std::max(gpu_queue, queue) - std::min(gpu_queue, queue), 2 * nodes) << what;
        EXPECT_LE(std::max(gpu_sorted, sorted) - std::min(gpu_sorted, sorted), 2 * nodes) << what;
        EXPECT_EQ(keep_sorted_order(gpu_queue, gpu_sorted), keep) << what << ": queue " << gpu_queue << ", sorted "
                                                                  << gpu_sorted << ", cap " << cap;
        EXPECT_EQ(choice.tally().kept[1].batches, keep ? 1u : 0u) << what;
        // Measured once: a second batch of the frame reads the same cap.
        Buffer again = Buffer::from(c.sorted);
        choice.choose({}, rays, c.first, n, again, nullptr, 4, diagonal, 1);
        EXPECT_EQ(choice.last_costs()[0], gpu_queue) << what;
    }
}

}  // namespace
}  // namespace rt
