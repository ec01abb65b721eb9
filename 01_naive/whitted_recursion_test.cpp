// Whitted's secondary rays (common/trace/whitted.h), traced with stage 01's brute force (exercise 01.whitted_recursion
// grades against these): a reflection ray per mirror bounce up to --max-depth, refraction only where Snell's law has a
// solution, the cut-off on the path's weight, the ray counts per kind, the path numbers of the ray tree (2p
// reflection, 2p + 1 refraction) and the side of the surface each child starts on. Scenes of one or two squares, so
// every count is known by hand.
#include <gtest/gtest.h>

#include <vector>

#include "common/scene/effects.h"
#include "01_naive/brute_force_tracer.h"
#include "common/trace/whitted.h"

namespace rt {
namespace {

// A 20 x 20 square in the plane z = `z`, facing +z (up) or -z, of material `material`.
void add_square(Scene& s, float z, bool up, std::uint32_t material) {
    const glm::vec3 a{-10, -10, z}, b{10, -10, z}, c{10, 10, z}, d{-10, 10, z};
    const glm::vec3 n{0, 0, up ? 1.0f : -1.0f};
    if (up)
        s.positions.insert(s.positions.end(), {a, b, c, a, c, d});
    else
        s.positions.insert(s.positions.end(), {a, c, b, a, d, c});
    for (int i = 0; i < 6; ++i) {
        s.normals.push_back(n);
        s.uvs.push_back({0, 0});
    }
    s.material_ids.insert(s.material_ids.end(), {material, material});
}

Material mirror(float reflectance) {
    Material m;
    m.base_color = glm::vec4(glm::vec3(reflectance), 1.0f);
    m.metallic = 1.0f;
    m.roughness = 0.0f;
    return m;
}

Material glass() {
    Material m;
    m.metallic = 0.0f;
    m.roughness = 0.0f;
    m.transmission = 1.0f;
    m.ior = 1.5f;
    return m;
}

struct Traced {
    RayCounters counters;
    std::vector<HitRecord> records;
    const HitRecord* path(std::uint32_t p) const {
        for (const HitRecord& r : records)
            if (r.path == p && ray_kind(r.kind_light) != RayKind::Shadow) return &r;
        return nullptr;
    }
};

Traced trace(const Scene& s, const Ray<float>& primary, int max_depth, float cutoff = kDefaultCutoff,
             bool reflections = true, bool refractions = true, FresnelMode fresnel = FresnelMode::Exact,
             glm::vec3* color = nullptr) {
    const BruteForceTracer<float> tracer(s, IntersectMethod::Watertight);
    WhittedSettings ws;
    ws.fresnel = fresnel;
    ws.effects = analyze_effects(s);
    ws.effects.reflections = ws.effects.reflections && reflections;
    ws.effects.refractions = ws.effects.refractions && refractions;
    ws.max_depth = max_depth;
    ws.cutoff = cutoff;
    Traced t;
    const HitLog log{&t.records};
    t.counters.rays[int(RayKind::Primary)]++;
    const glm::vec3 c = Whitted<float, BruteForceTracer<float>>(s, tracer, ws)
                            .radiance(primary, 0, glm::vec3(1.0f), t.counters, &log);
    EXPECT_TRUE(all_finite(c));
    if (color) *color = c;
    return t;
}

// Two perfect mirrors facing each other (z = 0 up, z = 2 down): a ray bounces between them until the depth runs out.
Scene mirror_pair(float reflectance) {
    Scene s;
    s.materials = {mirror(reflectance)};
    add_square(s, 0.0f, true, 0);
    add_square(s, 2.0f, false, 0);
    return s;
}

TEST(WhittedRecursion, AMirrorSpawnsOneReflectionPerBounceUpToTheMaxDepth) {
    const Scene s = mirror_pair(1.0f);
    for (int depth : {0, 1, 2, 5}) {
        const Traced t = trace(s, Ray<float>{{0.1f, 0.2f, 1.0f}, glm::normalize(glm::vec3(0.05f, 0.0f, -1.0f))}, depth);
        EXPECT_EQ(t.counters.rays[int(RayKind::Reflection)], std::uint64_t(depth)) << "max depth " << depth;
        EXPECT_EQ(t.counters.rays[int(RayKind::Refraction)], 0u) << "a mirror refracts nothing";
        EXPECT_EQ(t.counters.intersection_tests, std::uint64_t(depth + 1) * 4) << "each ray tests the 4 triangles";
        // The ray tree: path 1, then 2, 4, 8, ... each one bounce further, alternating between the mirrors.
        std::uint32_t p = 1;
        for (int k = 0; k <= depth; ++k, p *= 2) {
            const HitRecord* r = t.path(p);
            ASSERT_NE(r, nullptr) << "no ray with path " << p;
            ASSERT_GE(r->triangle, 0) << "path " << p << " hits a mirror";
            EXPECT_EQ(r->triangle / 2, k % 2 == 0 ? 0 : 1) << "path " << p;
            if (k > 0) {   // the child starts on the side of the mirror it left, heading away from it
                const float z = r->origin[2], dz = r->direction[2];
                EXPECT_TRUE(k % 2 == 1 ? (z > 0.0f && z < 1e-3f && dz > 0.0f) : (z < 2.0f && z > 2.0f - 1e-3f && dz < 0.0f))
                    << "path " << p << " starts at z " << z << " going " << dz;
                EXPECT_NEAR(glm::length(glm::vec3(r->direction[0], r->direction[1], r->direction[2])), 1.0f, 1e-6f);
            }
        }
        EXPECT_EQ(t.path(p), nullptr) << "a ray beyond the max depth";
    }
}

TEST(WhittedRecursion, TheCutoffStopsAPathWhoseWeightFallsBelowIt) {
    // Reflectance 0.5: the k-th reflection carries 0.5^k. With cut-off 0.1 the children of weight 0.5, 0.25 and
    // 0.125 are traced, 0.0625 is not.
    const Scene s = mirror_pair(0.5f);
    const Traced t = trace(s, Ray<float>{{0.1f, 0.2f, 1.0f}, {0.0f, 0.0f, -1.0f}}, 10, 0.1f);
    EXPECT_EQ(t.counters.rays[int(RayKind::Reflection)], 3u);
    const Traced all = trace(s, Ray<float>{{0.1f, 0.2f, 1.0f}, {0.0f, 0.0f, -1.0f}}, 10, 0.0f);
    EXPECT_EQ(all.counters.rays[int(RayKind::Reflection)], 10u) << "cut-off 0: only the depth stops it";
}

TEST(WhittedRecursion, EffectsTurnedOffSpawnNothing) {
    const Scene s = mirror_pair(1.0f);
    const Traced t = trace(s, Ray<float>{{0.1f, 0.2f, 1.0f}, {0.0f, 0.0f, -1.0f}}, 5, kDefaultCutoff, false, false);
    EXPECT_EQ(t.counters.rays[int(RayKind::Reflection)], 0u);
    EXPECT_EQ(t.counters.intersection_tests, 4u);
}

// Glass below z = 0 (one face, seen from either side).
Scene glass_surface() {
    Scene s;
    s.materials = {glass()};
    add_square(s, 0.0f, true, 0);
    return s;
}

TEST(WhittedRecursion, GlassReflectsAndRefractsWithTheChildrenOnEitherSide) {
    const Scene s = glass_surface();
    const glm::vec3 d = glm::normalize(glm::vec3(0.3f, 0.0f, -1.0f));
    const Traced t = trace(s, Ray<float>{{0.0f, 0.0f, 1.0f}, d}, 1);
    EXPECT_EQ(t.counters.rays[int(RayKind::Reflection)], 1u);
    EXPECT_EQ(t.counters.rays[int(RayKind::Refraction)], 1u);
    const HitRecord* reflection = t.path(2);
    const HitRecord* refraction = t.path(3);
    ASSERT_NE(reflection, nullptr);
    ASSERT_NE(refraction, nullptr);
    EXPECT_GT(reflection->origin[2], 0.0f) << "the reflection starts above the surface";
    EXPECT_GT(reflection->direction[2], 0.0f);
    EXPECT_NEAR(reflection->direction[0], d.x, 1e-6f) << "the mirror direction keeps the tangential part";
    EXPECT_LT(refraction->origin[2], 0.0f) << "the refraction starts below it";
    EXPECT_LT(refraction->direction[2], 0.0f);
    // Snell: sin(theta_t) = sin(theta_i) / 1.5, entering the glass.
    EXPECT_NEAR(refraction->direction[0], d.x / 1.5f, 1e-5f);
}

TEST(WhittedRecursion, TotalInternalReflectionSpawnsNoRefractionRay) {
    const Scene s = glass_surface();
    // From inside (below the face) at 60 degrees from the normal: 1.5 sin 60 > 1.
    const glm::vec3 steep{std::sin(1.0472f), 0.0f, std::cos(1.0472f)};
    const Traced t = trace(s, Ray<float>{{-1.0f, 0.0f, -1.0f}, steep}, 1);
    EXPECT_EQ(t.counters.rays[int(RayKind::Reflection)], 1u);
    EXPECT_EQ(t.counters.rays[int(RayKind::Refraction)], 0u);
    EXPECT_EQ(t.path(3), nullptr);
    // At 20 degrees the ray leaves the glass: both children, the refraction bent away from the normal.
    const glm::vec3 gentle{std::sin(0.349f), 0.0f, std::cos(0.349f)};
    const Traced out = trace(s, Ray<float>{{-1.0f, 0.0f, -1.0f}, gentle}, 1);
    EXPECT_EQ(out.counters.rays[int(RayKind::Refraction)], 1u);
    const HitRecord* refraction = out.path(3);
    ASSERT_NE(refraction, nullptr);
    EXPECT_GT(refraction->origin[2], 0.0f) << "it starts above the surface, outside";
    EXPECT_NEAR(refraction->direction[0], 1.5f * gentle.x, 1e-5f);
}

// --fresnel chooses the reflectance F of a dielectric, and the refraction carries 1 - F of the path: through a
// glass surface onto an emitting floor below (the reflection leaves into a black sky) a ray brings back (1 - F) times
// the floor's radiance with either formula. At 60 degrees Schlick's approximation and the exact formula differ, so a
// recursion that ignored the mode (the exact formula always) fails here.
TEST(WhittedRecursion, TheFresnelModeChoosesTheReflectanceOfGlass) {
    Scene s = glass_surface();
    Material floor;
    floor.base_color = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    floor.emissive = glm::vec3(1.0f);
    s.materials.push_back(floor);
    add_square(s, -1.0f, true, 1);
    const float theta = 1.0472f;   // 60 degrees from the normal
    const Ray<float> ray{{0.0f, 0.0f, 1.0f}, {std::sin(theta), 0.0f, -std::cos(theta)}};
    const float cos_i = std::cos(theta), eta = 1.0f / 1.5f;
    glm::vec3 exact, schlick;
    trace(s, ray, 1, kDefaultCutoff, true, true, FresnelMode::Exact, &exact);
    trace(s, ray, 1, kDefaultCutoff, true, true, FresnelMode::Schlick, &schlick);
    ASSERT_GT(exact.g, 0.0f) << "the refraction reaches the emitting floor";
    EXPECT_NEAR(schlick.g / exact.g, (1.0f - fresnel_schlick(cos_i, eta)) / (1.0f - fresnel_exact(cos_i, eta)), 1e-4f);
    EXPECT_GT(std::abs(fresnel_schlick(cos_i, eta) - fresnel_exact(cos_i, eta)), 1e-3f) << "the formulas differ here";
}

}  // namespace
}  // namespace rt
