// Area lights (common/trace/area_light.h, common/scene/area_lights.cpp; docs/shading.md, "Area lights"): which
// emitters are gathered, how a light is sampled, and the hard cases of its light at a point: a 1 x 1 grid is a
// point light at the centroid, the light scales with its area, a point on the light, edge-on or behind a one-sided
// light gets none. The shadow rays' hard cases, which need a tracer, are 01_naive/area_light_shadows_test.cpp's.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "common/trace/area_light.h"
#include "common/trace/shading.h"

namespace rt {
namespace {

// A scene of one quad (corner + u edge_u + v edge_v as two triangles sharing the diagonal) emitting `radiance`
// downwards from y = height, and a floor at y = 0. Built as an asset so flatten gathers the light.
SceneAsset quad_light_scene(float half_x, float half_z, float height, glm::vec3 radiance, bool double_sided = false) {
    SceneAsset a;
    Material light;
    light.name = "light";
    light.emissive = radiance;
    light.double_sided = double_sided;
    Material floor;
    floor.name = "floor";
    floor.metallic = 0.0f;
    a.materials = {light, floor};
    Primitive quad;
    quad.positions = {{-half_x, height, -half_z}, {half_x, height, -half_z}, {half_x, height, half_z},
                      {-half_x, height, half_z}};
    quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    quad.indices = {0, 1, 2, 0, 2, 3};   // (-x,-z) (x,-z) (x,z): normal -y, facing down
    quad.material = 0;
    Primitive ground;
    ground.positions = {{-5, 0, -5}, {5, 0, -5}, {5, 0, 5}, {-5, 0, 5}};
    ground.indices = {0, 2, 1, 0, 3, 2};   // facing up
    ground.material = 1;
    a.meshes = {{"light", {quad}}, {"floor", {ground}}};
    Node n0, n1;
    n0.name = "light";
    n0.mesh = 0;
    n1.name = "floor";
    n1.mesh = 1;
    a.nodes = {n0, n1};
    a.roots = {0, 1};
    return a;
}

// The light of every cell of `light`'s grid at p (normal n) as Whitted::shade sums it, without shadows.
glm::vec3 area_irradiance(const Scene& scene, std::uint32_t light_index, LightGrid grid, glm::vec3 p, glm::vec3 n,
                          PixelSample id = {}, std::uint32_t* lit_cells = nullptr) {
    const AreaLight& area = scene.area_lights[light_index - scene.lights.size()];
    glm::vec3 sum(0.0f);
    std::uint32_t lit = 0;
    for (std::uint32_t cell = 0; cell < grid.cells(); ++cell) {
        const AreaSample s = area_light_cell(scene, grid, light_index, cell, id);
        Light point;
        if (!area_sample_as_point_light(area, s, area_light_emission(scene, area, s, true), grid.cells(), p, point))
            continue;
        glm::vec3 to_light;
        float distance;
        const glm::vec3 e = light_incidence(point, p, n, to_light, distance);
        EXPECT_TRUE(all_finite(e));
        if (e != glm::vec3(0.0f)) ++lit;
        sum += e;
    }
    if (lit_cells) *lit_cells = lit;
    return sum;
}

TEST(AreaLights, EmittersBrighterThanWhiteAreGatheredPerPrimitiveAndReplaceTheDefaultLight) {
    const Scene bright = flatten(quad_light_scene(0.5f, 0.5f, 2.0f, glm::vec3(4.0f)), {});
    ASSERT_EQ(bright.area_lights.size(), 1u);
    EXPECT_TRUE(bright.lights.empty());   // no default light: the file is lit by its emitter
    EXPECT_FALSE(bright.default_light);
    EXPECT_TRUE(analyze_effects(bright).shadows);
    const AreaLight& l = bright.area_lights[0];
    EXPECT_EQ(l.first_triangle, 0u);
    EXPECT_EQ(l.triangle_count, 2u);
    EXPECT_TRUE(l.parallelogram);
    EXPECT_FLOAT_EQ(l.area, 1.0f);
    EXPECT_LT(glm::cross(l.edge_u, l.edge_v).y, 0.0f);   // the front faces down, as the winding says

    // A glow (radiance at most 1) lights nothing under auto; all makes it a light; off drops every emitter.
    const SceneAsset dim = quad_light_scene(0.5f, 0.5f, 2.0f, glm::vec3(1.0f));
    const Scene glow = flatten(dim, {});
    EXPECT_TRUE(glow.area_lights.empty());
    EXPECT_TRUE(glow.default_light);
    FlattenOptions all;
    all.area_lights = AreaLightMode::All;
    EXPECT_EQ(flatten(dim, all).area_lights.size(), 1u);
    FlattenOptions off;
    off.area_lights = AreaLightMode::Off;
    const Scene unlit = flatten(quad_light_scene(0.5f, 0.5f, 2.0f, glm::vec3(4.0f)), off);
    EXPECT_TRUE(unlit.area_lights.empty());
    EXPECT_TRUE(unlit.default_light);   // off, for comparison: lit as before area lights existed

    // A cut-out emitter glows but lights nothing (its holes would pass light).
    SceneAsset masked = quad_light_scene(0.5f, 0.5f, 2.0f, glm::vec3(4.0f));
    masked.materials[0].alpha_mode = AlphaMode::Mask;
    EXPECT_TRUE(flatten(masked, all).area_lights.empty());

    // Two nodes instancing the light's mesh are two lights.
    SceneAsset twice = quad_light_scene(0.5f, 0.5f, 2.0f, glm::vec3(4.0f));
    Node copy = twice.nodes[0];
    copy.translation = {2.0f, 0.0f, 0.0f};
    twice.nodes.push_back(copy);
    twice.roots.push_back(2);
    const Scene two = flatten(twice, {});
    ASSERT_EQ(two.area_lights.size(), 2u);
    EXPECT_EQ(two.area_lights[1].first_triangle, 4u);   // after the floor's two triangles
    EXPECT_EQ(two.light_count(), 2u);
}

TEST(AreaLights, NonParallelogramShapesAreSampledByArea) {
    // A trapezoid (two triangles of areas 1 and 2) is no parallelogram: its triangles are picked by area.
    SceneAsset a = quad_light_scene(0.5f, 0.5f, 2.0f, glm::vec3(4.0f));
    a.meshes[0].primitives[0].positions = {{0, 2, 0}, {1, 2, 0}, {3, 2, 1}, {0, 2, 1}};
    a.meshes[0].primitives[0].indices = {0, 3, 1, 1, 3, 2};
    const Scene scene = flatten(a, {});
    ASSERT_EQ(scene.area_lights.size(), 1u);
    const AreaLight& l = scene.area_lights[0];
    EXPECT_FALSE(l.parallelogram);
    EXPECT_FLOAT_EQ(l.area, 2.0f);
    ASSERT_EQ(scene.area_light_cdf.size(), 2u);
    EXPECT_FLOAT_EQ(scene.area_light_cdf[0], 0.25f);   // triangle 0: 0.5 of 2
    EXPECT_EQ(scene.area_light_cdf[1], 1.0f);
    // A 16 x 16 grid puts a quarter of its cells on triangle 0, and every sample on the light (y = 2, inside).
    LightGrid grid;
    grid.n = 16;
    int on_first = 0;
    for (std::uint32_t cell = 0; cell < grid.cells(); ++cell) {
        const AreaSample s = area_light_cell(scene, grid, 0, cell, {});
        EXPECT_FLOAT_EQ(s.position.y, 2.0f);
        EXPECT_GE(s.position.z, 0.0f);
        EXPECT_LE(s.position.z, 1.0f);
        EXPECT_GE(s.position.x, -1e-6f);
        EXPECT_LE(s.position.x, 1.0f + 2.0f * s.position.z + 1e-5f);
        EXPECT_NEAR(s.normal.y, 1.0f, 1e-6f);   // its winding faces up
        if (s.position.x <= 1.0f - s.position.z + 1e-5f && s.position.x < 1.0f) ++on_first;
    }
    EXPECT_EQ(on_first, 64);
    // Texture coordinates that are not affine over a quad make it a mesh light, not a parallelogram.
    SceneAsset bent = quad_light_scene(0.5f, 0.5f, 2.0f, glm::vec3(4.0f));
    bent.meshes[0].primitives[0].uvs[2] = {3.0f, 1.0f};
    EXPECT_FALSE(flatten(bent, {}).area_lights[0].parallelogram);
}

TEST(AreaLights, AOneByOneGridIsAPointLightAtTheCentroid) {
    const Scene scene = flatten(quad_light_scene(0.6f, 0.3f, 3.0f, glm::vec3(18.0f, 17.0f, 15.0f)), {});
    const AreaLight& l = scene.area_lights[0];
    LightGrid one;
    one.n = 1;
    const AreaSample s = area_light_cell(scene, one, 0, 0, {});
    EXPECT_NEAR(s.position.x, 0.0f, 1e-7f);
    EXPECT_NEAR(s.position.z, 0.0f, 1e-7f);
    EXPECT_FLOAT_EQ(s.position.y, 3.0f);
    for (const glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(1.5f, 0, -0.7f), glm::vec3(-2, 0.5f, 2)}) {
        const glm::vec3 n(0, 1, 0);
        // The point light a 1 x 1 grid stands for: at the centroid, intensity L A cos(theta_l).
        const glm::vec3 to_p = p - glm::vec3(0, 3, 0);
        Light point;
        point.type = LightType::Point;
        point.position = {0, 3, 0};
        point.color = glm::vec3(18.0f, 17.0f, 15.0f) / 18.0f;
        point.intensity = 18.0f * l.area * (-to_p.y / glm::length(to_p));
        glm::vec3 to_light;
        float distance;
        const glm::vec3 expected = light_incidence(point, p, n, to_light, distance);
        const glm::vec3 got = area_irradiance(scene, 0, one, p, n);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-5f * expected[c]) << c;
    }
}

TEST(AreaLights, TwiceTheAreaAtTheSameRadianceGivesTwiceTheLight) {
    LightGrid grid;
    grid.n = 8;
    const glm::vec3 p(0, 0, 0), n(0, 1, 0);
    const Scene small = flatten(quad_light_scene(0.05f, 0.05f, 10.0f, glm::vec3(5.0f)), {});
    const Scene large = flatten(quad_light_scene(0.1f, 0.05f, 10.0f, glm::vec3(5.0f)), {});
    const glm::vec3 e1 = area_irradiance(small, 0, grid, p, n), e2 = area_irradiance(large, 0, grid, p, n);
    EXPECT_NEAR(e2.x / e1.x, 2.0f, 1e-3f);   // far away: the solid angle doubles
    // In physical units: L A cos cos / d^2 (10 units under the centre: cos = 1).
    EXPECT_NEAR(e1.x, 5.0f * 0.01f / 100.0f, 1e-3f * e1.x);
    // More cells divide the same light: 1 and 16 x 16 agree far away.
    LightGrid one;
    one.n = 1;
    LightGrid fine;
    fine.n = 16;
    EXPECT_NEAR(area_irradiance(large, 0, one, p, n).x, area_irradiance(large, 0, fine, p, n).x, 1e-3f * e2.x);
}

TEST(AreaLights, NoLightOnTheLightItselfEdgeOnOrBehindAOneSidedLight) {
    const Scene one_sided = flatten(quad_light_scene(0.5f, 0.5f, 2.0f, glm::vec3(4.0f)), {});
    const Scene two_sided = flatten(quad_light_scene(0.5f, 0.5f, 2.0f, glm::vec3(4.0f), true), {});
    EXPECT_TRUE(two_sided.area_lights[0].two_sided);
    LightGrid grid;
    std::uint32_t lit = 1;
    // A point on the light itself (and a shading normal along the light's): every cell is edge-on, none lights it.
    EXPECT_EQ(area_irradiance(one_sided, 0, grid, {0.1f, 2.0f, 0.2f}, {0, -1, 0}, {}, &lit), glm::vec3(0.0f));
    EXPECT_EQ(lit, 0u);
    // Edge-on, beside the light in its plane.
    EXPECT_EQ(area_irradiance(two_sided, 0, grid, {3.0f, 2.0f, 0.0f}, {-1, 0, 0}, {}, &lit), glm::vec3(0.0f));
    EXPECT_EQ(lit, 0u);
    // Above a light that faces down: nothing, unless it is double-sided; then as much as below.
    EXPECT_EQ(area_irradiance(one_sided, 0, grid, {0.0f, 3.0f, 0.0f}, {0, -1, 0}, {}, &lit), glm::vec3(0.0f));
    const glm::vec3 above = area_irradiance(two_sided, 0, grid, {0.0f, 3.0f, 0.0f}, {0, -1, 0});
    const glm::vec3 below = area_irradiance(one_sided, 0, grid, {0.0f, 1.0f, 0.0f}, {0, 1, 0});
    EXPECT_GT(below.x, 0.0f);
    EXPECT_NEAR(above.x, below.x, 1e-6f * below.x);
    // The light behind the shaded surface (its normal faces away): nothing.
    EXPECT_EQ(area_irradiance(one_sided, 0, grid, {0.0f, 1.0f, 0.0f}, {0, -1, 0}, {}, &lit), glm::vec3(0.0f));
    EXPECT_EQ(lit, 0u);
}

TEST(AreaLights, JitterIsDeterministicPerPixelSampleAndLightAndStaysInItsCell) {
    LightGrid grid;
    grid.jitter = true;
    const glm::vec2 a = light_grid_offset(grid, {10, 0}, 3);
    EXPECT_EQ(a, light_grid_offset(grid, {10, 0}, 3));
    std::set<std::pair<float, float>> seen;
    for (std::uint32_t pixel = 0; pixel < 64; ++pixel)
        for (std::uint32_t sample = 0; sample < 4; ++sample) {
            const glm::vec2 o = light_grid_offset(grid, {pixel, sample}, 3);
            EXPECT_GE(o.x, 0.0f);
            EXPECT_LT(o.x, 1.0f);
            EXPECT_GE(o.y, 0.0f);
            EXPECT_LT(o.y, 1.0f);
            seen.insert({o.x, o.y});
        }
    EXPECT_EQ(seen.size(), 256u);   // every pixel and sample its own
    EXPECT_NE(light_grid_offset(grid, {10, 0}, 4), a);   // and every light
    grid.jitter = false;
    EXPECT_EQ(light_grid_offset(grid, {10, 0}, 3), glm::vec2(0.5f));
    // Cell (i, j) of an n x n grid holds its points: i = cell % n across, j = cell / n.
    const glm::vec2 q = light_grid_point(4, 6, glm::vec2(0.999f));
    EXPECT_GT(q.x, 0.5f);
    EXPECT_LT(q.x, 0.75f);
    EXPECT_GT(q.y, 0.25f);
    EXPECT_LT(q.y, 0.5f);
}

TEST(AreaLights, ATexturedEmitterLightsWithItsTexelAtTheSample) {
    SceneAsset a = quad_light_scene(0.5f, 0.5f, 2.0f, glm::vec3(4.0f));
    Texture stripes;   // left half black, right half white (nearest)
    stripes.width = 2;
    stripes.height = 1;
    stripes.nearest = true;
    stripes.rgba8 = {0, 0, 0, 255, 255, 255, 255, 255};
    a.textures.push_back(stripes);
    a.materials[0].emissive_texture = 0;
    const Scene scene = flatten(a, {});
    ASSERT_EQ(scene.area_lights.size(), 1u);
    LightGrid grid;
    std::uint32_t lit = 0;
    area_irradiance(scene, 0, grid, {0, 0, 0}, {0, 1, 0}, {}, &lit);
    EXPECT_EQ(lit, grid.cells() / 2);   // the black half's cells send nothing (and cast no shadow ray)
}

TEST(AreaLights, TheLightLimitIsChecked) {
    SceneAsset a = quad_light_scene(0.5f, 0.5f, 2.0f, glm::vec3(4.0f));
    a.lights.resize(kMaxLights);   // one more light than a shadow ray can name, with the quad
    for (std::size_t i = 0; i < kMaxLights; ++i) {
        Node n;
        n.light = int(i);
        a.nodes.push_back(n);
        a.roots.push_back(int(a.nodes.size() - 1));
    }
    EXPECT_THROW(flatten(a, {}), SceneError);
    FlattenOptions off;
    off.area_lights = AreaLightMode::Off;
    EXPECT_EQ(flatten(a, off).light_count(), kMaxLights);
}

TEST(AreaLights, BuiltInSoftShadowScenesAreLitByTheirCeilingLightAlone) {
    for (const char* name : {"soft_shadows", "office_soft"}) {
        SCOPED_TRACE(name);
        const Scene scene = flatten(make_builtin_scene(name), {});
        EXPECT_TRUE(scene.lights.empty());
        ASSERT_EQ(scene.area_lights.size(), 1u);
        EXPECT_TRUE(scene.area_lights[0].parallelogram);
        EXPECT_FALSE(scene.default_light);
    }
    // And no other built-in scene has an area light but material_maps' glowing panel (radiance 1.5).
    for (const std::string& name : builtin_scene_names()) {
        if (name == "soft_shadows" || name == "office_soft") continue;
        const Scene scene = flatten(make_builtin_scene(name), {});
        EXPECT_EQ(scene.area_lights.size(), name == "material_maps" ? 1u : 0u) << name;
    }
}

}  // namespace
}  // namespace rt
