// Stage 04's GLSL twins (shaders/rh_common.glsl) against the hierarchy's two properties, on the adversarial ray sets
// (ray_sets.h): every ray inside all its ancestors, and no rejected (node, triangle) pair that a ray below hits;
// empty children left out of the union; the leaves' two cheap per-ray tests keep every hit (and the box test, all
// additions, divisions and comparisons, equals its C++ twin bit for bit).
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "common/gpu/testing/glsl_test_harness.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/trace/intersect.h"
#include "object_tree.h"
#include "ray_hierarchy.h"
#include "ray_sets.h"

namespace rt {
namespace {

using gpu::Words;

RhNode node_at(const std::vector<std::uint32_t>& w, std::size_t i) {
    RhNode n;
    for (int k = 0; k < 4; ++k) n.sphere[k] = gpu::word_f(w, i + k);
    for (int k = 0; k < 4; ++k) n.cone[k] = gpu::word_f(w, i + 4 + k);
    return n;
}

// rh_union in GLSL: per record, the child count and 16 children (sphere, cone); out the node (sphere, cone).
gpu::GlslTestHarness& glsl_union() {
    static gpu::GlslTestHarness join("rh_union", R"(#include "04_ray_hierarchy/shaders/rh_common.glsl"
void test_main() {
    RhNode kids[16];
    for (uint k = 0u; k < 16u; ++k) kids[k] = RhNode(in_vec4(1u + 8u * k), in_vec4(5u + 8u * k));
    const RhNode n = rh_union(kids, in_u(0u));
    out_vec4(0u, n.sphere);
    out_vec4(4u, n.cone);
})");
    return join;
}

// The hierarchy built by the GLSL functions (leaves, then unions level by level), one harness run per level.
std::vector<std::vector<RhNode>> glsl_build(const std::vector<RhRay>& rays, int b) {
    static gpu::GlslTestHarness leaf("rh_leaf", R"(#include "04_ray_hierarchy/shaders/rh_common.glsl"
void test_main() {
    const RhNode n = rh_leaf(in_vec3(0u), in_vec3(3u));
    out_vec4(0u, n.sphere);
    out_vec4(4u, n.cone);
})");
    gpu::GlslTestHarness& join = glsl_union();
    Words in;
    for (const RhRay& r : rays) in << r.origin << r.direction;
    std::vector<std::vector<RhNode>> levels(1);
    const auto out = leaf.run(in.words, rays.size(), 6, 8);
    for (std::size_t i = 0; i < rays.size(); ++i) levels[0].push_back(node_at(out, 8 * i));
    while (levels.back().size() > 1 || levels.size() == 1) {
        const std::vector<RhNode>& below = levels.back();
        const std::size_t parents = (below.size() + b - 1) / b;
        Words w;
        for (std::size_t j = 0; j < parents; ++j) {
            const std::size_t count = std::min<std::size_t>(b, below.size() - j * b);
            w << std::uint32_t(count);
            for (std::size_t k = 0; k < 16; ++k) {
                const RhNode n = k < count ? below[j * b + k] : RhNode{};
                w << n.sphere << n.cone;
            }
        }
        const auto o = join.run(w.words, parents, 129, 8);
        std::vector<RhNode> level;
        for (std::size_t j = 0; j < parents; ++j) level.push_back(node_at(o, 8 * j));
        levels.push_back(std::move(level));
    }
    return levels;
}

std::vector<glm::vec4> glsl_spheres(const std::vector<glm::vec3>& triangles) {
    static gpu::GlslTestHarness h("rh_triangle_sphere", R"(#include "04_ray_hierarchy/shaders/rh_common.glsl"
void test_main() { out_vec4(0u, rh_triangle_sphere(in_vec3(0u), in_vec3(3u), in_vec3(6u))); })");
    Words in;
    for (const glm::vec3& v : triangles) in << v;
    const auto out = h.run(in.words, triangles.size() / 3, 9, 4);
    std::vector<glm::vec4> s;
    for (std::size_t i = 0; i < triangles.size() / 3; ++i)
        s.emplace_back(gpu::word_f(out, 4 * i), gpu::word_f(out, 4 * i + 1), gpu::word_f(out, 4 * i + 2),
                       gpu::word_f(out, 4 * i + 3));
    return s;
}

TEST(GlslRayHierarchy, EveryRayInsideItsAncestorsAndNoHitRejected) {
    gpu::test_context();
    static gpu::GlslTestHarness may_hit("rh_may_hit", R"(#include "04_ray_hierarchy/shaders/rh_common.glsl"
void test_main() { out_b(0u, rh_may_hit(RhNode(in_vec4(0u), in_vec4(4u)), in_vec4(8u))); })");
    std::size_t rejected = 0;
    for (const ray_sets::Case& c : ray_sets::all())
        for (int b : {4, 8, 16}) {
            const auto levels = glsl_build(c.rays, b);
            ASSERT_EQ(levels.back().size(), 1u);
            for (std::size_t i = 0; i < c.rays.size(); ++i) {
                if (rh_leaf(c.rays[i].origin, c.rays[i].direction).empty()) {
                    EXPECT_TRUE(levels[0][i].empty()) << c.name << " ray " << i;
                    continue;
                }
                std::size_t j = i;
                for (std::size_t l = 1; l < levels.size(); ++l) {
                    j /= std::size_t(b);
                    ASSERT_TRUE(rh_contains(levels[l][j], c.rays[i].origin, c.rays[i].direction))
                        << c.name << " B=" << b << " ray " << i << " level " << l;
                }
            }
            // Every (node, triangle) pair at once through the GLSL test.
            const std::vector<glm::vec4> spheres = glsl_spheres(c.triangles);
            Words in;
            std::vector<std::pair<std::size_t, std::size_t>> pairs;   // (level, node) per record, triangle-major
            for (std::size_t t = 0; t < spheres.size(); ++t)
                for (std::size_t l = 1; l < levels.size(); ++l)
                    for (std::size_t j = 0; j < levels[l].size(); ++j) {
                        in << levels[l][j].sphere << levels[l][j].cone << spheres[t];
                        pairs.emplace_back(l, j);
                    }
            const auto out = may_hit.run(in.words, pairs.size(), 12, 1);
            const std::size_t per_triangle = pairs.size() / spheres.size();
            for (std::size_t p = 0; p < pairs.size(); ++p) {
                if (out[p] != 0) continue;
                ++rejected;
                const auto [l, j] = pairs[p];
                const std::size_t t = p / per_triangle;
                const auto [first, last] = ray_sets::leaves_under(j, l, b, c.rays.size());
                for (std::size_t i = first; i < last; ++i)
                    ASSERT_FALSE(ray_sets::exact_hit(c.rays[i], &c.triangles[3 * t]))
                        << c.name << " B=" << b << " level " << l << " node " << j << " triangle " << t;
            }
        }
    EXPECT_GT(rejected, 1000u);
}

// The box test of ray nodes in GLSL (rh_node_box_test, used by rh_cull.comp), on every node of the adversarial ray
// sets and two beams (levels built by the GLSL functions) against every triangle's box and walls': a node is culled
// only when none of its rays passes its own box test (whose GLSL equals its twin:
// RayTestsOfTheLeavesKeepEveryHitAndTheBoxTestEqualsItsTwin), so never a hit.
TEST(GlslRayHierarchy, NodeBoxTestKeepsEveryNodeOneOfWhoseRaysPassesItsBoxTest) {
    gpu::test_context();
    static gpu::GlslTestHarness node_box("rh_node_box_test", R"(#include "04_ray_hierarchy/shaders/rh_common.glsl"
void test_main() { out_b(0u, rh_node_box_test(RhNode(in_vec4(0u), in_vec4(4u)), in_vec3(8u), in_vec3(11u))); })");
    std::size_t culled = 0;
    for (const ray_sets::Case& c : ray_sets::with_beams())
        for (int b : {4, 16}) {
            const auto levels = glsl_build(c.rays, b);
            const std::vector<glm::vec3> triangles = ray_sets::with_walls(c.triangles);
            Words in;
            struct Record {
                std::size_t level, node, triangle;
            };
            std::vector<Record> records;
            for (std::size_t t = 0; t < triangles.size() / 3; ++t) {
                const glm::vec3* v = &triangles[3 * t];
                const glm::vec3 lo = glm::min(v[0], glm::min(v[1], v[2])), hi = glm::max(v[0], glm::max(v[1], v[2]));
                for (std::size_t l = 1; l < levels.size(); ++l)
                    for (std::size_t j = 0; j < levels[l].size(); ++j) {
                        in << levels[l][j].sphere << levels[l][j].cone << lo << hi;
                        records.push_back({l, j, t});
                    }
            }
            const auto out = node_box.run(in.words, records.size(), 14, 1);
            for (std::size_t k = 0; k < records.size(); ++k) {
                if (out[k] != 0) continue;
                ++culled;
                const auto [l, j, t] = records[k];
                const glm::vec3* v = &triangles[3 * t];
                const glm::vec3 lo = glm::min(v[0], glm::min(v[1], v[2])), hi = glm::max(v[0], glm::max(v[1], v[2]));
                const auto [first, last] = ray_sets::leaves_under(j, l, b, c.rays.size());
                for (std::size_t i = first; i < last; ++i) {
                    const RhNode& leaf = levels[0][i];
                    ASSERT_FALSE(!leaf.empty() &&
                                 rh_ray_box_test(c.rays[i].origin, glm::vec3(leaf.cone), INFINITY, lo, hi))
                        << c.name << " B=" << b << " level " << l << " node " << j << " triangle " << t;
                    ASSERT_FALSE(ray_sets::exact_hit(c.rays[i], v)) << c.name << " node " << j << " hits";
                }
            }
        }
    EXPECT_GT(culled, 1000u);
}

// The leaves' per-ray tests in GLSL on every (ray, triangle) pair of the adversarial sets (each ray unbounded or
// ending short of the scene) and on rays aimed at triangles' edges and vertices: the sphere test and the box test
// keep every pair the exact test hits, and the box test answers as its C++ twin.
TEST(GlslRayHierarchy, RayTestsOfTheLeavesKeepEveryHitAndTheBoxTestEqualsItsTwin) {
    gpu::test_context();
    static gpu::GlslTestHarness tests("rh_ray_tests", R"(#include "04_ray_hierarchy/shaders/rh_common.glsl"
void test_main() {
    const vec3 o = in_vec3(0u), d = in_vec3(3u), a = in_vec3(7u), b = in_vec3(10u), c = in_vec3(13u);
    out_b(0u, rh_ray_may_hit(o, d, in_f(6u), rh_triangle_sphere(a, b, c)));
    out_b(1u, rh_ray_box_may_hit(o, d, in_f(6u), a, b, c));
})");
    std::vector<ray_sets::AimedRay> pairs = ray_sets::aimed_rays();
    for (const ray_sets::Case& c : ray_sets::all())
        for (std::size_t t = 0; t < c.triangles.size() / 3; ++t)
            for (std::size_t i = 0; i < c.rays.size(); ++i) {
                ray_sets::AimedRay a;
                a.ray = c.rays[i];
                a.tmax = i % 2 ? INFINITY : float(i % 7) * 0.3f * glm::length(c.triangles[0] - c.triangles[1]);
                for (int k = 0; k < 3; ++k) a.v[k] = c.triangles[3 * t + std::size_t(k)];
                pairs.push_back(a);
            }
    Words in;
    for (const ray_sets::AimedRay& a : pairs)
        in << a.ray.origin << a.ray.direction << a.tmax << a.v[0] << a.v[1] << a.v[2];
    const auto out = tests.run(in.words, pairs.size(), 16, 2);
    std::size_t sphere_culled = 0, box_culled = 0, hits = 0;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        const ray_sets::AimedRay& a = pairs[p];
        const bool cpu = rh_ray_box_may_hit(a.ray.origin, a.ray.direction, a.tmax, a.v[0], a.v[1], a.v[2]);
        ASSERT_EQ(out[2 * p + 1] != 0, cpu) << "pair " << p << " tmax " << a.tmax;
        sphere_culled += out[2 * p] == 0;
        box_culled += out[2 * p + 1] == 0;
        if (!ray_sets::exact_hit(a.ray, a.v, a.tmax)) continue;
        ++hits;
        ASSERT_NE(out[2 * p], 0u) << "the sphere test culls a hit, pair " << p << " tmax " << a.tmax;
        ASSERT_NE(out[2 * p + 1], 0u) << "the box test culls a hit, pair " << p << " tmax " << a.tmax;
    }
    EXPECT_GT(hits, 10000u);
    EXPECT_GT(sphere_culled, 10000u);
    EXPECT_GT(box_culled, 10000u);
}

// Empty children (rays of zero or non-finite direction, the padding of a last node) are left out of a union: a node
// over some children with empty ones between them is, bit for bit, the node over those children alone.
TEST(GlslRayHierarchy, EmptyChildrenAreLeftOutOfTheUnion) {
    gpu::test_context();
    gpu::GlslTestHarness& join = glsl_union();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Words w;
    const int cases = 64;
    for (int c = 0; c < cases; ++c) {
        const std::size_t n = 1 + std::size_t(c % 8);
        std::vector<RhNode> kids;
        for (std::size_t k = 0; k < n; ++k)
            kids.push_back(rh_leaf({u(rng) * 5, u(rng) * 5, u(rng) * 5}, {u(rng), u(rng), 0.5f + u(rng)}));
        std::vector<RhNode> with_empties;
        for (const RhNode& k : kids) {
            for (int e = int(rng() % 2); e > 0; --e) with_empties.push_back(RhNode{});
            with_empties.push_back(k);
        }
        if (c % 3 == 0) with_empties.insert(with_empties.begin(), RhNode{});
        for (const std::vector<RhNode>* set : {&kids, &with_empties}) {
            w << std::uint32_t(set->size());
            for (std::size_t k = 0; k < 16; ++k) {
                const RhNode node = k < set->size() ? (*set)[k] : RhNode{};
                w << node.sphere << node.cone;
            }
        }
    }
    const auto out = join.run(w.words, 2 * cases, 129, 8);
    for (int c = 0; c < cases; ++c) {
        const RhNode alone = node_at(out, 16 * std::size_t(c)), among = node_at(out, 16 * std::size_t(c) + 8);
        EXPECT_EQ(std::memcmp(&alone, &among, sizeof(RhNode)), 0) << "case " << c << ": an empty child changed the node";
        EXPECT_FALSE(alone.empty());
    }
    // No child with rays at all: the empty node.
    Words none;
    none << std::uint32_t(3);
    for (std::size_t k = 0; k < 16; ++k) none << RhNode{}.sphere << RhNode{}.cone;
    EXPECT_TRUE(node_at(join.run(none.words, 1, 129, 8), 0).empty());
}

// ---------------------------------------------------------------------------------------------------------------
// The batch traversal on crafted rays against brute force on the CPU (bit-exact twins on llvmpipe).

}  // namespace
}  // namespace rt
