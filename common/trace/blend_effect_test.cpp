// BLEND as coverage (docs/shading.md, "Alpha: cut-outs and blending"): when a scene calls for the `blend` effect
// (a triangle uses a BLEND material; MASK stays a cut-out) and what it turns on. How such a surface is traced and
// shaded: 01_naive/blend_coverage_test.cpp.
#include <gtest/gtest.h>

#include "common/scene/effects.h"
#include "common/scene/scene.h"

namespace rt {
namespace {

// A 20 x 20 square in the plane z = `z` facing +z, of material `material`.
void add_square(Scene& s, float z, std::uint32_t material) {
    const glm::vec3 a{-10, -10, z}, b{10, -10, z}, c{10, 10, z}, d{-10, 10, z};
    s.positions.insert(s.positions.end(), {a, b, c, a, c, d});
    for (int i = 0; i < 6; ++i) {
        s.normals.push_back({0, 0, 1});
        s.uvs.push_back({0, 0});
    }
    s.material_ids.insert(s.material_ids.end(), {material, material});
}

Material emitter(glm::vec3 emission) {
    Material m;
    m.base_color = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);   // black: only the emission shows
    m.metallic = 0.0f;
    m.roughness = 1.0f;
    m.emissive = emission;
    return m;
}

// A red BLEND pane of opacity `alpha` at z = 1 over a green wall at z = 0; no light, black background.
Scene pane_over_wall(float alpha, float transmission = 0.0f) {
    Scene s;
    Material pane = emitter({1, 0, 0});
    pane.alpha_mode = AlphaMode::Blend;
    pane.base_color.a = alpha;
    pane.transmission = transmission;
    pane.ior = 1.5f;
    s.materials = {pane, emitter({0, 1, 0})};
    add_square(s, 1.0f, 0);
    add_square(s, 0.0f, 1);
    s.ambient = AmbientModel::None;
    return s;
}

TEST(BlendCoverage, TheSceneCallsForBlendOnlyWhenATriangleUsesABlendMaterial) {
    EXPECT_TRUE(analyze_effects(pane_over_wall(0.5f)).blend);
    EXPECT_TRUE(analyze_effects(pane_over_wall(0.5f)).cutouts);
    Scene mask = pane_over_wall(0.5f);
    mask.materials[0].alpha_mode = AlphaMode::Mask;
    EXPECT_FALSE(analyze_effects(mask).blend) << "MASK stays a cut-out";
    Scene unused = pane_over_wall(0.5f);
    unused.material_ids.assign(unused.material_ids.size(), 1u);
    EXPECT_FALSE(analyze_effects(unused).blend) << "no triangle uses the BLEND material";
    EXPECT_TRUE(resolve_effects("blend", unused).cutouts) << "blend turns cutouts on";
}

}  // namespace
}  // namespace rt
