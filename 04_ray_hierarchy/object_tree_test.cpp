// The object tree and the pair traversal on the CPU (object_tree.h): the tree's shape (every triangle in exactly one
// leaf, every parent sphere holding its children, Morton order), and the traversal's one promise, on the
// adversarial ray sets of ray_sets.h and on far-moved, tiny and degenerate scenes: no (ray, triangle) pair that the
// exact test hits is ever culled, by a node test, an object node or the per-ray sphere and box tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "object_tree.h"
#include "ray_hierarchy.h"
#include "ray_sets.h"

namespace rt {
namespace {

std::vector<glm::vec4> spheres_of(const std::vector<glm::vec3>& v) {
    std::vector<glm::vec4> s;
    for (std::size_t i = 0; i + 2 < v.size(); i += 3) s.push_back(rh_triangle_sphere(v[i], v[i + 1], v[i + 2]));
    return s;
}

void box_of(const std::vector<glm::vec3>& v, glm::vec3& lo, glm::vec3& hi) {
    lo = glm::vec3(INFINITY);
    hi = glm::vec3(-INFINITY);
    for (const glm::vec3& p : v) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
}

// In double: does sphere `outer` hold sphere `inner` (centre distance + inner radius <= outer radius)?
bool holds(glm::vec4 outer, glm::vec4 inner) {
    const double d = glm::length(glm::dvec3(glm::vec3(outer)) - glm::dvec3(glm::vec3(inner)));
    return d + double(inner.w) <= double(outer.w);
}

// Every (ray, triangle) pair the exact test hits (either method, the ray's tmax) must reach the exact test.
bool exact_hit(const RhTraceRay& r, const glm::vec3* v) {
    return ray_sets::exact_hit({r.origin, r.direction}, v, r.tmax);
}

// Does node n's box hold point p?
bool box_holds(const ObjectNode& n, glm::vec3 p) {
    return glm::all(glm::lessThanEqual(glm::vec3(n.box_lo), p)) && glm::all(glm::lessThanEqual(p, glm::vec3(n.box_hi)));
}

void expect_shape(const ObjectTree& tree, const std::vector<glm::vec4>& spheres, const std::string& what,
                  const std::vector<glm::vec3>& triangles = {}) {
    ASSERT_GE(tree.levels(), 1u) << what;
    EXPECT_EQ(tree.level_count.back(), 1u) << what << ": a single root";
    // Every triangle in exactly one leaf.
    std::vector<int> seen(spheres.size(), 0);
    for (std::uint32_t j = 0; j < tree.level_count[0]; ++j) {
        const ObjectNode& n = tree.nodes[tree.level_first[0] + j];
        EXPECT_EQ(n.level, 1u);
        EXPECT_GE(n.count, 1u);
        EXPECT_LE(n.count, kClusterSize);
        for (std::uint32_t k = 0; k < n.count; ++k) {
            const std::uint32_t t = tree.order[n.first + k];
            ++seen[t];
            ASSERT_TRUE(holds(n.sphere, spheres[t]) || !std::isfinite(spheres[t].w)) << what << " leaf " << j;
            for (std::size_t v = 0; v < (triangles.empty() ? 0 : 3); ++v)
                ASSERT_TRUE(box_holds(n, triangles[3 * t + v]) || !std::isfinite(spheres[t].w)) << what << " leaf " << j;
        }
    }
    for (std::size_t t = 0; t < seen.size(); ++t) ASSERT_EQ(seen[t], 1) << what << " triangle " << t;
    // Every node above holds its children, which are exactly the level below, each once.
    for (std::uint32_t l = 1; l < tree.levels(); ++l) {
        std::uint32_t next = tree.level_first[l - 1];
        for (std::uint32_t j = 0; j < tree.level_count[l]; ++j) {
            const ObjectNode& n = tree.nodes[tree.level_first[l] + j];
            EXPECT_EQ(n.level, l + 1);
            EXPECT_EQ(n.first, next) << what;
            EXPECT_LE(n.count, kObjectBranching);
            next += n.count;
            for (std::uint32_t k = 0; k < n.count; ++k) {
                const ObjectNode& child = tree.nodes[n.first + k];
                ASSERT_TRUE(holds(n.sphere, child.sphere)) << what << " level " << l + 1 << " node " << j;
                ASSERT_TRUE(box_holds(n, glm::vec3(child.box_lo)) && box_holds(n, glm::vec3(child.box_hi)))
                    << what << " level " << l + 1 << " node " << j << ": its box holds its children's";
            }
        }
        EXPECT_EQ(next, tree.level_first[l - 1] + tree.level_count[l - 1]) << what;
    }
}

void expect_no_hit_culled(const std::string& what, const std::vector<RhTraceRay>& rays,
                          const std::vector<glm::vec3>& triangles, std::uint64_t* culled = nullptr) {
    const std::vector<glm::vec4> spheres = spheres_of(triangles);
    glm::vec3 lo, hi;
    box_of(triangles, lo, hi);
    std::vector<RhRay> rh;
    for (const RhTraceRay& r : rays) rh.push_back({r.origin, r.direction});
    std::vector<std::pair<std::uint32_t, std::uint32_t>> runs;
    for (std::uint32_t t = 0; t < spheres.size(); t += 7) runs.emplace_back(t, std::min<std::uint32_t>(7, std::uint32_t(spheres.size()) - t));
    const ObjectTree tree = build_object_tree(spheres, lo, hi, triangles), meshes = mesh_objects(spheres, runs);
    expect_shape(tree, spheres, what, triangles);
    for (int b : {4, 16})
        for (int levels : {0, 2})
            for (ObjectMode mode : {ObjectMode::triangles, ObjectMode::meshes, ObjectMode::tree}) {
                const auto hierarchy = rh_build(rh, b, levels);
                const PairTraversal p = traverse_pairs(rays, hierarchy, b, spheres,
                                                       mode == ObjectMode::meshes ? meshes : tree, mode, triangles);
                const std::set<std::pair<std::uint32_t, std::uint32_t>> reached(p.exact.begin(), p.exact.end());
                ASSERT_EQ(reached.size(), p.exact.size()) << what << ": a pair reached the exact test twice";
                for (std::uint32_t i = 0; i < rays.size(); ++i)
                    for (std::uint32_t t = 0; t < spheres.size(); ++t)
                        if (exact_hit(rays[i], &triangles[3 * t])) {
                            ASSERT_TRUE(reached.count({i, t}))
                                << what << " " << object_mode_name(mode) << " B=" << b << " levels " << levels
                                << ": ray " << i << " hits triangle " << t << " but the pair was culled";
                        }
                EXPECT_LE(p.exact.size(), p.box_tests);
                EXPECT_LE(p.box_tests, p.sphere_tests);
                // The boxes change no exact test but the triangle's own box test would: an object node's box holds
                // its triangles', so it never culls a pair the triangle's box keeps.
                const PairTraversal spheres_only =
                    traverse_pairs(rays, hierarchy, b, spheres, mode == ObjectMode::meshes ? meshes : tree, mode);
                std::set<std::pair<std::uint32_t, std::uint32_t>> expected;
                for (const auto& [i, t] : spheres_only.exact) {
                    const glm::vec3* v = &triangles[3 * std::size_t(t)];
                    if (rh_ray_box_may_hit(rays[i].origin, rays[i].direction, rays[i].tmax, v[0], v[1], v[2]))
                        expected.insert({i, t});
                }
                ASSERT_EQ(reached, expected) << what << " " << object_mode_name(mode) << " B=" << b;
                EXPECT_LE(p.node_tests, spheres_only.node_tests);
                if (culled) *culled += rays.size() * spheres.size() - p.exact.size();
            }
}

std::vector<RhTraceRay> trace_rays(const std::vector<RhRay>& rays, float tmax = INFINITY) {
    std::vector<RhTraceRay> out;
    for (const RhRay& r : rays) out.push_back({r.origin, r.direction, tmax});
    return out;
}

TEST(ObjectTree, MortonCodesInterleaveCubicCellsAndClampOutsideTheBox) {
    const glm::vec3 lo(0.0f), hi(4.0f, 1.0f, 2.0f);
    const float scale = morton_scale(lo, hi);
    EXPECT_EQ(scale, 256.0f);   // 1024 cells over the largest extent, the same size on every axis
    EXPECT_EQ(morton_code(glm::vec3(0.0f), lo, scale), 0u);
    EXPECT_EQ(morton_code(glm::vec3(4.0f, 0.0f, 0.0f), lo, scale), 0x24924924u);   // x cell 1023: every x bit
    EXPECT_EQ(morton_code(glm::vec3(0.0f, 4.0f, 0.0f), lo, scale), 0x12492492u);   // y beyond the box: clamped
    EXPECT_EQ(morton_code(glm::vec3(-1.0f, NAN, 0.0f), lo, scale), 0u);
    EXPECT_EQ(morton_scale(lo, lo), 0.0f);
    EXPECT_EQ(morton_scale(lo, glm::vec3(INFINITY)), 0.0f);
    EXPECT_EQ(morton_scale(glm::vec3(NAN), hi), 0.0f);
}

TEST(ObjectTree, EveryTriangleInOneLeafAndEveryParentHoldsItsChildren) {
    for (const ray_sets::Case& c : ray_sets::all()) {
        const std::vector<glm::vec4> s = spheres_of(c.triangles);
        glm::vec3 lo, hi;
        box_of(c.triangles, lo, hi);
        expect_shape(build_object_tree(s, lo, hi, c.triangles), s, c.name, c.triangles);
    }
    // Sizes around the cluster and branching factors, and a single triangle.
    std::mt19937 g(5);
    for (std::size_t n : {1u, 3u, 4u, 5u, 16u, 17u, 63u, 64u, 65u, 1000u}) {
        std::vector<glm::vec3> v;
        for (std::size_t i = 0; i < 3 * n; ++i) v.push_back(ray_sets::unit(g) * float(i % 7 + 1));
        const std::vector<glm::vec4> s = spheres_of(v);
        glm::vec3 lo, hi;
        box_of(v, lo, hi);
        expect_shape(build_object_tree(s, lo, hi, v), s, std::to_string(n) + " triangles", v);
    }
}

TEST(ObjectTree, LeavesFollowMortonOrderStably) {
    std::vector<glm::vec4> s;
    for (int i = 0; i < 40; ++i) s.emplace_back(float((i * 7) % 10), 0.0f, 0.0f, 0.1f);   // equal centres too
    const ObjectTree tree = build_object_tree(s, glm::vec3(0.0f), glm::vec3(10.0f));
    const float scale = morton_scale(glm::vec3(0.0f), glm::vec3(10.0f));
    for (std::size_t k = 1; k < tree.order.size(); ++k) {
        const std::uint32_t a = tree.order[k - 1], b = tree.order[k];
        const std::uint32_t ca = morton_code(glm::vec3(s[a]), glm::vec3(0.0f), scale);
        const std::uint32_t cb = morton_code(glm::vec3(s[b]), glm::vec3(0.0f), scale);
        ASSERT_TRUE(ca < cb || (ca == cb && a < b)) << k;
    }
}

// group_heads: the groups of one level follow the codes' prefixes, 1 to kObjectBranching nodes each.
std::vector<std::uint32_t> heads_of(const std::vector<std::uint32_t>& codes) { return group_heads(codes, codes); }

TEST(ObjectTree, GroupsNeverSpanAJumpOfTheMortonCurve) {
    // Two clumps of 3 far apart on the curve: one group each (every 4 nodes would put node 3 with the first clump).
    EXPECT_EQ(heads_of({0, 1, 2, 1u << 20, (1u << 20) + 1, (1u << 20) + 2}), (std::vector<std::uint32_t>{0, 3}));
    // Four clumps of 2: the two nearer pairs of clumps share a group (their subtree holds 4 nodes).
    EXPECT_EQ(heads_of({0, 1, 8, 9, 1u << 20, (1u << 20) + 1, (1u << 20) + 8, (1u << 20) + 9}),
              (std::vector<std::uint32_t>{0, 4}));
    // A group ends where the subtree of the strongest boundary inside 5 nodes would hold them all: 8 nodes in a row
    // split at their middle (bit 2), then each half is one group.
    EXPECT_EQ(heads_of({0, 1, 2, 3, 4, 5, 6, 7}), (std::vector<std::uint32_t>{0, 4}));
    // Nodes spanning ranges of codes (upper levels): the boundary is between one's last and the next one's first.
    EXPECT_EQ(group_heads({0, 2, 1u << 20, (1u << 20) + 4}, {1, 3, (1u << 20) + 2, (1u << 20) + 5}).size(), 1u);
    EXPECT_EQ(group_heads({0, 2, 4, 6, 1u << 20}, {1, 3, 5, 7, (1u << 20) + 2}), (std::vector<std::uint32_t>{0, 4}));
    EXPECT_TRUE(heads_of({}).empty());
    EXPECT_EQ(heads_of({7}), (std::vector<std::uint32_t>{0}));
}

TEST(ObjectTree, GroupsHalveEveryLevelEvenWhenTheCodesSplitOffOneNodeAtATime) {
    // Codes 2^k: every boundary is stronger than the one before, so the prefixes split one node off at a time and
    // would make 27 groups of 30 nodes, a level that barely shrinks (30 levels for 30 triangles). Such a level is
    // grouped every 4 nodes instead.
    std::vector<std::uint32_t> powers;
    for (std::uint32_t k = 0; k < 30; ++k) powers.push_back(1u << k);
    std::vector<std::uint32_t> every4;
    for (std::uint32_t k = 0; k < 30; k += 4) every4.push_back(k);
    EXPECT_EQ(heads_of(powers), every4);
    // Equal codes are split by position, as the radix tree splits them: groups of 4 from an aligned start.
    EXPECT_EQ(heads_of(std::vector<std::uint32_t>(10, 5u)), (std::vector<std::uint32_t>{0, 4, 8}));
    // Whatever the codes, groups hold 1 to 4 nodes and a level at least halves.
    std::mt19937 g(11);
    for (int trial = 0; trial < 200; ++trial) {
        std::vector<std::uint32_t> codes(1 + g() % 300);
        for (std::uint32_t& c : codes) c = trial % 2 ? g() % 64 : g() >> (g() % 32);
        std::sort(codes.begin(), codes.end());
        const std::vector<std::uint32_t> heads = heads_of(codes);
        ASSERT_FALSE(heads.empty());
        EXPECT_EQ(heads[0], 0u);
        for (std::size_t j = 0; j < heads.size(); ++j) {
            const std::uint32_t end = j + 1 < heads.size() ? heads[j + 1] : std::uint32_t(codes.size());
            ASSERT_GT(end, heads[j]) << trial;
            ASSERT_LE(end - heads[j], kObjectBranching) << trial;
        }
        if (codes.size() > 1) {
            EXPECT_LE(2 * heads.size(), codes.size() + 1) << trial;
        }
    }
}

TEST(ObjectTree, NoPairThatHitsIsCulledOnTheAdversarialRaySets) {
    std::uint64_t culled = 0;
    for (const ray_sets::Case& c : ray_sets::all()) expect_no_hit_culled(c.name, trace_rays(c.rays), c.triangles, &culled);
    EXPECT_GT(culled, 100000u);   // and the tests do cull
}

TEST(ObjectTree, ShortRaysCullBeyondTheirLengthButNeverAHit) {
    for (const ray_sets::Case& c : ray_sets::all()) {
        std::vector<RhTraceRay> rays = trace_rays(c.rays);
        std::mt19937 g(11);
        std::uniform_real_distribution<float> u(0.0f, 2.0f);
        for (RhTraceRay& r : rays) r.tmax = u(g) * std::max(1e-30f, glm::length(c.triangles[0] - c.triangles[1]));
        expect_no_hit_culled(c.name + " short", rays, c.triangles);
    }
}

// Degenerate triangles (points, needles, repeated), a scene far from the origin and a tiny one.
TEST(ObjectTree, DegenerateFarAndTinyScenesKeepEveryHit) {
    std::mt19937 g(9);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (const auto& [name, scale, centre] : {std::tuple<const char*, float, glm::vec3>{"unit", 1.0f, glm::vec3(0.0f)},
                                              {"far", 10.0f, glm::vec3(4e6f, -3e6f, 1e6f)},
                                              {"tiny", 1e-5f, glm::vec3(3e-5f)}}) {
        std::vector<glm::vec3> v;
        for (int t = 0; t < 48; ++t) {
            const glm::vec3 p = centre + scale * glm::vec3(u(g), u(g), u(g));
            const glm::vec3 e1 = 0.3f * scale * ray_sets::unit(g), e2 = 0.3f * scale * ray_sets::unit(g);
            if (t % 6 == 0) v.insert(v.end(), {p, p, p});                       // a point
            else if (t % 6 == 1) v.insert(v.end(), {p, p + e1, p + 2.0f * e1});  // a needle
            else v.insert(v.end(), {p, p + e1, p + e2});
        }
        for (int k = 0; k < 6; ++k) v.insert(v.end(), v.begin() + 6, v.begin() + 9);   // the same triangle again
        std::vector<RhTraceRay> rays;
        for (int i = 0; i < 300; ++i) {
            const glm::vec3 target = v[std::size_t(i * 7) % v.size()];
            const glm::vec3 o = centre + 2.0f * scale * glm::vec3(u(g), u(g), u(g));
            rays.push_back({o, glm::normalize(target - o + 0.01f * scale * ray_sets::unit(g)), INFINITY});
        }
        expect_no_hit_culled(name, rays, v);
    }
}

TEST(ObjectTree, RaySphereTestRejectsOnlyWhatNoRayPointReaches) {
    const glm::vec4 s(0.0f, 0.0f, 10.0f, 1.0f);
    EXPECT_TRUE(rh_ray_may_hit(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f), INFINITY, s));
    EXPECT_TRUE(rh_ray_may_hit(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1e-30f), INFINITY, s));   // tiny direction
    EXPECT_TRUE(rh_ray_may_hit(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1e30f), INFINITY, s));    // huge
    EXPECT_FALSE(rh_ray_may_hit(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), INFINITY, s));   // away from it
    EXPECT_FALSE(rh_ray_may_hit(glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 1.0f), INFINITY, s));    // past it
    EXPECT_FALSE(rh_ray_may_hit(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f), 8.9f, s));        // ends before it
    EXPECT_TRUE(rh_ray_may_hit(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 2.0f), 4.6f, s));         // t in |d| units
    EXPECT_TRUE(rh_ray_may_hit(glm::vec3(0.0f, 0.0f, 10.5f), glm::vec3(1.0f, 0.0f, 0.0f), INFINITY, s));   // inside
    EXPECT_FALSE(rh_ray_may_hit(glm::vec3(0.0f), glm::vec3(0.0f), INFINITY, s));
    EXPECT_FALSE(rh_ray_may_hit(glm::vec3(0.0f), glm::vec3(NAN, 0.0f, 1.0f), INFINITY, s));
    EXPECT_TRUE(rh_ray_may_hit(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f), NAN, s));   // NaN keeps the pair
}

TEST(ObjectTree, RayBoxTestRejectsOnlyWhatNoRayPointReaches) {
    // A flat, axis-aligned triangle (its box has no depth in z) and a slanted one.
    const glm::vec3 a(0.0f, 0.0f, 10.0f), b(4.0f, 0.0f, 10.0f), c(0.0f, 4.0f, 10.0f);
    const glm::vec3 z(0.0f, 0.0f, 1.0f);
    EXPECT_TRUE(rh_ray_box_may_hit(glm::vec3(1.0f, 1.0f, 0.0f), z, INFINITY, a, b, c));
    EXPECT_TRUE(rh_ray_box_may_hit(glm::vec3(3.9f, 3.9f, 0.0f), z, INFINITY, a, b, c));   // the box, not the triangle
    EXPECT_FALSE(rh_ray_box_may_hit(glm::vec3(4.1f, 1.0f, 0.0f), z, INFINITY, a, b, c));  // beside the box
    EXPECT_FALSE(rh_ray_box_may_hit(glm::vec3(1.0f, 1.0f, 0.0f), -z, INFINITY, a, b, c)); // away from it
    EXPECT_FALSE(rh_ray_box_may_hit(glm::vec3(1.0f, 1.0f, 0.0f), z, 9.9f, a, b, c));      // ends before it
    EXPECT_TRUE(rh_ray_box_may_hit(glm::vec3(1.0f, 1.0f, 0.0f), z, 10.0f, a, b, c));      // ends on it
    EXPECT_TRUE(rh_ray_box_may_hit(glm::vec3(1.0f, 1.0f, 0.0f), 2.0f * z, 5.0f, a, b, c)); // t in |d| units
    EXPECT_TRUE(rh_ray_box_may_hit(glm::vec3(1.0f, 1.0f, 0.0f), z, NAN, a, b, c));        // NaN keeps the pair
    EXPECT_TRUE(rh_ray_box_test(glm::vec3(1.0f, 1.0f, 0.0f), z, INFINITY, glm::vec3(NAN), glm::vec3(4.0f)));   // so
    EXPECT_TRUE(rh_ray_box_test(glm::vec3(1.0f, 1.0f, 0.0f), z, INFINITY, glm::vec3(-INFINITY), glm::vec3(INFINITY)));
    EXPECT_TRUE(rh_ray_box_may_hit(glm::vec3(1.0f, 1.0f, 0.0f), 1e-30f * z, INFINITY, a, b, c));   // tiny direction
    EXPECT_TRUE(rh_ray_box_may_hit(glm::vec3(1.0f, 1.0f, 0.0f), 1e30f * z, INFINITY, a, b, c));    // huge
    // Parallel to the plane: in it (on the flat box's face) or beside it.
    EXPECT_TRUE(rh_ray_box_may_hit(glm::vec3(-1.0f, 1.0f, 10.0f), glm::vec3(1.0f, 0.0f, 0.0f), INFINITY, a, b, c));
    EXPECT_FALSE(rh_ray_box_may_hit(glm::vec3(-1.0f, 1.0f, 10.1f), glm::vec3(1.0f, 0.0f, 0.0f), INFINITY, a, b, c));
    // The sphere of a long needle holds a ray the box does not.
    const glm::vec3 n0(-50.0f, 0.0f, 0.0f), n1(50.0f, 0.01f, 0.0f), n2(50.0f, 0.0f, 0.01f);
    const glm::vec3 o(0.0f, 20.0f, -5.0f), d(0.0f, 0.0f, 1.0f);
    EXPECT_TRUE(rh_ray_may_hit(o, d, INFINITY, rh_triangle_sphere(n0, n1, n2)));
    EXPECT_FALSE(rh_ray_box_may_hit(o, d, INFINITY, n0, n1, n2));
    // A ray that cannot hit anything.
    EXPECT_FALSE(rh_ray_box_may_hit(glm::vec3(1.0f, 1.0f, 0.0f), glm::vec3(0.0f), INFINITY, a, b, c));
    EXPECT_FALSE(rh_ray_box_may_hit(glm::vec3(NAN), z, INFINITY, a, b, c));
    EXPECT_FALSE(rh_ray_box_may_hit(glm::vec3(1.0f, 1.0f, 0.0f), glm::vec3(INFINITY, 0.0f, 1.0f), INFINITY, a, b, c));
}

// Rays aimed at the vertices and edges of axis-aligned, slanted, needle and point triangles (where a box is flat or
// the exact test grazes it), near the origin, far from it and tiny: every hit of the exact test passes the box test.
TEST(ObjectTree, RayBoxTestKeepsEveryGrazingHit) {
    std::uint64_t hits = 0, culled = 0;
    for (const ray_sets::AimedRay& a : ray_sets::aimed_rays()) {
        if (!exact_hit({a.ray.origin, a.ray.direction, a.tmax}, a.v)) continue;
        ++hits;
        if (!rh_ray_box_may_hit(a.ray.origin, a.ray.direction, a.tmax, a.v[0], a.v[1], a.v[2])) ++culled;
    }
    EXPECT_GT(hits, 10000u);
    EXPECT_EQ(culled, 0u);
}

// The box test of a ray node (rh_node_box_test) by hand: a beam of four rays along +z, a flat triangle's box ahead,
// beside and behind them; a node of every direction and an empty node.
TEST(ObjectTree, NodeBoxTestRejectsOnlyWhatNoRayOfTheNodeReaches) {
    const glm::vec3 z(0.0f, 0.0f, 1.0f);
    std::vector<RhNode> leaves;
    for (int i = 0; i < 4; ++i)
        leaves.push_back(rh_leaf(glm::vec3(float(i % 2), float(i / 2), 0.0f), z + 0.05f * glm::vec3(float(i), 0, 0)));
    const RhNode beam = rh_union(leaves.data(), leaves.size());
    const glm::vec3 lo(0.0f, 0.0f, 10.0f), hi(4.0f, 4.0f, 10.0f);   // no depth in z
    EXPECT_TRUE(rh_node_box_test(beam, lo, hi));
    EXPECT_FALSE(rh_node_box_test(beam, lo + glm::vec3(6.0f, 0.0f, 0.0f), hi + glm::vec3(6.0f, 0.0f, 0.0f)));
    EXPECT_TRUE(rh_node_box_test(beam, lo + glm::vec3(1.4f, 0.0f, 0.0f), hi + glm::vec3(1.4f, 0.0f, 0.0f)));
    EXPECT_FALSE(rh_node_box_test(beam, -hi, -lo));   // behind the origins
    EXPECT_TRUE(rh_node_box_test(beam, glm::vec3(0.2f, 0.2f, -0.1f), glm::vec3(0.3f, 0.3f, 0.1f)));   // at them
    // The sphere of a long needle beside the beam holds it; the needle's box does not.
    const glm::vec3 n0(-50.0f, 10.0f, 20.0f), n1(50.0f, 10.01f, 20.0f), n2(50.0f, 10.0f, 20.01f);
    EXPECT_TRUE(rh_may_hit(beam, rh_triangle_sphere(n0, n1, n2)));
    EXPECT_FALSE(rh_node_box_test(beam, glm::min(n0, glm::min(n1, n2)), glm::max(n0, glm::max(n1, n2))));
    const glm::vec3 opposite[2] = {z, -z};
    RhNode all[2] = {rh_leaf(glm::vec3(0.0f), opposite[0]), rh_leaf(glm::vec3(0.0f), opposite[1])};
    EXPECT_TRUE(rh_node_box_test(rh_union(all, 2), -hi, -lo));   // every direction reaches everything
    EXPECT_FALSE(rh_node_box_test(RhNode{}, lo, hi));            // an empty node reaches nothing
    EXPECT_TRUE(rh_node_box_test(beam, glm::vec3(-INFINITY), glm::vec3(INFINITY)));   // all space (mesh objects)
    EXPECT_TRUE(rh_node_box_test(beam, glm::vec3(NAN), hi));                          // NaN keeps the pair
}

// The node's box test keeps a node whenever one of its rays passes its own box test (unbounded), on every node of
// the adversarial ray sets and two beams against every triangle's box: so it culls no pair the leaves would keep, and
// no hit. A leaf node (one ray, no spread) too.
TEST(ObjectTree, NodeBoxTestKeepsEveryNodeOneOfWhoseRaysPassesItsBoxTest) {
    std::uint64_t culled = 0, culled_past_the_sphere = 0;
    for (const ray_sets::Case& c : ray_sets::with_beams())
        for (int b : {4, 16}) {
            const auto levels = rh_build(c.rays, b);
            const std::vector<glm::vec3> triangles = ray_sets::with_walls(c.triangles);
            for (std::size_t t = 0; t < triangles.size() / 3; ++t) {
                const glm::vec3* v = &triangles[3 * t];
                const glm::vec3 lo = glm::min(v[0], glm::min(v[1], v[2])), hi = glm::max(v[0], glm::max(v[1], v[2]));
                // Each ray's box test on its direction as its leaf holds it (unit length: the ray test's absolute
                // slack of 1e-30 in t would keep rays of directions near 1e30 that pass beside the box).
                std::vector<char> ray_kept(c.rays.size());
                for (std::size_t i = 0; i < c.rays.size(); ++i) {
                    const RhNode& leaf = levels[0][i];
                    ray_kept[i] =
                        !leaf.empty() && rh_ray_box_test(c.rays[i].origin, glm::vec3(leaf.cone), INFINITY, lo, hi);
                    if (ray_kept[i]) {
                        ASSERT_TRUE(rh_node_box_test(leaf, lo, hi)) << c.name << " ray " << i;
                    }
                }
                for (std::size_t l = 1; l < levels.size(); ++l) {
                    for (std::size_t j = 0; j < levels[l].size(); ++j) {
                        if (rh_node_box_test(levels[l][j], lo, hi)) continue;
                        ++culled;
                        culled_past_the_sphere += rh_may_hit(levels[l][j], rh_triangle_sphere(v[0], v[1], v[2]));
                        const auto [first, last] = ray_sets::leaves_under(j, l, b, c.rays.size());
                        for (std::size_t i = first; i < last; ++i) {
                            ASSERT_FALSE(ray_kept[i])
                                << c.name << " B=" << b << " level " << l << " node " << j << " triangle " << t;
                            ASSERT_FALSE(ray_sets::exact_hit(c.rays[i], v)) << c.name << " node " << j << " hits";
                        }
                    }
                }
            }
        }
    EXPECT_GT(culled, 1000u);
    EXPECT_GT(culled_past_the_sphere, 200u);   // it culls where the cone+sphere test keeps the pair
}

// The split rule (rh_split_rays): the rays of a pair are split when their beam (radius + distance x sin(spread)) is
// wider than kSplitRaysWidth of the object node's radius, else the object node; a node of every direction always
// splits its rays.
TEST(ObjectTree, SplitRaysWhenTheBeamIsWiderThanAQuarterOfTheObject) {
    const glm::vec3 z(0.0f, 0.0f, 1.0f);
    RhNode beam = rh_leaf(glm::vec3(0.0f), z);
    beam.sphere.w = 1.0f;   // no spread: the beam is 1 wide at any distance
    const glm::vec3 ahead(0.0f, 0.0f, 10.0f);
    EXPECT_TRUE(rh_split_rays(beam, glm::vec4(ahead, 0.5f)));    // wider than the object
    EXPECT_TRUE(rh_split_rays(beam, glm::vec4(ahead, 3.0f)));    // narrower, but wider than a quarter of it
    EXPECT_FALSE(rh_split_rays(beam, glm::vec4(ahead, 5.0f)));   // narrower than a quarter: the object splits
    beam.cone.w = 0.1f;   // spread: 1 + 10 sin(0.1) = 2.0 wide at the object
    EXPECT_TRUE(rh_split_rays(beam, glm::vec4(ahead, 7.0f)));
    EXPECT_FALSE(rh_split_rays(beam, glm::vec4(ahead, 9.0f)));
    beam.cone.w = kRhAllDirections;
    EXPECT_TRUE(rh_split_rays(beam, glm::vec4(ahead, 1e30f)));
}

TEST(ObjectTree, TheTreeMeetsFewerPairsThanEveryTriangle) {
    // 4096 small triangles on a grid, a coherent beam: the tree's node and sphere tests are a small fraction of
    // the triangles mode's (where every top node meets every triangle).
    std::vector<glm::vec3> v;
    for (int i = 0; i < 64; ++i)
        for (int j = 0; j < 64; ++j) {
            const glm::vec3 p(float(i), float(j), 0.0f);
            v.insert(v.end(), {p, p + glm::vec3(0.5f, 0.0f, 0.0f), p + glm::vec3(0.0f, 0.5f, 0.0f)});
        }
    std::vector<RhTraceRay> rays;
    std::vector<RhRay> rh;
    for (int i = 0; i < 256; ++i) {
        const glm::vec3 o(10.0f + 0.01f * float(i % 16), 20.0f + 0.01f * float(i / 16), 5.0f);
        rays.push_back({o, glm::vec3(0.001f * float(i % 16), 0.0f, -1.0f), INFINITY});
        rh.push_back({rays.back().origin, rays.back().direction});
    }
    const std::vector<glm::vec4> s = spheres_of(v);
    glm::vec3 lo, hi;
    box_of(v, lo, hi);
    const ObjectTree tree = build_object_tree(s, lo, hi);
    const auto levels = rh_build(rh, 4);
    const PairTraversal flat = traverse_pairs(rays, levels, 4, s, tree, ObjectMode::triangles);
    const PairTraversal dual = traverse_pairs(rays, levels, 4, s, tree, ObjectMode::tree);
    std::set<std::pair<std::uint32_t, std::uint32_t>> a(flat.exact.begin(), flat.exact.end());
    for (const auto& p : dual.exact) a.erase(p);
    for (const auto& p : a) ASSERT_FALSE(exact_hit(rays[p.first], &v[3 * p.second])) << "a hit only the flat mode found";
    EXPECT_LT(10 * (dual.node_tests + dual.sphere_tests), flat.node_tests + flat.sphere_tests);
    // With the box tests the same pairs pass or fewer (a box only ever removes pairs), never a hit.
    const PairTraversal boxed = traverse_pairs(rays, levels, 4, s, build_object_tree(s, lo, hi, v), ObjectMode::tree, v);
    EXPECT_LE(boxed.box_tests, dual.exact.size());
    EXPECT_LE(boxed.exact.size(), dual.exact.size());
    for (const auto& p : dual.exact) {
        const bool kept = std::count(boxed.exact.begin(), boxed.exact.end(), p) > 0;
        ASSERT_TRUE(kept || !exact_hit(rays[p.first], &v[3 * p.second])) << "a hit the box test culled";
    }
}

}  // namespace
}  // namespace rt
