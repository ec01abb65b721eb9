// BLEND as coverage (docs/shading.md, "Alpha: cut-outs and blending"), traced by stage 01's brute force through
// Whitted: a BLEND surface of opacity alpha is shaded with weight alpha and a transparency ray carries 1 - alpha on
// through it; shadow rays read it as a cut-out at 0.5; a fully transparent texel is no hit; a BLEND surface does not
// refract; without the `blend` effect BLEND is a cut-out at 0.5 for every ray. Scenes of emissive squares, so every
// colour is known by hand.
#include <gtest/gtest.h>

#include <vector>

#include "01_naive/brute_force_tracer.h"
#include "common/scene/effects.h"
#include "common/trace/whitted.h"

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

struct Traced {
    glm::vec3 color{0.0f};
    RayCounters counters;
    std::vector<HitRecord> records;
};

const Ray<float> kDown{{0.1f, 0.2f, 5.0f}, {0.0f, 0.0f, -1.0f}};

Traced trace(const Scene& s, bool blend, int max_depth = 5) {
    WhittedSettings ws;
    ws.effects = analyze_effects(s);
    ws.effects.blend = ws.effects.blend && blend;
    ws.max_depth = max_depth;
    const BruteForceTracer<float> tracer(s, IntersectMethod::Watertight, ws.effects.cutouts, ws.effects.blend);
    const BruteForceTracer<float> shadow_tracer(s, IntersectMethod::Watertight, ws.effects.cutouts, false);
    Traced t;
    const HitLog log{&t.records};
    t.color = Whitted<float, BruteForceTracer<float>>(s, tracer, ws, &shadow_tracer)
                  .radiance(kDown, 0, glm::vec3(1.0f), t.counters, &log);
    EXPECT_TRUE(all_finite(t.color));
    return t;
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

TEST(BlendCoverage, APaneShowsAlphaOfItsColourAndOneMinusAlphaOfWhatIsBehindIt) {
    for (float alpha : {0.25f, 0.5f, 0.8f}) {
        const Traced t = trace(pane_over_wall(alpha), true);
        EXPECT_NEAR(t.color.r, alpha, 1e-6f) << alpha;
        EXPECT_NEAR(t.color.g, 1.0f - alpha, 1e-6f) << alpha;
        EXPECT_EQ(t.color.b, 0.0f);
        EXPECT_EQ(t.counters.rays[int(RayKind::Transparency)], 1u) << alpha;
        EXPECT_EQ(t.counters.rays[int(RayKind::Refraction)], 0u);
        // Two traced rays of 4 tests each: the camera ray and the transparency ray, each attributed to its kind.
        EXPECT_EQ(t.counters.intersection_tests, 8u);
        EXPECT_EQ(t.counters.tests_by_kind[int(RayKind::Primary)], 4u);
        EXPECT_EQ(t.counters.tests_by_kind[int(RayKind::Transparency)], 4u);
        // The ray tree: the camera ray (path 1) hits the pane, the transparency ray (path 3, the refraction slot)
        // starts just below it, going on in the same direction, and hits the wall.
        ASSERT_EQ(t.records.size(), 2u);
        EXPECT_EQ(t.records[0].path, 1u);
        EXPECT_EQ(t.records[0].triangle / 2, 0);
        EXPECT_EQ(t.records[1].path, 3u);
        EXPECT_EQ(t.records[1].kind_light, std::uint32_t(RayKind::Transparency));
        EXPECT_EQ(t.records[1].triangle / 2, 1);
        EXPECT_LT(t.records[1].origin[2], 1.0f);
        EXPECT_GT(t.records[1].origin[2], 1.0f - 1e-3f);
        EXPECT_EQ(t.records[1].direction[2], -1.0f);
    }
}

TEST(BlendCoverage, WithoutTheBlendEffectBlendIsACutoutAtHalfForEveryRay) {
    const Traced faint = trace(pane_over_wall(0.25f), false);
    EXPECT_EQ(faint.color, glm::vec3(0, 1, 0)) << "opacity 0.25 < 0.5: a hole, the wall shows";
    const Traced solid = trace(pane_over_wall(0.75f), false);
    EXPECT_EQ(solid.color, glm::vec3(1, 0, 0)) << "opacity 0.75 >= 0.5: the pane, whole";
    EXPECT_EQ(faint.counters.rays[int(RayKind::Transparency)] + solid.counters.rays[int(RayKind::Transparency)], 0u);
}

TEST(BlendCoverage, AFullyTransparentTexelIsNoHit) {
    const Traced t = trace(pane_over_wall(0.0f), true);
    EXPECT_EQ(t.color, glm::vec3(0, 1, 0));
    EXPECT_EQ(t.counters.rays[int(RayKind::Transparency)], 0u) << "the camera ray goes through; nothing continues";
    ASSERT_EQ(t.records.size(), 1u);
    EXPECT_EQ(t.records[0].triangle / 2, 1);
}

TEST(BlendCoverage, AnOpaqueBlendTexelSpawnsNoTransparencyRay) {
    const Traced t = trace(pane_over_wall(1.0f), true);
    EXPECT_EQ(t.color, glm::vec3(1, 0, 0));
    EXPECT_EQ(t.counters.rays[int(RayKind::Transparency)], 0u) << "weight 1 - alpha = 0 is below the cut-off";
}

TEST(BlendCoverage, TheTransparencyRayCountsAgainstTheDepthAndTheCutoff) {
    const Traced at_depth = trace(pane_over_wall(0.5f), true, 0);
    EXPECT_EQ(at_depth.counters.rays[int(RayKind::Transparency)], 0u) << "--max-depth 0: no secondary ray";
    EXPECT_NEAR(at_depth.color.r, 0.5f, 1e-6f) << "the pane still shades with weight alpha";
    EXPECT_EQ(at_depth.color.g, 0.0f);
    const Traced faint = trace(pane_over_wall(1.0f - kDefaultCutoff / 2.0f), true);
    EXPECT_EQ(faint.counters.rays[int(RayKind::Transparency)], 0u) << "weight 1 - alpha below the cut-off";
}

TEST(BlendCoverage, ABlendSurfaceDoesNotRefract) {
    const Traced t = trace(pane_over_wall(0.5f, 1.0f), true);
    EXPECT_EQ(t.counters.rays[int(RayKind::Refraction)], 0u) << "its see-through part is the transparency ray";
    EXPECT_EQ(t.counters.rays[int(RayKind::Transparency)], 1u);
    for (const HitRecord& r : t.records) EXPECT_NE(r.kind_light, std::uint32_t(RayKind::Refraction));
}

TEST(BlendCoverage, ShadowRaysReadBlendAsACutoutAtHalf) {
    // A light above a BLEND pane over a white floor: the shadow ray from the floor passes a pane of opacity 0.25
    // (below the cut-out) and is blocked by one of 0.75, while camera rays see both panes (coverage).
    for (float alpha : {0.25f, 0.75f}) {
        Scene s = pane_over_wall(alpha);
        const BruteForceTracer<float> closest(s, IntersectMethod::Watertight, true, true);
        const BruteForceTracer<float> shadow(s, IntersectMethod::Watertight, true, false);
        const Ray<float> up{{0.1f, 0.2f, 1e-3f}, {0.0f, 0.0f, 1.0f}, 10.0f};
        RayCounters counters;
        EXPECT_EQ(shadow.occluded(up, counters), alpha >= 0.5f) << alpha;
        Hit<float> hit;
        EXPECT_TRUE(closest.closest(up, hit, counters)) << alpha;
        EXPECT_EQ(hit.triangle / 2, 0) << alpha;
    }
}

}  // namespace
}  // namespace rt
