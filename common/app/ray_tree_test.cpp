// --pixel's ray tree (ray_tree.h): the order a reader follows (each ray, its shadow rays, then its reflection and
// refraction subtrees), work added up per ray, and work for no recorded ray kept visible.
#include <gtest/gtest.h>

#include "ray_tree.h"

namespace rt {
namespace {

HitRecord ray(std::uint32_t sample, std::uint32_t path, RayKind kind, std::uint32_t light = 0,
              std::uint32_t pixel = 7) {
    HitRecord r;
    r.sample = sample;
    r.pixel = pixel;
    r.path = path;
    r.kind_light = std::uint32_t(kind) | light << 8;
    return r;
}

std::uint32_t key(const HitRecord& r) { return r.kind_light; }

TEST(RayTree, PreOrderWithShadowRaysUnderTheirHitAndSamplesApart) {
    using K = RayKind;
    // Given out of order, as a wavefront records them (depth by depth, shadow rays after their pass).
    const std::vector<HitRecord> hits = {ray(0, 3, K::Refraction), ray(0, 2, K::Reflection), ray(0, 1, K::Shadow, 1),
                                         ray(0, 4, K::Reflection), ray(1, 1, K::Primary),   ray(0, 1, K::Primary),
                                         ray(0, 2, K::Shadow, 0),  ray(0, 1, K::Shadow, 0), ray(0, 7, K::Refraction),
                                         ray(0, 1, K::Primary, 0, 8)};   // another pixel
    const std::vector<RayTreeLine> lines = ray_tree(hits, {}, 7);
    ASSERT_EQ(lines.size(), 9u);
    const std::vector<std::pair<std::uint32_t, std::uint32_t>> order = {
        {1, key(ray(0, 1, K::Primary))}, {1, key(ray(0, 1, K::Shadow, 0))}, {1, key(ray(0, 1, K::Shadow, 1))},
        {2, key(ray(0, 2, K::Reflection))}, {2, key(ray(0, 2, K::Shadow, 0))}, {4, key(ray(0, 4, K::Reflection))},
        {3, key(ray(0, 3, K::Refraction))}, {7, key(ray(0, 7, K::Refraction))}, {1, key(ray(1, 1, K::Primary))}};
    for (std::size_t i = 0; i < order.size(); ++i) {
        EXPECT_EQ(lines[i].ray.path, order[i].first) << i;
        EXPECT_EQ(lines[i].ray.kind_light, order[i].second) << i;
    }
    EXPECT_EQ(lines.back().ray.sample, 1u);
    EXPECT_EQ(lines[0].depth, 0);
    EXPECT_EQ(lines[1].depth, 1);   // a shadow ray sits under its hit
    EXPECT_EQ(lines[5].depth, 2);   // path 4: two bounces
}

TEST(RayTree, WorkInPartsAddsUpAndWorkForNoRecordedRayIsShown) {
    const std::vector<HitRecord> hits = {ray(0, 1, RayKind::Primary), ray(0, 1, RayKind::Shadow, 2)};
    const std::uint32_t shadow = std::uint32_t(RayKind::Shadow) | 2u << 8;
    const std::vector<RayWork> work = {{0, 1, 0, 9, 0},       {0, 1, shadow, 30, 4}, {0, 1, shadow, 12, 1},
                                       {0, 2, 2, 5, 5}};   // a reflection the stage did not record
    const std::vector<RayTreeLine> lines = ray_tree(hits, work, 7);
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_EQ(lines[0].tests, 9u);
    EXPECT_EQ(lines[1].tests, 42u);
    EXPECT_EQ(lines[1].steps, 5u);
    EXPECT_EQ(lines[2].ray.path, 2u);
    EXPECT_EQ(lines[2].ray.triangle, -2);
    const nlohmann::json j = ray_tree_json(lines, 3, 4, 56, "grid cells");
    EXPECT_EQ(j["tests"], 56);
    EXPECT_EQ(j["heatmap_tests"], 56);
    EXPECT_EQ(j["work_without_a_ray"], 1);
    const std::string text = format_ray_tree(lines, 3, 4, 56, "grid cells");
    EXPECT_NE(text.find("pixel (3, 4): 3 rays, 56 ray/triangle tests (its heatmap value: 56), 10 grid cells"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("no such ray in the stage's records"), std::string::npos) << text;
}

}  // namespace
}  // namespace rt
