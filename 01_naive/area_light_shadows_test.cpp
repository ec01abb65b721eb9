// The shadow rays of area lights, traced by stage 01's brute force (common/trace/area_light.h; docs/shading.md, "Area
// lights"): the light's own triangles never block them (a ray through the shared diagonal of a quad light
// included), a light inside a closed box lights only its inside, and the penumbra lies between the umbra and the
// lit floor. Every intersection test and offset method.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "01_naive/brute_force_tracer.h"
#include "common/scene/effects.h"
#include "common/trace/whitted.h"

namespace rt {
namespace {

// A floor (y = 0, 20 x 20, facing up) under a 1 x 1 quad light at y = 3 facing down, its diagonal from (-0.5, -0.5)
// to (0.5, 0.5), and optionally a closed box (12 triangles facing out) of half size `box` around the light.
SceneAsset room(float box = 0.0f, glm::vec3 occluder = glm::vec3(0.0f)) {
    SceneAsset a;
    Material floor;
    floor.metallic = 0.0f;
    Material light = floor;
    light.emissive = glm::vec3(10.0f);
    a.materials = {floor, light};
    Primitive ground;
    ground.positions = {{-10, 0, -10}, {10, 0, -10}, {10, 0, 10}, {-10, 0, 10}};
    ground.indices = {0, 2, 1, 0, 3, 2};
    ground.material = 0;
    Primitive quad;
    quad.positions = {{-0.5f, 3, -0.5f}, {0.5f, 3, -0.5f}, {0.5f, 3, 0.5f}, {-0.5f, 3, 0.5f}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    quad.material = 1;
    a.meshes = {{"floor", {ground}}, {"light", {quad}}};
    if (box > 0.0f) {
        Primitive b;
        const glm::vec3 lo(-box, 3 - box, -box), hi(box, 3 + box, box);
        for (int i = 0; i < 8; ++i) b.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
        b.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
        b.material = 0;
        a.meshes.push_back({"box", {b}});
    }
    if (occluder != glm::vec3(0.0f)) {   // a 0.6 x 0.6 card at height occluder.y
        Primitive card;
        const glm::vec3 c = occluder;
        card.positions = {{c.x - 0.3f, c.y, c.z - 0.3f}, {c.x + 0.3f, c.y, c.z - 0.3f}, {c.x + 0.3f, c.y, c.z + 0.3f},
                          {c.x - 0.3f, c.y, c.z + 0.3f}};
        card.indices = {0, 2, 1, 0, 3, 2};
        card.material = 0;
        a.meshes.push_back({"card", {card}});
    }
    for (std::size_t m = 0; m < a.meshes.size(); ++m) {
        Node n;
        n.mesh = int(m);
        a.nodes.push_back(n);
        a.roots.push_back(int(m));
    }
    return a;
}

// The radiance of the floor point under camera ray `ray`, and its shadow rays' records.
struct Shaded {
    glm::vec3 color;
    std::vector<HitRecord> records;
};
Shaded shade(const Scene& scene, const Ray<float>& ray, IntersectMethod method, OffsetMethod offset, int grid = 1,
             std::optional<Effects> effects = std::nullopt) {
    const BruteForceTracer<float> tracer(scene, method);
    WhittedSettings settings;
    settings.offset = offset;
    settings.effects = effects ? *effects : analyze_effects(scene);
    settings.light_grid.n = grid;
    const Whitted<float, BruteForceTracer<float>> whitted(scene, tracer, settings);
    Shaded s;
    RayCounters counters;
    const HitLog log{&s.records};
    s.color = whitted.radiance(ray, 0, glm::vec3(1.0f), counters, &log);
    EXPECT_EQ(counters.light_samples, counters.rays[int(RayKind::Shadow)]);
    return s;
}

Ray<float> down_to(glm::vec3 p) {   // a camera ray from above the light's side, down onto floor point p
    Ray<float> r;
    r.origin = p + glm::vec3(0.0f, 1.0f, 0.0f);
    r.direction = {0, -1, 0};
    return r;
}

TEST(AreaLightShadows, RaysThroughTheQuadsDiagonalAreNeverBlockedByTheLight) {
    const Scene scene = flatten(room(), {});
    ASSERT_EQ(scene.area_lights.size(), 1u);
    for (IntersectMethod method : {IntersectMethod::Moller, IntersectMethod::Watertight})
        for (OffsetMethod offset : {OffsetMethod::Epsilon, OffsetMethod::Robust}) {
            int blocked = 0, rays = 0;
            for (int i = 0; i < 40; ++i)
                for (int j = 0; j < 40; ++j) {
                    // A 1 x 1 grid aims at the centre, on the diagonal both triangles share.
                    const glm::vec3 p(-4.0f + 0.2f * float(i) + 0.013f, 0.0f, -4.0f + 0.2f * float(j) + 0.007f);
                    for (const HitRecord& r : shade(scene, down_to(p), method, offset).records)
                        if (ray_kind(r.kind_light) == RayKind::Shadow) blocked += r.triangle == 1, ++rays;
                }
            EXPECT_EQ(rays, 1600) << int(method) << " " << int(offset);
            EXPECT_EQ(blocked, 0) << int(method) << " " << int(offset);
        }
}

TEST(AreaLightShadows, ALightInsideAClosedBoxLightsOnlyTheInside) {
    const Scene scene = flatten(room(1.0f), {});
    ASSERT_EQ(scene.area_lights.size(), 1u);
    for (IntersectMethod method : {IntersectMethod::Moller, IntersectMethod::Watertight}) {
        // Outside: the floor below the box sees the light's cells through the box's bottom, all blocked.
        const Shaded outside = shade(scene, down_to({0.3f, 0.0f, 0.2f}), method, OffsetMethod::Robust, 4);
        int shadow = 0, blocked = 0;
        for (const HitRecord& r : outside.records)
            if (ray_kind(r.kind_light) == RayKind::Shadow) ++shadow, blocked += r.triangle == 1;
        EXPECT_EQ(shadow, 16);
        EXPECT_EQ(blocked, 16);
        // Inside: the box's floor (y = 2) under the light is lit by every cell.
        Ray<float> in;
        in.origin = {0.1f, 2.5f, 0.1f};
        in.direction = {0, -1, 0};
        const Shaded inside = shade(scene, in, method, OffsetMethod::Robust, 4);
        shadow = blocked = 0;
        for (const HitRecord& r : inside.records)
            if (ray_kind(r.kind_light) == RayKind::Shadow) ++shadow, blocked += r.triangle == 1;
        EXPECT_EQ(shadow, 16);
        EXPECT_EQ(blocked, 0);
        EXPECT_GT(inside.color.x, outside.color.x);
    }
}

TEST(AreaLightShadows, APenumbraLiesBetweenTheUmbraAndTheLitFloor) {
    // A card halfway up hides the whole light from the floor under it (x <= 0.1), part of it out to x = 1.1 (its
    // shadow on the light's plane is [-0.6 - x, 0.6 - x] against the light's [-0.5, 0.5]), none beyond.
    const Scene scene = flatten(room(0.0f, {0.0f, 1.5f, 0.0f}), {});
    std::vector<float> light;
    std::vector<int> blocked_cells;
    for (float x : {0.0f, 0.3f, 0.6f, 0.9f, 2.0f}) {
        const Shaded s = shade(scene, down_to({x, 0.0f, 0.0f}), IntersectMethod::Watertight, OffsetMethod::Robust, 8);
        int blocked = 0;
        for (const HitRecord& r : s.records) blocked += ray_kind(r.kind_light) == RayKind::Shadow && r.triangle == 1;
        light.push_back(s.color.x);
        blocked_cells.push_back(blocked);
    }
    EXPECT_EQ(blocked_cells.front(), 64);    // umbra: every cell hidden
    EXPECT_EQ(blocked_cells.back(), 0);      // lit
    EXPECT_EQ(blocked_cells[1], 48);         // penumbra: x = 0.3 sees the cells beyond x = 0.3 (2 columns of 8)
    EXPECT_EQ(blocked_cells[2], 32);         // x = 0.6: half
    EXPECT_EQ(blocked_cells[3], 16);         // x = 0.9: 2 columns hidden
    for (std::size_t i = 1; i < 4; ++i) EXPECT_GT(light[i], light[i - 1]) << i;   // brighter across the penumbra
    // Without shadows the light is summed unblocked: the umbra is lit.
    Effects no_shadows = analyze_effects(scene);
    no_shadows.shadows = false;
    const Shaded unshadowed = shade(scene, down_to({0.0f, 0.0f, 0.0f}), IntersectMethod::Watertight,
                                    OffsetMethod::Robust, 8, no_shadows);
    EXPECT_TRUE(unshadowed.records.size() == 1);   // the camera ray alone
    EXPECT_GT(unshadowed.color.x, light.back() * 0.9f);
}

}  // namespace
}  // namespace rt
