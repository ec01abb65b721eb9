// Alpha cut-outs on the CPU (opacity.h, docs/shading.md "Alpha: cut-outs and blending"): the opacity test itself and
// the effect analysis (stage 01's brute force honouring it: 01_naive/brute_force_cutouts_test.cpp; stage 03's grid:
// 03_uniform_grid/grid_cutouts_test.cpp).
#include "opacity.h"

#include <gtest/gtest.h>

#include "whitted.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "tests/cutout_scenes.h"

namespace rt {
namespace {

TEST(Opacity, FactorAlphaOnlyIsOpaqueExactlyAtTheCutoff) {
    EXPECT_TRUE(surface_opaque(one_triangle(masked(0.5f, 0.5f)), 0, 0.2f, 0.2f));   // glTF: >= cutoff is opaque
    EXPECT_FALSE(surface_opaque(one_triangle(masked(std::nextafter(0.5f, 0.0f), 0.5f)), 0, 0.2f, 0.2f));
    EXPECT_TRUE(surface_opaque(one_triangle(masked(0.0f, 0.0f)), 0, 0.2f, 0.2f));    // cutoff 0: nothing cut
    EXPECT_EQ(surface_opacity(one_triangle(masked(0.25f, 0.5f)), 0, 0.3f, 0.1f), 0.25f);
}

TEST(Opacity, OpaqueMaterialsIgnoreAlphaAndBlendCutsAtHalf) {
    Material m = masked(0.1f, 0.05f);
    m.alpha_mode = AlphaMode::Opaque;
    EXPECT_TRUE(surface_opaque(one_triangle(m), 0, 0.2f, 0.2f));
    m.alpha_mode = AlphaMode::Blend;   // alphaCutoff is not used by BLEND: 0.5
    EXPECT_EQ(alpha_test_cutoff(m), 0.5f);
    EXPECT_FALSE(surface_opaque(one_triangle(m), 0, 0.2f, 0.2f));
    m.base_color.a = 0.5f;
    EXPECT_TRUE(surface_opaque(one_triangle(m), 0, 0.2f, 0.2f));
}

TEST(Opacity, TextureAlphaIsSampledBilinearlyAtTheInterpolatedUv) {
    // 2 x 1 texture, alpha 0 on the left texel and 255 on the right; bilinear between the texel centres (u 0.25
    // and 0.75), so alpha rises linearly from 0 to 1 there.
    Scene s = one_triangle(masked(0.8f, 0.4f));
    Texture t;
    t.width = 2;
    t.height = 1;
    t.rgba8 = {255, 255, 255, 0, 255, 255, 255, 255};
    s.textures = {t};
    s.materials[0].base_color_texture = 0;
    // u = 0.5 (barycentric u of vertex 1 = the uv's x): alpha 0.5, opacity 0.8 * 0.5 = 0.4, at the cutoff.
    EXPECT_EQ(surface_opacity(s, 0, 0.5f, 0.25f), 0.8f * 0.5f);
    EXPECT_TRUE(surface_opaque(s, 0, 0.5f, 0.25f));
    EXPECT_FALSE(surface_opaque(s, 0, 0.45f, 0.25f));
    EXPECT_EQ(surface_opacity(s, 0, 0.3f, 0.1f), 0.8f * sample_texture(t, {0.3f, 0.1f}).a);
    // The same uv as surface_point interpolates, in double geometry too.
    Ray<double> ray;
    Hit<double> hit;
    hit.triangle = 0;
    hit.u = 0.6;
    hit.v = 0.3;
    EXPECT_EQ(surface_opacity(s, 0, hit.u, hit.v), 0.8f * sample_texture(t, surface_point(s, ray, hit).uv).a);
}

TEST(Opacity, EffectAnalysisAsksForCutoutsOnlyWhenATriangleUsesAMaskOrBlendMaterial) {
    EXPECT_TRUE(analyze_effects(flatten(make_builtin_scene("cutouts"), {})).cutouts);
    for (const char* name : {"whitted", "cornell", "diffuse"})
        EXPECT_FALSE(analyze_effects(flatten(make_builtin_scene(name), {})).cutouts) << name;
    Scene s = one_triangle(masked(1.0f, 0.5f));
    s.materials.push_back(s.materials[0]);
    s.materials[0].alpha_mode = AlphaMode::Opaque;   // the MASK material (1) is used by no triangle
    EXPECT_FALSE(analyze_effects(s).cutouts);
    EXPECT_TRUE(resolve_effects("cutouts", s).cutouts);
    EXPECT_TRUE(resolve_effects("all", s).cutouts);
    EXPECT_EQ(resolve_effects("cutouts,shadows", s).names(), (std::vector<std::string>{"shadows", "cutouts"}));
}

}  // namespace
}  // namespace rt
