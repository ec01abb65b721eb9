// The hierarchy's two properties on the CPU twin (ray_hierarchy.cpp), on random and adversarial ray sets
// (ray_sets.h: all directions, identical rays, one origin, one plane, opposite rays, zero/NaN/infinite directions,
// tiny and huge directions and coordinates), for every branching:
//   1. every ray lies inside all its ancestors' sphere and cone;
//   2. the node test never rejects a triangle that some ray below the node hits (both exact tests).
// Plus the shape of the tree (counts that are not a power of B, --levels) and the awkward unions.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/trace/intersect.h"
#include "ray_hierarchy.h"
#include "ray_sets.h"

namespace rt {
namespace {

bool valid(const RhRay& r) { return !rh_leaf(r.origin, r.direction).empty(); }

TEST(RayHierarchy, EveryRayLiesInsideAllItsAncestors) {
    for (const ray_sets::Case& c : ray_sets::all())
        for (int b : {4, 8, 16}) {
            const auto levels = rh_build(c.rays, b);
            ASSERT_EQ(levels.back().size(), 1u) << c.name;
            for (std::size_t i = 0; i < c.rays.size(); ++i) {
                if (!valid(c.rays[i])) continue;
                std::size_t j = i;
                for (std::size_t l = 1; l < levels.size(); ++l) {
                    j /= std::size_t(b);
                    ASSERT_TRUE(rh_contains(levels[l][j], c.rays[i].origin, c.rays[i].direction))
                        << c.name << " B=" << b << " ray " << i << " level " << l;
                }
            }
        }
}

TEST(RayHierarchy, TheNodeTestNeverRejectsATriangleARayBelowHits) {
    std::size_t rejected = 0, checked = 0;
    for (const ray_sets::Case& c : ray_sets::all())
        for (int b : {4, 8, 16}) {
            const auto levels = rh_build(c.rays, b);
            for (std::size_t t = 0; t < c.triangles.size() / 3; ++t) {
                const glm::vec3* v = &c.triangles[3 * t];
                const glm::vec4 s = rh_triangle_sphere(v[0], v[1], v[2]);
                for (std::size_t l = 1; l < levels.size(); ++l)
                    for (std::size_t j = 0; j < levels[l].size(); ++j) {
                        if (rh_may_hit(levels[l][j], s)) continue;
                        ++rejected;
                        const auto [first, last] = ray_sets::leaves_under(j, l, b, c.rays.size());
                        for (std::size_t i = first; i < last; ++i) {
                            ++checked;
                            ASSERT_FALSE(ray_sets::exact_hit(c.rays[i], v))
                                << c.name << " B=" << b << " level " << l << " node " << j << " triangle " << t;
                        }
                    }
            }
        }
    EXPECT_GT(rejected, 1000u);   // the test is not vacuous: many pairs are culled
    EXPECT_GT(checked, 10000u);
}

// A ray that grazes a sphere (passes at exactly its radius from the centre) may hit what the sphere holds: the node
// test must keep the pair whatever the rounding of the distance, near the origin and far from it (the margin).
TEST(RayHierarchy, ARayGrazingASphereIsKeptNearAndFarFromTheOrigin) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    int kept = 0, cases = 0;
    for (float offset : {0.0f, 1e3f, 1e5f})
        for (int i = 0; i < 2000; ++i) {
            const glm::vec3 centre = glm::vec3(u(rng), u(rng), u(rng)) * 10.0f + offset;
            const float radius = 0.01f + 2.0f * std::abs(u(rng));
            const glm::vec3 d = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0.0f, 0.0f, 1e-3f));
            glm::vec3 n = glm::cross(d, glm::vec3(0.3f, 0.8f, 0.5f));   // a unit normal of d
            n = glm::normalize(n);
            const glm::vec3 origin = centre + radius * n - (5.0f + 10.0f * std::abs(u(rng))) * d;
            ++cases;
            if (rh_may_hit(rh_leaf(origin, d), glm::vec4(centre, radius))) ++kept;
        }
    EXPECT_EQ(kept, cases) << cases - kept << " grazing rays rejected";
}

TEST(RayHierarchy, LevelsHoldCeilOfChildrenOverBranchingAndStopAtTheLimit) {
    std::vector<RhRay> rays(10, RhRay{glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f)});
    auto levels = rh_build(rays, 4);
    ASSERT_EQ(levels.size(), 3u);   // 10 rays -> 3 nodes -> 1
    EXPECT_EQ(levels[1].size(), 3u);
    EXPECT_EQ(levels[2].size(), 1u);
    levels = rh_build(std::vector<RhRay>(100, rays[0]), 4, 2);
    ASSERT_EQ(levels.size(), 3u);   // --levels 2: 100 -> 25 -> 7, no root
    EXPECT_EQ(levels[2].size(), 7u);
    EXPECT_EQ(rh_build(std::vector<RhRay>(1, rays[0]), 8).size(), 2u);   // one ray still gets a node above it
}

TEST(RayHierarchy, BranchingIsFourEightOrSixteen) {
    for (int b : {4, 8, 16}) EXPECT_TRUE(valid_branching(b));
    for (int b : {-4, 0, 1, 2, 3, 5, 32}) EXPECT_FALSE(valid_branching(b));
}

TEST(RayHierarchy, ZeroAndNonFiniteDirectionsGiveEmptyLeavesWhichUnionsSkip) {
    EXPECT_TRUE(rh_leaf(glm::vec3(0.0f), glm::vec3(0.0f)).empty());
    EXPECT_TRUE(rh_leaf(glm::vec3(0.0f), glm::vec3(NAN, 0.0f, 1.0f)).empty());
    EXPECT_TRUE(rh_leaf(glm::vec3(INFINITY, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 1.0f)).empty());
    EXPECT_FALSE(rh_leaf(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1e-38f)).empty());   // tiny is not zero
    const RhNode kids[2] = {rh_leaf(glm::vec3(0.0f), glm::vec3(0.0f)), rh_leaf(glm::vec3(1.0f), glm::vec3(0, 0, 1))};
    const RhNode u = rh_union(kids, 2);
    EXPECT_FALSE(u.empty());
    EXPECT_LT(u.cone.w, 1e-3f);   // only the valid ray counts
    EXPECT_TRUE(rh_union(kids, 1).empty());
    EXPECT_FALSE(rh_may_hit(rh_union(kids, 1), glm::vec4(0.0f, 0.0f, 0.0f, 1e30f)));   // an empty node hits nothing
}

TEST(RayHierarchy, OppositeDirectionsCoverEveryDirection) {
    const RhNode kids[2] = {rh_leaf(glm::vec3(0.0f), glm::vec3(1, 0, 0)), rh_leaf(glm::vec3(0.0f), glm::vec3(-1, 0, 0))};
    const RhNode u = rh_union(kids, 2);
    EXPECT_GE(u.cone.w, kRhAllDirections);
    EXPECT_TRUE(rh_may_hit(u, glm::vec4(0.0f, 50.0f, 0.0f, 0.1f)));   // even at 90 degrees from both rays
}

TEST(RayHierarchy, IdenticalRaysGiveAPointSphereAndAThinCone) {
    const RhNode leaf = rh_leaf(glm::vec3(1, 2, 3), glm::vec3(0, 0, 2));
    const RhNode kids[4] = {leaf, leaf, leaf, leaf};
    const RhNode u = rh_union(kids, 4);
    EXPECT_LE(u.sphere.w, 1e-3f);
    EXPECT_LE(u.cone.w, 2e-4f);
    EXPECT_FALSE(rh_may_hit(u, glm::vec4(1.0f, 2.0f, -5.0f, 1.0f)));   // behind the rays
    EXPECT_TRUE(rh_may_hit(u, glm::vec4(1.0f, 2.0f, 50.0f, 0.01f)));   // ahead of them
    EXPECT_FALSE(rh_may_hit(u, glm::vec4(1.5f, 2.0f, 50.0f, 0.1f)));   // beside their path
}

}  // namespace
}  // namespace rt
