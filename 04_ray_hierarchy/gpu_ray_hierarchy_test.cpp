// Stage 04 on the GPU:
//  - the GLSL twins (rh_common.glsl) keep the hierarchy's two properties on the adversarial ray sets (ray_sets.h):
//    every ray inside all its ancestors, and no rejected (node, triangle) pair that a ray below hits;
//  - the batch traversal on crafted rays (all directions, identical rays, one origin, zero and NaN directions, ...)
//    gives exactly brute force's closest hits and occlusion;
//  - the renderer's image, hits and ray counts equal stage 02's for every branching, a --levels limit and without
//    object culling, and under a tiny storage limit (many chunks and windows, a pruned hit list).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <tuple>
#include <cstring>
#include <random>

#include "02_raster_hybrid/hybrid_renderer.h"
#include "common/gpu/glsl_test_harness.h"
#include "common/gpu/gpu_scene.h"
#include "common/gpu/gpu_test_context.h"
#include "common/gpu/same_frame_expectations.h"
#include "common/scene/builtin_scenes.h"
#include "common/scene/effects.h"
#include "common/trace/intersect.h"
#include "gpu_ray_hierarchy.h"
#include "object_tree.h"
#include "ray_hierarchy.h"
#include "ray_hierarchy_renderer.h"
#include "ray_sets.h"
#include "tests/stage_test_fixture.h"

namespace rt {
namespace {

using gpu::Words;

std::uint32_t bits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

RhNode node_at(const std::vector<std::uint32_t>& w, std::size_t i) {
    RhNode n;
    for (int k = 0; k < 4; ++k) n.sphere[k] = gpu::word_f(w, i + k);
    for (int k = 0; k < 4; ++k) n.cone[k] = gpu::word_f(w, i + 4 + k);
    return n;
}

// rh_union in GLSL: per record, the child count and 16 children (sphere, cone); out the node (sphere, cone).
gpu::GlslTestHarness& glsl_union() {
    static gpu::GlslTestHarness join("rh_union", R"(#include "04_ray_hierarchy/shaders/rh_common.glsl"
void test_main() {
    RhNode kids[16];
    for (uint k = 0u; k < 16u; ++k) kids[k] = RhNode(in_vec4(1u + 8u * k), in_vec4(5u + 8u * k));
    const RhNode n = rh_union(kids, in_u(0u));
    out_vec4(0u, n.sphere);
    out_vec4(4u, n.cone);
})");
    return join;
}

// The hierarchy built by the GLSL functions (leaves, then unions level by level), one harness run per level.
std::vector<std::vector<RhNode>> glsl_build(const std::vector<RhRay>& rays, int b) {
    static gpu::GlslTestHarness leaf("rh_leaf", R"(#include "04_ray_hierarchy/shaders/rh_common.glsl"
void test_main() {
    const RhNode n = rh_leaf(in_vec3(0u), in_vec3(3u));
    out_vec4(0u, n.sphere);
    out_vec4(4u, n.cone);
})");
    gpu::GlslTestHarness& join = glsl_union();
    Words in;
    for (const RhRay& r : rays) in << r.origin << r.direction;
    std::vector<std::vector<RhNode>> levels(1);
    const auto out = leaf.run(in.words, rays.size(), 6, 8);
    for (std::size_t i = 0; i < rays.size(); ++i) levels[0].push_back(node_at(out, 8 * i));
    while (levels.back().size() > 1 || levels.size() == 1) {
        const std::vector<RhNode>& below = levels.back();
        const std::size_t parents = (below.size() + b - 1) / b;
        Words w;
        for (std::size_t j = 0; j < parents; ++j) {
            const std::size_t count = std::min<std::size_t>(b, below.size() - j * b);
            w << std::uint32_t(count);
            for (std::size_t k = 0; k < 16; ++k) {
                const RhNode n = k < count ? below[j * b + k] : RhNode{};
                w << n.sphere << n.cone;
            }
        }
        const auto o = join.run(w.words, parents, 129, 8);
        std::vector<RhNode> level;
        for (std::size_t j = 0; j < parents; ++j) level.push_back(node_at(o, 8 * j));
        levels.push_back(std::move(level));
    }
    return levels;
}

std::vector<glm::vec4> glsl_spheres(const std::vector<glm::vec3>& triangles) {
    static gpu::GlslTestHarness h("rh_triangle_sphere", R"(#include "04_ray_hierarchy/shaders/rh_common.glsl"
void test_main() { out_vec4(0u, rh_triangle_sphere(in_vec3(0u), in_vec3(3u), in_vec3(6u))); })");
    Words in;
    for (const glm::vec3& v : triangles) in << v;
    const auto out = h.run(in.words, triangles.size() / 3, 9, 4);
    std::vector<glm::vec4> s;
    for (std::size_t i = 0; i < triangles.size() / 3; ++i)
        s.emplace_back(gpu::word_f(out, 4 * i), gpu::word_f(out, 4 * i + 1), gpu::word_f(out, 4 * i + 2),
                       gpu::word_f(out, 4 * i + 3));
    return s;
}

TEST(GlslRayHierarchy, EveryRayInsideItsAncestorsAndNoHitRejected) {
    gpu::test_context();
    static gpu::GlslTestHarness may_hit("rh_may_hit", R"(#include "04_ray_hierarchy/shaders/rh_common.glsl"
void test_main() { out_b(0u, rh_may_hit(RhNode(in_vec4(0u), in_vec4(4u)), in_vec4(8u))); })");
    std::size_t rejected = 0;
    for (const ray_sets::Case& c : ray_sets::all())
        for (int b : {4, 8, 16}) {
            const auto levels = glsl_build(c.rays, b);
            ASSERT_EQ(levels.back().size(), 1u);
            for (std::size_t i = 0; i < c.rays.size(); ++i) {
                if (rh_leaf(c.rays[i].origin, c.rays[i].direction).empty()) {
                    EXPECT_TRUE(levels[0][i].empty()) << c.name << " ray " << i;
                    continue;
                }
                std::size_t j = i;
                for (std::size_t l = 1; l < levels.size(); ++l) {
                    j /= std::size_t(b);
                    ASSERT_TRUE(rh_contains(levels[l][j], c.rays[i].origin, c.rays[i].direction))
                        << c.name << " B=" << b << " ray " << i << " level " << l;
                }
            }
            // Every (node, triangle) pair at once through the GLSL test.
            const std::vector<glm::vec4> spheres = glsl_spheres(c.triangles);
            Words in;
            std::vector<std::pair<std::size_t, std::size_t>> pairs;   // (level, node) per record, triangle-major
            for (std::size_t t = 0; t < spheres.size(); ++t)
                for (std::size_t l = 1; l < levels.size(); ++l)
                    for (std::size_t j = 0; j < levels[l].size(); ++j) {
                        in << levels[l][j].sphere << levels[l][j].cone << spheres[t];
                        pairs.emplace_back(l, j);
                    }
            const auto out = may_hit.run(in.words, pairs.size(), 12, 1);
            const std::size_t per_triangle = pairs.size() / spheres.size();
            for (std::size_t p = 0; p < pairs.size(); ++p) {
                if (out[p] != 0) continue;
                ++rejected;
                const auto [l, j] = pairs[p];
                const std::size_t t = p / per_triangle;
                std::size_t span = 1;
                for (std::size_t k = 0; k < l; ++k) span *= std::size_t(b);
                for (std::size_t i = j * span; i < std::min(c.rays.size(), (j + 1) * span); ++i)
                    ASSERT_FALSE(ray_sets::exact_hit(c.rays[i], &c.triangles[3 * t]))
                        << c.name << " B=" << b << " level " << l << " node " << j << " triangle " << t;
            }
        }
    EXPECT_GT(rejected, 1000u);
}

// Empty children (rays of zero or non-finite direction, the padding of a last node) are left out of a union: a node
// over some children with empty ones between them is, bit for bit, the node over those children alone.
TEST(GlslRayHierarchy, EmptyChildrenAreLeftOutOfTheUnion) {
    gpu::test_context();
    gpu::GlslTestHarness& join = glsl_union();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Words w;
    const int cases = 64;
    for (int c = 0; c < cases; ++c) {
        const std::size_t n = 1 + std::size_t(c % 8);
        std::vector<RhNode> kids;
        for (std::size_t k = 0; k < n; ++k)
            kids.push_back(rh_leaf({u(rng) * 5, u(rng) * 5, u(rng) * 5}, {u(rng), u(rng), 0.5f + u(rng)}));
        std::vector<RhNode> with_empties;
        for (const RhNode& k : kids) {
            for (int e = int(rng() % 2); e > 0; --e) with_empties.push_back(RhNode{});
            with_empties.push_back(k);
        }
        if (c % 3 == 0) with_empties.insert(with_empties.begin(), RhNode{});
        for (const std::vector<RhNode>* set : {&kids, &with_empties}) {
            w << std::uint32_t(set->size());
            for (std::size_t k = 0; k < 16; ++k) {
                const RhNode node = k < set->size() ? (*set)[k] : RhNode{};
                w << node.sphere << node.cone;
            }
        }
    }
    const auto out = join.run(w.words, 2 * cases, 129, 8);
    for (int c = 0; c < cases; ++c) {
        const RhNode alone = node_at(out, 16 * std::size_t(c)), among = node_at(out, 16 * std::size_t(c) + 8);
        EXPECT_EQ(std::memcmp(&alone, &among, sizeof(RhNode)), 0) << "case " << c << ": an empty child changed the node";
        EXPECT_FALSE(alone.empty());
    }
    // No child with rays at all: the empty node.
    Words none;
    none << std::uint32_t(3);
    for (std::size_t k = 0; k < 16; ++k) none << RhNode{}.sphere << RhNode{}.cone;
    EXPECT_TRUE(node_at(join.run(none.words, 1, 129, 8), 0).empty());
}

// ---------------------------------------------------------------------------------------------------------------
// The batch traversal on crafted rays against brute force on the CPU (bit-exact twins on llvmpipe).

// `scene` moved and scaled: p * scale + offset (huge and tiny coordinates for the float padding).
Scene transformed(Scene scene, float scale, glm::vec3 offset) {
    Bounds b;
    for (glm::vec3& p : scene.positions) {
        p = p * scale + offset;
        b.add(p);
    }
    scene.bounds = b;
    return scene;
}

void expect_brute_force_answers(const Scene& scene, const std::string& what) {
    gpu::GpuScene gpu_scene;
    gpu_scene.upload(scene);
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.effects = analyze_effects(scene);
    gpu::Wavefront wavefront({"02_raster_hybrid/shaders/brute_force.glsl", {}, {}});
    wavefront.begin_frame(gpu_scene, settings);

    // Rays from inside the box: random, identical, one origin, opposite, zero/NaN/infinite directions.
    std::mt19937 g(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const glm::vec3 lo = scene.bounds.lo, size = scene.bounds.hi - scene.bounds.lo;
    auto inside = [&] {
        const glm::vec3 f(u(g), u(g), u(g));
        return lo + size * (0.05f + 0.9f * f);
    };
    std::vector<gpu::WavefrontRay> rays;
    const glm::vec3 one_origin = inside(), one_dir = ray_sets::unit(g);
    for (int i = 0; i < 1500; ++i) {
        gpu::WavefrontRay r{};
        const int kind = i < 700 ? 2 : (i < 1000 ? 3 : 1);   // reflection, refraction, then shadow rays (2 lights)
        r.origin = i % 5 == 1 ? one_origin : inside();
        r.direction = i % 7 == 3 ? one_dir : (i % 11 == 5 ? -one_dir : ray_sets::unit(g));
        if (i % 13 == 6) r.direction = glm::vec3(0.0f);
        if (i % 17 == 8) r.direction = glm::vec3(NAN, 1.0f, 0.0f);
        if (i % 19 == 9) r.direction = glm::vec3(INFINITY, 0.0f, 0.0f);
        r.tmax = kind == 1 ? 0.1f + 2.0f * u(g) : INFINITY;
        r.depth_kind = std::uint32_t(kind) << 16 | 1u;
        r.light = kind == 1 ? (i < 1250 ? 0u : 1u) : 0u;
        rays.push_back(r);
    }
    const gpu::Buffer ray_buffer = gpu::Buffer::from(rays);
    gpu::Buffer results(rays.size() * sizeof(gpu::WavefrontTraceResult));
    for (const HierarchyOptions o : {HierarchyOptions{4, 0, ObjectMode::tree}, HierarchyOptions{4, 0, ObjectMode::meshes},
                                     HierarchyOptions{16, 2, ObjectMode::triangles}, HierarchyOptions{8, 2, ObjectMode::tree}}) {
        GpuRayHierarchy h;
        h.options = o;
        h.prepare(gpu_scene, object_ranges(scene.material_ids), scene.bounds);
        h.trace({ray_buffer, 0, 1000, results, nullptr, wavefront}, false);
        const auto closest = results.download<gpu::WavefrontTraceResult>(1000);
        h.trace({ray_buffer, 1000, 500, results, nullptr, wavefront}, true);
        const auto occluded = results.download<std::uint32_t>(500);
        EXPECT_EQ(h.stats()[2].groups + h.stats()[3].groups, 2u);
        EXPECT_EQ(h.stats()[1].groups, 2u);   // one hierarchy per light
        std::size_t hits = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            Ray<float> ray;
            ray.origin = rays[i].origin;
            ray.direction = rays[i].direction;
            ray.tmax = rays[i].tmax;
            const WatertightRay<float> w(ray.direction);
            Hit<float> best;
            bool any = false;
            for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
                float tt, uu, vv;
                const glm::vec3* v = &scene.positions[3 * t];
                if (intersect_watertight(ray, w, v[0], v[1], v[2], tt, uu, vv)) {
                    any = true;
                    if (tt < best.t) {
                        best = Hit<float>{tt, uu, vv, std::int32_t(t)};
                        ray.tmax = tt;
                    }
                }
            }
            if (i < 1000) {
                ASSERT_EQ(closest[i].triangle, best.triangle) << what << " ray " << i;
                if (best.valid()) {
                    ASSERT_EQ(bits(closest[i].t), bits(best.t)) << what << " ray " << i;
                }
                hits += best.valid();
            } else {
                ASSERT_EQ(occluded[i - 1000], any ? 1u : 0u) << what << " shadow ray " << i;
            }
        }
        EXPECT_GT(hits, 500u) << what;
        EXPECT_LE(h.stats()[2].local_tests, h.stats()[2].brute_force_tests);
    }
}

TEST(GpuRayHierarchy, CraftedRaysGetBruteForcesHitsAndOcclusion) {
    gpu::test_context();
    const Scene cornell = builtin_scene("cornell");
    expect_brute_force_answers(cornell, "cornell");
    expect_brute_force_answers(transformed(cornell, 1e3f, glm::vec3(3e6f, -1e6f, 2e6f)), "cornell x1e3 at 3e6");
    expect_brute_force_answers(transformed(cornell, 1e-4f, glm::vec3(1e-3f)), "cornell x1e-4");
}

// The object tree built on the GPU (ot_build.comp and the shared radix sort) is the CPU twin's (build_object_tree):
// the same leaf order and levels, node for node; every GPU sphere holds its children; on a scene far from the
// origin and a tiny one too.
TEST(GpuObjectTree, TheGpuBuildsTheCpuTree) {
    gpu::test_context();
    const Scene cornell = builtin_scene("cornell");
    for (const auto& [what, scene] : {std::pair<std::string, Scene>{"cornell", cornell},
                                      {"spheres:45", builtin_scene("spheres:45")},
                                      {"cornell x1e3 at 3e6", transformed(cornell, 1e3f, glm::vec3(3e6f, -1e6f, 2e6f))},
                                      {"cornell x1e-4", transformed(cornell, 1e-4f, glm::vec3(1e-3f))}}) {
        gpu::GpuScene gpu_scene;
        gpu_scene.upload(scene);
        GpuRayHierarchy h;
        h.options.objects = ObjectMode::tree;
        h.prepare(gpu_scene, object_ranges(scene.material_ids), scene.bounds);
        const ObjectTree gpu = h.download_tree();
        std::vector<glm::vec4> spheres;
        for (std::size_t t = 0; t < scene.triangle_count(); ++t)
            spheres.push_back(rh_triangle_sphere(scene.positions[3 * t], scene.positions[3 * t + 1],
                                                 scene.positions[3 * t + 2]));
        const ObjectTree cpu = build_object_tree(spheres, scene.bounds.lo, scene.bounds.hi);
        ASSERT_EQ(gpu.order, cpu.order) << what;
        ASSERT_EQ(gpu.level_first, cpu.level_first) << what;
        ASSERT_EQ(gpu.level_count, cpu.level_count) << what;
        ASSERT_EQ(gpu.nodes.size(), cpu.nodes.size()) << what;
        EXPECT_EQ(h.object_levels(), cpu.levels());
        auto holds = [](glm::vec4 outer, glm::vec4 inner) {
            return glm::length(glm::dvec3(glm::vec3(outer)) - glm::dvec3(glm::vec3(inner))) + double(inner.w) <=
                   double(outer.w);
        };
        for (std::size_t i = 0; i < cpu.nodes.size(); ++i) {
            const ObjectNode &g = gpu.nodes[i], &c = cpu.nodes[i];
            ASSERT_EQ(g.first, c.first) << what << " node " << i;
            ASSERT_EQ(g.count, c.count) << what << " node " << i;
            ASSERT_EQ(g.level, c.level) << what << " node " << i;
            const float scale = std::max(glm::length(glm::vec3(c.sphere)), c.sphere.w);
            EXPECT_LE(glm::length(glm::vec3(g.sphere) - glm::vec3(c.sphere)), 1e-5f * scale) << what << " node " << i;
            EXPECT_NEAR(g.sphere.w, c.sphere.w, 1e-5f * scale) << what << " node " << i;
            for (std::uint32_t k = 0; k < g.count; ++k) {
                const glm::vec4 child = g.level == 1 ? spheres[gpu.order[g.first + k]] : gpu.nodes[g.first + k].sphere;
                ASSERT_TRUE(holds(g.sphere, child)) << what << " node " << i << " child " << k;
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------------------------
// The renderer against stage 02.

FrameResult render_rh(const Scene& s, const RenderSettings& settings, HierarchyOptions o) {
    RayHierarchyRenderer renderer;
    renderer.hierarchy_options = o;
    return renderer.render(s, settings);
}

TEST(RayHierarchyRenderer, CornellEqualsStage02ForEveryBranchingAndALevelLimit) {
    gpu::test_context();
    const Scene s = builtin_scene("cornell");
    const RenderSettings settings = test_frame_settings(s);
    HybridRenderer stage02;
    const FrameResult reference = stage02.render(s, settings);
    for (const HierarchyOptions o :
         {HierarchyOptions{4, 0, ObjectMode::tree}, HierarchyOptions{8, 0, ObjectMode::tree},
          HierarchyOptions{16, 0, ObjectMode::tree}, HierarchyOptions{8, 2, ObjectMode::tree},
          HierarchyOptions{4, 0, ObjectMode::meshes}, HierarchyOptions{8, 2, ObjectMode::meshes},
          HierarchyOptions{4, 1, ObjectMode::triangles}}) {
        const FrameResult r = render_rh(s, settings, o);
        const std::string what = "B=" + std::to_string(o.branching) + " levels " + std::to_string(o.levels) + " " +
                                 object_mode_name(o.objects);
        expect_same_frame(r, reference, what);
        const auto& refl = r.extra["ray_hierarchy"]["kinds"]["reflection"];
        // At 64x48 neighbouring rays diverge: B = 4 still skips most tests, B = 16 fewer (see README.md).
        EXPECT_LT(double(refl["percent_of_brute_force"]), o.branching == 4 ? 25.0 : 75.0) << what;
        if (o.levels > 0) {
            EXPECT_EQ(refl["levels"].size(), std::size_t(o.levels) + 1) << what;
        }
        EXPECT_LT(r.stats.counters.intersection_tests, reference.stats.counters.intersection_tests) << what;
    }
}

TEST(RayHierarchyRenderer, LaterFramesOfTheDynamicSceneEqualStage02) {
    gpu::test_context();
    for (float time : {0.0f, 0.5f}) {
        const Scene s = builtin_scene("dynamic", time);
        const RenderSettings settings = test_frame_settings(s);
        HybridRenderer stage02;
        expect_same_frame(render_rh(s, settings, {}), stage02.render(s, settings), "dynamic t=" + std::to_string(time));
    }
}

// A built-in scene on the GPU with the wavefront pipeline's frame begun over it: what GpuRayHierarchy::trace needs
// besides the rays, for the tests that trace batches of their own.
struct TraceSetup {
    explicit TraceSetup(const std::string& name) : scene(builtin_scene(name)), wavefront({"02_raster_hybrid/shaders/brute_force.glsl", {}, {}}) {
        gpu_scene.upload(scene);
        RenderSettings settings;
        settings.effects = analyze_effects(scene);
        wavefront.begin_frame(gpu_scene, settings);
    }
    Scene scene;
    gpu::GpuScene gpu_scene;
    gpu::Wavefront wavefront;
};

// The stats add up, on one group of rays (one hierarchy): with --objects triangles the top level tests every node
// with every triangle, each level's pairs come from the survivors above (at most B each), the leaves' pairs get the
// sphere test and its survivors are the local tests.
TEST(GpuRayHierarchy, PerLevelStatsAddUp) {
    gpu::test_context();
    const TraceSetup setup("cornell");
    const Scene& scene = setup.scene;
    const gpu::GpuScene& gpu_scene = setup.gpu_scene;
    const gpu::Wavefront& wavefront = setup.wavefront;
    std::mt19937 g(3);
    std::vector<gpu::WavefrontRay> rays;
    const glm::vec3 centre = scene.bounds.center();
    const glm::vec3 d = ray_sets::unit(g);
    for (int i = 0; i < 1000; ++i) {   // a coherent beam: rays from a small patch, within ~10 degrees
        gpu::WavefrontRay r{};
        r.origin = centre + 0.01f * ray_sets::unit(g);
        r.direction = glm::normalize(d + 0.15f * ray_sets::unit(g));
        r.tmax = INFINITY;
        r.depth_kind = 2u << 16 | 1u;
        rays.push_back(r);
    }
    const gpu::Buffer ray_buffer = gpu::Buffer::from(rays);
    gpu::Buffer results(rays.size() * sizeof(gpu::WavefrontTraceResult));
    for (int b : {4, 8, 16}) {
        GpuRayHierarchy h;
        h.options = HierarchyOptions{b, 0, ObjectMode::triangles};
        h.prepare(gpu_scene, object_ranges(scene.material_ids), scene.bounds);
        h.trace({ray_buffer, 0, rays.size(), results, nullptr, wavefront}, false);
        const HierarchyKindStats& k = h.stats()[2];
        ASSERT_EQ(k.groups, 1u);
        const std::size_t top = k.levels.size() - 1;
        EXPECT_EQ(k.levels[top].nodes, 1u);
        EXPECT_EQ(k.levels[top].pairs_in, scene.triangle_count());
        std::uint64_t node_tests = 0;
        for (std::size_t l = 1; l <= top; ++l) {
            EXPECT_LE(k.levels[l].pairs_out, k.levels[l].pairs_in) << "B=" << b << " level " << l;
            EXPECT_LE(k.levels[l - 1].pairs_in, std::uint64_t(b) * k.levels[l].pairs_out) << "B=" << b << " " << l;
            EXPECT_GE(k.levels[l - 1].pairs_in, k.levels[l].pairs_out) << "B=" << b << " level " << l;
            node_tests += k.levels[l].pairs_in;
        }
        // Level 0's pairs are the (ray, triangle) pairs: each gets the sphere test, and those that pass it the
        // exact test.
        EXPECT_EQ(k.sphere_tests, k.levels[0].pairs_in);
        EXPECT_EQ(k.node_tests(), node_tests);
        EXPECT_EQ(k.local_tests, k.levels[0].pairs_out);
        EXPECT_LE(k.local_tests, k.sphere_tests);
        EXPECT_EQ(k.brute_force_tests, rays.size() * scene.triangle_count());
        EXPECT_LT(k.local_tests * 10, k.brute_force_tests) << "B=" << b;   // a coherent beam culls well
    }
}

// A batch whose chunks fit one window each is traced without a read-back inside it: the GPU sizes every step's
// dispatches from the counts it wrote itself (rh_args.comp). Shadow rays of one light (one group): the read-backs are
// the batch's groups (1: their starts and kinds in one list) and, once the CPU's bound of the pairs (x4 a step)
// passes the pair capacity, one look at the real count (2), however many steps the traversal takes (a read-back per
// step before); the group's counts stay on the GPU (rh_tally.comp) until stats() reads them, once (1). With 64-pair
// buffers the chunks are cut into windows (read-backs), with the same occlusion and counts.
TEST(GpuRayHierarchy, ChunksThatFitOneWindowNeedNoReadBack) {
    gpu::test_context();
    const TraceSetup setup("cornell");
    const Scene& scene = setup.scene;
    const gpu::GpuScene& gpu_scene = setup.gpu_scene;
    const gpu::Wavefront& wavefront = setup.wavefront;
    std::mt19937 g(8);
    std::vector<gpu::WavefrontRay> rays;
    const glm::vec3 lo = scene.bounds.lo, size = scene.bounds.hi - scene.bounds.lo;
    std::uniform_real_distribution<float> u(0.1f, 0.9f);
    for (int i = 0; i < 2000; ++i) {
        gpu::WavefrontRay r{};
        r.origin = lo + size * glm::vec3(u(g), u(g), u(g));
        r.direction = ray_sets::unit(g);
        r.tmax = 0.5f * glm::length(size);
        r.depth_kind = 1u << 16 | 1u;
        rays.push_back(r);
    }
    const gpu::Buffer ray_buffer = gpu::Buffer::from(rays);
    gpu::Buffer results(rays.size() * sizeof(gpu::WavefrontTraceResult));
    std::vector<std::uint32_t> reference;
    std::uint64_t reference_tests = 0;
    for (std::size_t capacity : {std::size_t(0), std::size_t(64)}) {
        GpuRayHierarchy h;
        h.options.pair_capacity = capacity;
        h.prepare(gpu_scene, object_ranges(scene.material_ids), scene.bounds);
        h.trace({ray_buffer, 0, rays.size(), results, nullptr, wavefront}, true);
        const std::vector<std::uint32_t> occluded = results.download<std::uint32_t>(rays.size());
        const std::uint64_t trace_syncs = h.syncs;
        ASSERT_EQ(h.stats()[1].groups, 1u);
        EXPECT_EQ(h.syncs, trace_syncs + 1) << "stats() reads the GPU's sums once";
        EXPECT_EQ(h.stats()[1].groups, 1u);
        EXPECT_EQ(h.syncs, trace_syncs + 1) << "and not again while no trace ran";
        EXPECT_GT(h.chunks, 5u) << "steps of the traversal";
        if (capacity == 0) {
            EXPECT_LE(trace_syncs, 3u) << "the groups (1), one bound check (2)";
            EXPECT_LT(h.syncs, h.chunks);
            reference = occluded;
            reference_tests = h.stats()[1].node_tests();
        } else {
            EXPECT_GT(h.syncs, 4u) << "64-pair windows are read back";
            EXPECT_EQ(occluded, reference);
            EXPECT_EQ(h.stats()[1].node_tests(), reference_tests);
        }
    }
}

// More groups than the first read-back of the group list holds (kGroupsAtOnce = 64): shadow rays whose light changes
// from ray to ray, 150 groups of one ray each. All are found (a second read-back), each traced on its own, and every
// ray is occluded as it is in one group (the light does not change what a shadow ray hits).
TEST(GpuRayHierarchy, ABatchOfManyGroupsFindsEveryGroup) {
    gpu::test_context();
    const TraceSetup setup("cornell");
    const Scene& scene = setup.scene;
    std::mt19937 g(11);
    std::uniform_real_distribution<float> u(0.1f, 0.9f);
    const glm::vec3 lo = scene.bounds.lo, size = scene.bounds.hi - scene.bounds.lo;
    std::vector<gpu::WavefrontRay> rays;
    for (std::uint32_t i = 0; i < 150; ++i) {
        gpu::WavefrontRay r{};
        r.origin = lo + size * glm::vec3(u(g), u(g), u(g));
        r.direction = ray_sets::unit(g);
        r.tmax = 0.5f * glm::length(size);
        r.depth_kind = 1u << 16 | 1u;
        r.light = i % 2;   // a new group at every ray
        rays.push_back(r);
    }
    std::vector<gpu::WavefrontRay> one_group = rays;
    for (gpu::WavefrontRay& r : one_group) r.light = 0;
    gpu::Buffer results(rays.size() * 4);
    std::vector<std::uint32_t> occluded[2];
    for (int pass = 0; pass < 2; ++pass) {
        const gpu::Buffer ray_buffer = gpu::Buffer::from(pass == 0 ? rays : one_group);
        GpuRayHierarchy h;
        h.prepare(setup.gpu_scene, object_ranges(scene.material_ids), scene.bounds);
        h.trace({ray_buffer, 0, rays.size(), results, nullptr, setup.wavefront}, true);
        occluded[pass] = results.download<std::uint32_t>(rays.size());
        EXPECT_EQ(h.stats()[1].groups, pass == 0 ? 150u : 1u);
        EXPECT_EQ(h.stats()[1].rays, 150u);
    }
    EXPECT_EQ(occluded[0], occluded[1]);
    EXPECT_GT(std::count(occluded[0].begin(), occluded[0].end(), 1u), 0) << "some rays are occluded";
    EXPECT_GT(std::count(occluded[0].begin(), occluded[0].end(), 0u), 0) << "some are not";
}

std::vector<HitRecord> sorted_by_ray(std::vector<HitRecord> hits) {
    std::sort(hits.begin(), hits.end(), [](const HitRecord& a, const HitRecord& b) {
        return std::tie(a.pixel, a.sample, a.path, a.kind_light) < std::tie(b.pixel, b.sample, b.path, b.kind_light);
    });
    return hits;
}

// Pair buffers of 256 entries and a hit list of 2 entries per ray: the traversal runs in many chunks and windows and
// the hit list fills up and is pruned; the frame is the same, pair for pair, and so are the tests counted.
TEST(RayHierarchyRenderer, TinyPairBuffersGiveTheSameImageHitsAndCounts) {
    gpu::test_context();
    const Scene s = builtin_scene("cornell");
    const RenderSettings settings = test_frame_settings(s);
    const FrameResult reference = render_rh(s, settings, {});
    HierarchyOptions tiny_options;
    tiny_options.pair_capacity = 256;
    tiny_options.hit_list_per_ray = 2;
    const FrameResult tiny = render_rh(s, settings, tiny_options);
    expect_same_frame(tiny, reference, "256 pairs per buffer");
    EXPECT_EQ(tiny.stats.counters.intersection_tests, reference.stats.counters.intersection_tests);
    const auto& t = tiny.extra["ray_hierarchy"];
    const auto& r = reference.extra["ray_hierarchy"];
    EXPECT_EQ(t["pair_capacity"], 256);
    EXPECT_GT(std::uint64_t(t["windows"]), 10 * std::uint64_t(r["windows"]));
    EXPECT_GT(std::uint64_t(t["hit_list_prunes"]), 0u);
    for (const char* kind : {"shadow", "reflection", "refraction"})
        for (const char* key : {"node_tests", "local_tests", "fold_tests"})
            EXPECT_EQ(t["kinds"][kind][key], r["kinds"][kind][key]) << kind << " " << key;
}

// $RT_MAX_SSBO_BYTES = 48 KiB: the pipeline's batches, and the stage's buffers with them, shrink (3072 pairs). The
// frame equals stage 02's under the same limit, hit for hit in the same order, and the unlimited frame's image.
TEST(RayHierarchyRenderer, ATinyStorageLimitGivesStage02sFrame) {
    gpu::test_context();
    const Scene s = builtin_scene("cornell");
    const RenderSettings settings = test_frame_settings(s);
    const FrameResult unlimited = render_rh(s, settings, {});
    ::setenv("RT_MAX_SSBO_BYTES", "49152", 1);
    const FrameResult tiny = render_rh(s, settings, {});
    HybridRenderer stage02;
    const FrameResult tiny02 = stage02.render(s, settings);
    ::unsetenv("RT_MAX_SSBO_BYTES");
    expect_same_frame(tiny, tiny02, "04 vs 02 at 48 KiB");
    EXPECT_EQ(tiny.extra["ray_hierarchy"]["pair_capacity"], 3072);
    for (std::size_t i = 0; i < tiny.image.pixels.size(); ++i)
        ASSERT_EQ(tiny.image.pixels[i], unlimited.image.pixels[i]) << "pixel " << i;
    const auto a = sorted_by_ray(tiny.hits), b = sorted_by_ray(unlimited.hits);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a[i].triangle, b[i].triangle) << "ray " << i;
        ASSERT_EQ(bits(a[i].t), bits(b[i].t)) << "ray " << i;
    }
}

}  // namespace
}  // namespace rt
