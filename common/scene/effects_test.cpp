// Effects analysis of scenes and the --effects option.
#include "effects.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "common/scene/builtin/builtin_scenes.h"

namespace rt {
namespace {

Effects effects_of(const std::string& builtin) { return analyze_effects(flatten(make_builtin_scene(builtin), {})); }

// One triangle per material, no light.
Scene scene_with(const std::vector<Material>& materials) {
    Scene s;
    s.materials = materials;
    for (std::size_t i = 0; i < materials.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            s.positions.push_back(glm::vec3(float(k == 1), float(k == 2), 0));
            s.normals.push_back({0, 0, 1});
            s.uvs.push_back({0, 0});
        }
        s.material_ids.push_back(std::uint32_t(i));
    }
    return s;
}

TEST(EffectsAnalysis, DiffuseIsShadowsOnly) {
    const Effects e = effects_of("diffuse");
    EXPECT_EQ(e, (Effects{true, false, false, false}));
    EXPECT_EQ(e.names(), std::vector<std::string>{"shadows"});
}

TEST(EffectsAnalysis, WhittedAndFarNeedAllFour) {
    EXPECT_EQ(effects_of("whitted"), (Effects{true, true, true, true}));
    EXPECT_EQ(effects_of("far"), (Effects{true, true, true, true}));
    EXPECT_EQ(effects_of("whitted").names(),
              (std::vector<std::string>{"shadows", "reflections", "refractions", "textures"}));
}

TEST(EffectsAnalysis, OtherBuiltins) {
    EXPECT_EQ(effects_of("cornell"), (Effects{true, true, true, false}));
    EXPECT_EQ(effects_of("dynamic"), (Effects{true, true, false, false}));
    EXPECT_EQ(effects_of("spheres:4"), (Effects{true, false, false, false}));
}

TEST(EffectsAnalysis, NoLightMeansNoShadows) {
    Material diffuse;
    diffuse.metallic = 0;
    const Scene s = scene_with({diffuse});
    EXPECT_EQ(analyze_effects(s), Effects{});
    Scene lit = s;
    lit.lights.push_back(Light{});
    EXPECT_TRUE(analyze_effects(lit).shadows);
    Scene empty;
    empty.lights.push_back(Light{});
    EXPECT_FALSE(analyze_effects(empty).shadows);
}

TEST(EffectsAnalysis, OnlyMaterialsUsedByTrianglesCount) {
    Material diffuse;
    diffuse.metallic = 0;
    Material mirror;
    mirror.roughness = 0;
    Material glass;
    glass.metallic = 0;
    glass.roughness = 0;
    glass.transmission = 1;
    Material textured = diffuse;
    textured.base_color_texture = 0;
    Scene s = scene_with({diffuse, mirror, glass, textured});
    s.textures.push_back(Texture{"t", 1, 1, {255, 255, 255, 255}, false});
    EXPECT_EQ(analyze_effects(s), (Effects{false, true, true, true}));
    s.material_ids.assign(s.material_ids.size(), 0);   // only the diffuse material is used now
    EXPECT_EQ(analyze_effects(s), Effects{});
}

TEST(MaterialPredicates, ReflectsFollowsTheShadingContract) {
    Material m;   // glTF default: metallic 1 but roughness 1: no mirror
    EXPECT_FALSE(material_reflects(m));
    m.roughness = 0.5f;
    EXPECT_TRUE(material_reflects(m));
    m.metallic = 0;   // dielectric with F0 from ior 1.5
    EXPECT_TRUE(material_reflects(m));
    m.ior = 1.0f;
    EXPECT_FALSE(material_reflects(m));
    m.ior = 1.5f;
    m.specular = 0;
    EXPECT_FALSE(material_reflects(m));
    m.specular = 1;
    m.specular_color = glm::vec3(0);
    EXPECT_FALSE(material_reflects(m));
}

TEST(MaterialPredicates, TransmitsOnlyWhenNotFullyMetallic) {
    Material m;
    m.transmission = 1;
    EXPECT_FALSE(material_transmits(m));   // metallic 1
    m.metallic = 0.5f;
    EXPECT_TRUE(material_transmits(m));
    m.transmission = 0;
    EXPECT_FALSE(material_transmits(m));
}

// Avocado's case: factors metallic 1, roughness 1 (a rough metal, no mirror) that its metallic-roughness texture
// turns into a smooth dielectric in places.
TEST(MaterialPredicates, MetallicRoughnessTextureCountsAtItsExtremes) {
    Material m;
    m.transmission = 1;
    m.metallic_roughness_texture = 0;
    std::vector<Texture> textures{Texture{"mr", 2, 1, {0, 255, 255, 255, 0, 128, 0, 255}, false}};
    EXPECT_FALSE(material_reflects(m));                 // the factors alone
    EXPECT_TRUE(material_reflects(m, &textures));       // green 128: roughness 0.5 somewhere
    EXPECT_FALSE(material_transmits(m));
    EXPECT_TRUE(material_transmits(m, &textures));      // blue 0: a dielectric somewhere
    textures[0].rgba8 = {0, 255, 255, 255, 0, 255, 255, 255};   // rough metal everywhere
    EXPECT_FALSE(material_reflects(m, &textures));
    EXPECT_FALSE(material_transmits(m, &textures));
    Scene s = scene_with({m});
    s.textures = textures;
    EXPECT_TRUE(analyze_effects(s).textures);           // a metallic-roughness texture alone is a texture lookup
}

TEST(EffectsSpec, ResolvesAutoAllNoneAndLists) {
    const Scene s = flatten(make_builtin_scene("diffuse"), {});
    EXPECT_EQ(resolve_effects("auto", s), analyze_effects(s));
    EXPECT_EQ(resolve_effects("all", s), (Effects{true, true, true, true, true, true, true, true}));
    EXPECT_EQ(resolve_effects("none", s), Effects{});
    EXPECT_EQ(resolve_effects("textures,shadows", s), (Effects{true, false, false, true}));
    EXPECT_EQ(resolve_effects("reflections", s), (Effects{false, true, false, false}));
    EXPECT_THROW(resolve_effects("shadows,glow", s), std::invalid_argument);
    EXPECT_THROW(resolve_effects("", s), std::invalid_argument);
    EXPECT_THROW(resolve_effects("shadows,", s), std::invalid_argument);
}

TEST(EffectsSpec, ValidityCheck) {
    for (const char* ok : {"auto", "all", "none", "shadows", "shadows,reflections,refractions,textures"})
        EXPECT_TRUE(is_valid_effects_spec(ok)) << ok;
    for (const char* bad : {"", "Auto", "shadow", "shadows,,textures", "all,shadows", "caustics"})
        EXPECT_FALSE(is_valid_effects_spec(bad)) << bad;
}

}  // namespace
}  // namespace rt
