// Stage 03's CPU grid (uniform_grid.cpp) with alpha cut-outs (common/trace/opacity.h): brute force's hits, exactly.
#include <gtest/gtest.h>

#include <random>

#include "common/scene/builtin/builtin_scenes.h"
#include "01_naive/brute_force_tracer.h"
#include "uniform_grid.h"

namespace rt {
namespace {

// Stage 03's CPU grid with cut-outs gives brute force's hits exactly, ray for ray, on the built-in scene.
TEST(GridCutouts, CpuGridGivesBruteForcesHitsThroughCutouts) {
    const Scene scene = flatten(make_builtin_scene("cutouts"), {});
    const CpuGrid grid = build_grid(scene, choose_resolution(scene.bounds, scene.triangle_count(), kDefaultGridLambda));
    const BruteForceTracer<float> tracer(scene, IntersectMethod::Watertight, true);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> x(-1.5f, 1.5f), y(0.1f, 2.5f);
    int through = 0;
    for (int i = 0; i < 4000; ++i) {
        Ray<float> ray;
        ray.origin = scene.camera.position;
        ray.direction = glm::normalize(glm::vec3(x(rng), y(rng), -0.6f) - ray.origin);
        Hit<float> expected;
        RayCounters c;
        tracer.closest(ray, expected, c);
        const Hit<float> got = grid_closest_hit(grid, scene.positions, ray, IntersectMethod::Watertight, nullptr, &scene);
        ASSERT_EQ(got.triangle, expected.triangle) << "ray " << i;
        ASSERT_EQ(got.t, expected.t) << "ray " << i;
        const Hit<float> solid = grid_closest_hit(grid, scene.positions, ray, IntersectMethod::Watertight);
        if (solid.triangle != got.triangle) ++through;
    }
    EXPECT_GT(through, 200) << "many rays pass through the fence's holes";
}

}  // namespace
}  // namespace rt
