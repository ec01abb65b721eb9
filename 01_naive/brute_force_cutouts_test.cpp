// Alpha cut-outs (opacity.h) in stage 01's brute-force tracer: closest and any hit see through a hole with either
// ray/triangle test (the opacity test itself: common/trace/opacity_test.cpp; stage 03's grid:
// 03_uniform_grid/grid_cutouts_test.cpp).
#include <gtest/gtest.h>

#include "01_naive/brute_force_tracer.h"
#include "common/trace/opacity.h"
#include "tests/cutout_scenes.h"

namespace rt {
namespace {

// A hole (alpha 0) in front of a wall: every ray kind passes through the hole and stops at the solid part.
TEST(Opacity, BruteForceSeesThroughHolesForClosestAndAnyHit) {
    Scene s = one_triangle(masked(1.0f, 0.5f));
    Texture t;   // 2 x 1, nearest: left half (u < 0.5) a hole
    t.width = 2;
    t.height = 1;
    t.nearest = true;
    t.rgba8 = {255, 255, 255, 0, 255, 255, 255, 255};
    s.textures = {t};
    s.materials[0].base_color_texture = 0;
    s.materials.push_back(Material{});   // the wall behind, opaque
    for (const glm::vec3& p : {glm::vec3(-1, -1, -1), glm::vec3(2, -1, -1), glm::vec3(-1, 2, -1)}) {
        s.positions.push_back(p);
        s.normals.push_back({0, 0, 1});
        s.uvs.push_back({0, 0});
    }
    s.material_ids.push_back(1);
    Ray<float> through_hole, through_solid;
    through_hole.origin = {0.2f, 0.3f, 1.0f};
    through_solid.origin = {0.7f, 0.1f, 1.0f};
    for (IntersectMethod method : {IntersectMethod::Watertight, IntersectMethod::Moller}) {
        const BruteForceTracer<float> cut(s, method, true), plain(s, method, false);
        RayCounters c;
        Hit<float> hit;
        EXPECT_TRUE(cut.closest(through_hole, hit, c));
        EXPECT_EQ(hit.triangle, 1) << "the wall behind the hole";
        EXPECT_FLOAT_EQ(hit.t, 2.0f);
        hit = Hit<float>();
        EXPECT_TRUE(plain.closest(through_hole, hit, c));
        EXPECT_EQ(hit.triangle, 0) << "without cut-outs the hole is a surface";
        hit = Hit<float>();
        EXPECT_TRUE(cut.closest(through_solid, hit, c));
        EXPECT_EQ(hit.triangle, 0);
        Ray<float> shadow = through_hole;
        shadow.tmax = 1.5f;   // stops before the wall: only the cut-out could block it
        EXPECT_FALSE(cut.occluded(shadow, c));
        EXPECT_TRUE(plain.occluded(shadow, c));
        shadow.origin = through_solid.origin;
        EXPECT_TRUE(cut.occluded(shadow, c));
    }
}

}  // namespace
}  // namespace rt
