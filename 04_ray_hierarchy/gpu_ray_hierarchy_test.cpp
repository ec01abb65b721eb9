// Stage 04's batch traversal on the GPU (gpu_ray_hierarchy.h): on crafted rays (all directions, identical rays, one
// origin, zero and NaN directions, ...) exactly brute force's closest hits and occlusion, on scenes moved far and
// shrunk; the object tree built as the CPU twin builds it; stats that add up; the read-backs a batch makes.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <random>

#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "common/trace/intersect.h"
#include "gpu_ray_hierarchy.h"
#include "object_tree.h"
#include "ray_hierarchy.h"
#include "ray_sets.h"
#include "tests/stage_test_fixture.h"

namespace rt {
namespace {

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

// A scene of small triangles (cornell's first's material), one around each centre.
Scene triangles_at(const std::vector<glm::vec3>& centres) {
    Scene scene = builtin_scene("cornell");
    scene.positions.clear();
    scene.normals.clear();
    scene.uvs.clear();
    scene.tangents.clear();
    scene.material_ids.assign(centres.size(), scene.material_ids[0]);
    Bounds b;
    for (glm::vec3 c : centres)
        for (glm::vec3 corner : {glm::vec3(0.0f), glm::vec3(0.25f, 0.0f, 0.0f), glm::vec3(0.0f, 0.25f, 0.0f)}) {
            scene.positions.push_back(c + corner);
            scene.normals.emplace_back(0.0f, 0.0f, 1.0f);
            scene.uvs.emplace_back(0.0f);
            b.add(c + corner);
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
    gpu::GlslTraversal per_ray("02_raster_hybrid/shaders/brute_force.glsl");
    gpu::Wavefront wavefront(per_ray);
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
    // The last two: 64-pair windows and a hit list of one entry per ray, so that the speculative try of a batch runs
    // out of room and its marked groups are traced again (gpu_ray_hierarchy.h), and the same without speculation.
    const HierarchyOptions variants[] = {
        {4, 0, ObjectMode::tree},      {4, 0, ObjectMode::meshes},           {16, 2, ObjectMode::triangles},
        {8, 2, ObjectMode::tree},      {4, 0, ObjectMode::tree, 64, 1, true}, {4, 0, ObjectMode::tree, 64, 1, false}};
    for (const HierarchyOptions& o : variants) {
        GpuRayHierarchy h;
        h.options = o;
        h.prepare(gpu_scene, object_ranges(scene.material_ids), scene.bounds);
        h.trace({ray_buffer, 0, 1000, results, nullptr, wavefront, gpu::ray_runs(rays, 0, 1000)}, false);
        const auto closest = results.download<gpu::WavefrontTraceResult>(1000);
        h.trace({ray_buffer, 1000, 500, results, nullptr, wavefront, gpu::ray_runs(rays, 1000, 500)}, true);
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
                    ASSERT_EQ(std::bit_cast<std::uint32_t>(closest[i].t), std::bit_cast<std::uint32_t>(best.t)) << what << " ray " << i;
                }
                hits += best.valid();
            } else {
                ASSERT_EQ(occluded[i - 1000], any ? 1u : 0u) << what << " shadow ray " << i;
            }
        }
        EXPECT_GT(hits, 500u) << what;
        EXPECT_LE(h.stats()[2].local_tests, h.stats()[2].brute_force_tests);
        if (o.pair_capacity == 64) {
            EXPECT_EQ(h.groups_retraced > 0, o.speculate) << what;
        }
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
// origin and a tiny one too; built by one work group or a pass a dispatch.
TEST(GpuObjectTree, TheGpuBuildsTheCpuTree) {
    gpu::test_context();
    const Scene cornell = builtin_scene("cornell");
    // Triangles in x cells 0, 1, 2, 4, ... 512 of the Morton grid: each code's highest bit is above the last's, so
    // the prefixes split one node off at a time and the level is grouped every 4 nodes (group_heads' fallback).
    std::vector<glm::vec3> centres = {glm::vec3(0.0f)};
    for (int k = 0; k < 10; ++k) centres.emplace_back(float(1 << k) + 0.5f, 0.0f, 0.0f);
    centres.emplace_back(1024.0f, 0.0f, 0.0f);
    const Scene powers_of_two = triangles_at(centres);
    for (const auto& [name, scene] : {std::pair<std::string, Scene>{"cornell", cornell},
                                      {"spheres:45", builtin_scene("spheres:45")},
                                      {"cornell x1e3 at 3e6", transformed(cornell, 1e3f, glm::vec3(3e6f, -1e6f, 2e6f))},
                                      {"cornell x1e-4", transformed(cornell, 1e-4f, glm::vec3(1e-3f))},
                                      {"one triangle", triangles_at({glm::vec3(1.0f)})},
                                      {"37 triangles at one place", triangles_at(std::vector<glm::vec3>(37))},
                                      {"codes 2^k (grouped every 4)", powers_of_two}}) {
        // Prefix groups, and every 4 nodes (the build's choice where the prefix groups' worst case passes the limit);
        // each built by one work group (ot_build.comp, mode 5) and a pass a dispatch, whatever the triangle count.
        for (const auto& [every_4, one_group] : {std::pair{false, true}, std::pair{false, false},
                                                 std::pair{true, true}, std::pair{true, false}}) {
            const std::string what =
                name + (every_4 ? ", every 4" : "") + (one_group ? ", one work group" : ", a pass a dispatch");
            gpu::GpuScene gpu_scene;
            gpu_scene.upload(scene);
            GpuRayHierarchy h;
            h.options.objects = ObjectMode::tree;
            h.tree_limit_for_testing = every_4 ? 64 : 0;
            h.one_group_tree_triangles = one_group ? scene.triangle_count() : 0;
            h.prepare(gpu_scene, object_ranges(scene.material_ids), scene.bounds);
            ASSERT_EQ(h.tree_every_4(), every_4 && scene.triangle_count() > 2) << what;
            const ObjectTree gpu = h.download_tree();
            std::vector<glm::vec4> spheres;
            for (std::size_t t = 0; t < scene.triangle_count(); ++t)
                spheres.push_back(rh_triangle_sphere(scene.positions[3 * t], scene.positions[3 * t + 1],
                                                     scene.positions[3 * t + 2]));
            const ObjectTree cpu =
                build_object_tree(spheres, scene.bounds.lo, scene.bounds.hi, scene.positions, h.tree_every_4());
            ASSERT_EQ(gpu.order, cpu.order) << what;
            ASSERT_EQ(gpu.level_first, cpu.level_first) << what;
            ASSERT_EQ(gpu.level_count, cpu.level_count) << what;
            if (name.starts_with("codes 2^k")) {
                EXPECT_EQ(cpu.level_count[0], 3u) << "12 triangles, every 4 in a cluster";
            }
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
                ASSERT_EQ(glm::vec3(g.box_lo), glm::vec3(c.box_lo)) << what << " node " << i;   // min and max: exact
                ASSERT_EQ(glm::vec3(g.box_hi), glm::vec3(c.box_hi)) << what << " node " << i;
                const float scale = std::max(glm::length(glm::vec3(c.sphere)), c.sphere.w);
                EXPECT_LE(glm::length(glm::vec3(g.sphere) - glm::vec3(c.sphere)), 1e-5f * scale)
                    << what << " node " << i;
                EXPECT_NEAR(g.sphere.w, c.sphere.w, 1e-5f * scale) << what << " node " << i;
                for (std::uint32_t k = 0; k < g.count; ++k) {
                    const glm::vec4 child =
                        g.level == 1 ? spheres[gpu.order[g.first + k]] : gpu.nodes[g.first + k].sphere;
                    ASSERT_TRUE(holds(g.sphere, child)) << what << " node " << i << " child " << k;
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------------------------
// The renderer against stage 02.

// A built-in scene on the GPU with the wavefront pipeline's frame begun over it: what GpuRayHierarchy::trace needs
// besides the rays, for the tests that trace batches of their own.
struct TraceSetup {
    explicit TraceSetup(const std::string& name)
        : scene(builtin_scene(name)), wavefront(per_ray) {
        gpu_scene.upload(scene);
        RenderSettings settings;
        settings.effects = analyze_effects(scene);
        wavefront.begin_frame(gpu_scene, settings);
    }
    Scene scene;
    gpu::GpuScene gpu_scene;
    gpu::GlslTraversal per_ray{"02_raster_hybrid/shaders/brute_force.glsl"};
    gpu::Wavefront wavefront;
};

// The stats add up, on one group of rays (one hierarchy): with --objects triangles the top level tests every node
// with every triangle, each level's pairs come from the survivors above (at most B each), the leaves' pairs get the
// sphere test, its survivors the box test, and the survivors of both are the local tests.
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
        h.trace({ray_buffer, 0, rays.size(), results, nullptr, wavefront, gpu::ray_runs(rays, 0, rays.size())},
                false);
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
        // Level 0's pairs are the (ray, triangle) pairs: each gets the sphere test, those that pass it the box test,
        // and those that pass both the exact test.
        EXPECT_EQ(k.sphere_tests, k.levels[0].pairs_in);
        EXPECT_EQ(k.node_tests(), node_tests);
        EXPECT_EQ(k.local_tests, k.levels[0].pairs_out);
        EXPECT_LE(k.box_tests, k.sphere_tests);
        EXPECT_LT(k.local_tests, k.box_tests) << "B=" << b << ": the box test culls pairs the sphere test keeps";
        // Without the box tests the nodes keep more pairs (their box test culls where a triangle's sphere is loose)
        // and the pairs the sphere test keeps are the exact tests; without both tests, every leaf pair. The sphere
        // test of the leaves changes nothing above them.
        std::uint64_t leaf_pairs_without_box = 0;
        for (const auto& [box, sphere] : {std::pair{false, true}, std::pair{false, false}}) {
            GpuRayHierarchy off;
            off.options = h.options;
            off.options.box_test = box;
            off.options.sphere_test = sphere;
            off.prepare(gpu_scene, object_ranges(scene.material_ids), scene.bounds);
            off.trace({ray_buffer, 0, rays.size(), results, nullptr, wavefront, gpu::ray_runs(rays, 0, rays.size())},
                      false);
            const HierarchyKindStats& o = off.stats()[2];
            EXPECT_EQ(o.box_tests, 0u);
            EXPECT_LT(k.leaf_pairs, o.leaf_pairs) << "B=" << b << ": the nodes' box test culls no pair";
            EXPECT_LE(k.local_tests, o.local_tests) << "B=" << b;
            if (sphere) {
                EXPECT_LE(o.local_tests, o.leaf_pairs) << "B=" << b;
                leaf_pairs_without_box = o.leaf_pairs;
            } else {
                EXPECT_EQ(o.local_tests, o.leaf_pairs) << "B=" << b;
                EXPECT_EQ(o.leaf_pairs, leaf_pairs_without_box) << "B=" << b;
            }
        }
        EXPECT_EQ(k.brute_force_tests, rays.size() * scene.triangle_count());
        EXPECT_LT(k.local_tests * 10, k.brute_force_tests) << "B=" << b;   // a coherent beam culls well
    }
}

// What one trace tested, measured on the GPU (stage 05's check of its choice of order): the tally copied before and
// after a trace, tally_pairs() of the later copy minus the earlier one's, is that trace's node tests + leaf pairs as
// stats() counts them, every kind together; copies around a second trace (refraction rays, another beam) measure it
// alone.
TEST(GpuRayHierarchy, TallyCopiesMeasureTheTraceBetweenThem) {
    gpu::test_context();
    const TraceSetup setup("cornell");
    const Scene& scene = setup.scene;
    std::mt19937 g(5);
    std::vector<gpu::WavefrontRay> rays;
    for (std::uint32_t kind : {2u, 3u}) {   // reflection, then refraction: a coherent beam each
        const glm::vec3 origin = scene.bounds.center() + 0.1f * ray_sets::unit(g), d = ray_sets::unit(g);
        for (int i = 0; i < 500; ++i) {
            gpu::WavefrontRay r{};
            r.origin = origin + 0.01f * ray_sets::unit(g);
            r.direction = glm::normalize(d + 0.2f * ray_sets::unit(g));
            r.tmax = INFINITY;
            r.depth_kind = kind << 16 | 1u;
            rays.push_back(r);
        }
    }
    const gpu::Buffer ray_buffer = gpu::Buffer::from(rays);
    gpu::Buffer results(rays.size() * sizeof(gpu::WavefrontTraceResult));
    GpuRayHierarchy h;
    h.prepare(setup.gpu_scene, object_ranges(scene.material_ids), scene.bounds);
    const std::size_t bytes = GpuRayHierarchy::tally_bytes();
    gpu::Buffer copies(3 * bytes);
    const auto pairs_in_stats = [&h] {
        std::uint64_t n = 0;
        for (const HierarchyKindStats& k : h.stats()) n += k.node_tests() + k.leaf_pairs;
        return n;
    };
    std::uint64_t before = pairs_in_stats();
    ASSERT_EQ(before, 0u);
    std::vector<std::uint64_t> traced;
    for (std::size_t t = 0; t < 2; ++t) {
        h.copy_tally(copies, t * bytes);
        h.trace({ray_buffer, t * 500, 500, results, nullptr, setup.wavefront, gpu::ray_runs(rays, t * 500, 500)},
                false);
        const std::uint64_t now = pairs_in_stats();
        traced.push_back(now - before);
        before = now;
    }
    h.copy_tally(copies, 2 * bytes);
    const std::vector<std::uint32_t> words = copies.download<std::uint32_t>(3 * bytes / 4);
    const auto at = [&](std::size_t c) { return GpuRayHierarchy::tally_pairs(words.data() + c * bytes / 4); };
    EXPECT_EQ(at(0), 0u);
    for (std::size_t t = 0; t < 2; ++t) {
        EXPECT_GT(traced[t], 0u) << "trace " << t;
        EXPECT_EQ(at(t + 1) - at(t), traced[t]) << "trace " << t;
    }
    EXPECT_GT(h.stats()[2].leaf_pairs, 0u);
    EXPECT_GT(h.stats()[3].leaf_pairs, 0u);
}

// A batch is traced without a read-back inside it: the GPU sizes every step's dispatches from the counts it wrote
// itself (the last work group of each step's rh_cull.comp), each step's children in one window. Shadow rays of one
// light (one group, which the batch's runs name: nothing is read back to find it): the only read-back is one look at
// the group mark after the batch (1); the group's counts stay on the GPU (rh_tally.comp) until stats() reads them,
// once (1). The same rays for closest hits: the fold's look at its flag after two rounds is the mark's look too (its
// rounds and the select's length stay on the GPU). With 64-pair buffers the speculative try runs out of room and the
// group is traced again, its windows cut from read-back lengths: the same occlusion and counts; the next batch of that
// size skips the try.
TEST(GpuRayHierarchy, ABatchIsTracedWithOneReadBackAtItsEnd) {
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
        EXPECT_EQ(h.syncs, 1u) << "the tree's level sizes, read once a frame after its build";
        h.syncs = 0;   // the batch's own from here
        h.trace({ray_buffer, 0, rays.size(), results, nullptr, wavefront, gpu::ray_runs(rays, 0, rays.size())},
                true);
        const std::vector<std::uint32_t> occluded = results.download<std::uint32_t>(rays.size());
        const std::uint64_t trace_syncs = h.syncs;
        ASSERT_EQ(h.stats()[1].groups, 1u);
        EXPECT_EQ(h.syncs, trace_syncs + 1) << "stats() reads the GPU's sums once";
        EXPECT_EQ(h.stats()[1].groups, 1u);
        EXPECT_EQ(h.syncs, trace_syncs + 1) << "and not again while no trace ran";
        EXPECT_GT(h.chunks, 5u) << "steps of the traversal";
        if (capacity == 0) {
            EXPECT_EQ(trace_syncs, 1u) << "one look at the group mark";
            EXPECT_EQ(h.groups_retraced, 0u);
            reference = occluded;
            reference_tests = h.stats()[1].node_tests();
        } else {
            EXPECT_EQ(h.groups_retraced, 1u) << "the try ran out of room";
            EXPECT_GT(h.syncs, 4u) << "64-pair windows are read back";
            EXPECT_EQ(occluded, reference);
            EXPECT_EQ(h.stats()[1].node_tests(), reference_tests);
            // A batch as large as one that ran out of room is traced the careful way from the start: no second try.
            h.trace({ray_buffer, 0, rays.size(), results, nullptr, wavefront, gpu::ray_runs(rays, 0, rays.size())},
                    true);
            EXPECT_EQ(h.groups_retraced, 1u);
            EXPECT_EQ(results.download<std::uint32_t>(rays.size()), reference);
        }
    }
    for (gpu::WavefrontRay& r : rays) r.depth_kind = 1u << 16 | 2u;   // reflection rays: closest hits and the fold
    const gpu::Buffer closest_rays = gpu::Buffer::from(rays);
    GpuRayHierarchy h;
    h.prepare(gpu_scene, object_ranges(scene.material_ids), scene.bounds);
    h.syncs = 0;
    h.trace({closest_rays, 0, rays.size(), results, nullptr, wavefront, gpu::ray_runs(rays, 0, rays.size())}, false);
    EXPECT_GE(h.fold_rounds, 2u);
    EXPECT_EQ(h.syncs * 2, h.fold_rounds) << "a look at the fold's flag per two rounds, the first at the mark too";
}

// Many groups: shadow rays whose light changes from ray to ray, 150 runs of one ray each (the batch's runs name them:
// nothing is read back to find them). Each is traced on its own, and every ray is occluded as it is in one group
// (the light does not change what a shadow ray hits).
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
        h.trace({ray_buffer, 0, rays.size(), results, nullptr, setup.wavefront,
                 gpu::ray_runs(pass == 0 ? rays : one_group, 0, rays.size())},
                true);
        occluded[pass] = results.download<std::uint32_t>(rays.size());
        EXPECT_EQ(h.stats()[1].groups, pass == 0 ? 150u : 1u);
        EXPECT_EQ(h.stats()[1].rays, 150u);
    }
    EXPECT_EQ(occluded[0], occluded[1]);
    EXPECT_GT(std::count(occluded[0].begin(), occluded[0].end(), 1u), 0) << "some rays are occluded";
    EXPECT_GT(std::count(occluded[0].begin(), occluded[0].end(), 0u), 0) << "some are not";
}

}  // namespace
}  // namespace rt
