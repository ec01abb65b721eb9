// Stage 02's tie rule: a camera ray through the edge two triangles share hits both at the same t, and the G-buffer's
// 3x3 neighbourhood holds both, so primary_hits.comp must pick the lowest id, as stage 01's brute force does
// (BruteForceTracer.TiesAtEqualTGoToTheLowestTriangleId). A square facing the camera head-on, split along the
// diagonal that the pixels (i, i) of a square image look through exactly (the camera ray's x and y are then
// negatives of each other, bit for bit): about one pixel per row is such a tie.
#include <gtest/gtest.h>

#include "01_naive/naive_renderer.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/scene/builtin/builtin_builders.h"
#include "common/scene/effects.h"
#include "01_naive/brute_force_tracer.h"
#include "hybrid_renderer.h"

namespace rt {
namespace {

Scene square_split_along_the_view_diagonal() {
    SceneAsset a;
    a.name = "diagonal";
    Material white;
    white.metallic = 0.0f;
    const int m = add_material(a, white);
    // Corners (1, -1), (1, 1), (-1, 1), (-1, -1) at z = 0, facing +z; triangles (0, 1, 2) and (0, 2, 3) share the
    // diagonal from (1, -1) to (-1, 1): x = -y, where pixel (i, i) looks (image rows go down, y up).
    add_mesh_node(a, "square", make_quad({0, 0, 0}, {0, 1, 0}, {-1, 0, 0}, 1.0f, m));
    Camera c;
    c.yfov = 0.5f;
    c.znear = 0.01f;
    a.cameras.push_back(c);
    Node n;
    n.name = "camera";
    n.camera = 0;
    n.translation = {0, 0, 3};   // looking down -z at the square
    a.nodes.push_back(n);
    a.roots.push_back(int(a.nodes.size()) - 1);
    FlattenOptions options;
    options.aspect = 1.0f;
    return flatten(a, options);
}

TEST(HybridRenderer, PrimaryRaysThroughASharedEdgeTieToTheLowestIdAsStage01) {
    gpu::test_context();
    const int size = 48;
    const Scene scene = square_split_along_the_view_diagonal();
    ASSERT_EQ(scene.triangle_count(), 2u);
    RenderSettings settings;
    settings.width = settings.height = size;
    settings.effects = analyze_effects(scene);
    settings.record_hits = true;
    const FrameResult stage02 = HybridRenderer().render(scene, settings);
    const FrameResult stage01 = NaiveRenderer().render(scene, settings);

    // The pixels whose camera ray hits both triangles at the same t (stage 01's intersection test says so).
    std::vector<int> tie(std::size_t(size * size), 0);
    int ties = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const Ray<float> ray = camera_ray<float>(scene.camera, size, size, float(x) + 0.5f, float(y) + 0.5f);
            float t[2], u, v;
            const WatertightRay<float> w(ray.direction);
            bool hit[2];
            for (int k = 0; k < 2; ++k)
                hit[k] = intersect_watertight(ray, w, scene.positions[3 * k], scene.positions[3 * k + 1],
                                              scene.positions[3 * k + 2], t[k], u, v);
            if (hit[0] && hit[1] && t[0] == t[1]) {
                tie[std::size_t(y * size + x)] = 1;
                ++ties;
            }
        }
    ASSERT_GE(ties, size / 2) << "the diagonal's pixels should be ties; the setup no longer makes them";
    auto primary_triangles = [&](const FrameResult& r) {
        std::vector<int> ids(std::size_t(size * size), -2);
        for (const HitRecord& h : r.hits)
            if (ray_kind(h.kind_light) == RayKind::Primary) ids[h.pixel] = h.triangle;
        return ids;
    };
    const std::vector<int> a = primary_triangles(stage02), b = primary_triangles(stage01);
    int checked = 0;
    for (std::size_t p = 0; p < a.size(); ++p) {
        if (!tie[p]) continue;
        ++checked;
        EXPECT_EQ(b[p], 0) << "stage 01, pixel " << p;
        EXPECT_EQ(a[p], b[p]) << "pixel " << p << " (x = y = " << p % std::size_t(size) << "): a tie at equal t";
    }
    EXPECT_EQ(checked, ties);
}

}  // namespace
}  // namespace rt
