// How many object-tree node tests a single ray makes, and what would lower them: a study on the CPU twin
// (object_tree.h), for docs/benchmarks.md ("Stage 04: where the node tests go"). Not part of the stage.
//
// For every reflection, refraction and transparency ray of a --dump-hits file (shadow rays are left out: the dump
// holds no occluder distance), a tree is walked top-down the way rh_cull.comp walks it for a single ray: each child of
// a node that passed is tested (rh_ray_may_hit, then rh_ray_box_test) and counted. Per ray kind, node tests per ray:
//   tree          the stage's object tree (groups at the Morton codes' prefixes), over the ray's whole length (what
//                 level 0 of the traversal costs);
//   to hit        the same with tmax cut to the ray's closest hit (what a traversal that knew it would save);
//   every 4       the tree grouped every 4 nodes whatever the codes (the stage's choice on a GPU whose storage
//                 limit the prefix groups' worst case would pass);
//   median        a 4-wide tree split top-down at the median of the widest centroid axis (two splits a node,
//                 leaves of at most 4 triangles, boxes of their vertices, spheres around the boxes).
//     build/bin/04_ray_hierarchy --scene S --width 160 --height 120 --dump-hits h.bin --out o.png
//     build/bin/object_tree_study S h.bin        (S a glTF file; builtin scenes: --export S.glb first)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <string>
#include <vector>

#include "04_ray_hierarchy/object_tree.h"
#include "common/scene/gltf/gltf_io.h"
#include "common/scene/scene.h"
#include "common/trace/hit_record.h"

using namespace rt;

namespace {

// Children tested by a single ray walking the stage's tree from its top level.
std::uint64_t tree_tests(const ObjectTree& tree, glm::vec3 o, glm::vec3 d, float tmax) {
    std::uint64_t tests = 0;
    std::vector<std::uint32_t> stack;
    const std::uint32_t top = tree.levels() - 1;
    for (std::uint32_t k = 0; k < tree.level_count[top]; ++k) stack.push_back(tree.level_first[top] + k);
    while (!stack.empty()) {
        const ObjectNode& node = tree.nodes[stack.back()];
        stack.pop_back();
        ++tests;
        if (!rh_ray_may_hit(o, d, tmax, node.sphere) ||
            !rh_ray_box_test(o, d, tmax, glm::vec3(node.box_lo), glm::vec3(node.box_hi)) || node.level == 1)
            continue;
        for (std::uint32_t k = 0; k < node.count; ++k) stack.push_back(node.first + k);   // absolute above level 1
    }
    return tests;
}

struct MedianNode {
    glm::vec3 lo{INFINITY}, hi{-INFINITY};
    glm::vec4 sphere{0.0f};
    std::vector<std::uint32_t> children;
};

struct MedianTree {
    const std::vector<glm::vec3>& v;   // 3 vertices a triangle
    std::vector<MedianNode> nodes;

    float centroid(std::uint32_t t, int axis) const { return v[3 * t][axis] + v[3 * t + 1][axis] + v[3 * t + 2][axis]; }

    // Sorts ids[b, e) around their median on the widest centroid axis; returns the median's place.
    std::size_t split(std::vector<std::uint32_t>& ids, std::size_t b, std::size_t e) const {
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (std::size_t i = b; i < e; ++i)
            for (int a = 0; a < 3; ++a) {
                lo[a] = std::min(lo[a], centroid(ids[i], a));
                hi[a] = std::max(hi[a], centroid(ids[i], a));
            }
        const glm::vec3 extent = hi - lo;
        const int axis = extent.x > extent.y ? (extent.x > extent.z ? 0 : 2) : (extent.y > extent.z ? 1 : 2);
        const std::size_t m = (b + e) / 2;
        const auto at = [&](std::size_t i) { return ids.begin() + std::ptrdiff_t(i); };
        std::nth_element(at(b), at(m), at(e),
                         [&](std::uint32_t x, std::uint32_t y) { return centroid(x, axis) < centroid(y, axis); });
        return m;
    }

    std::uint32_t build(std::vector<std::uint32_t>& ids, std::size_t b, std::size_t e) {
        MedianNode n;
        for (std::size_t i = b; i < e; ++i)
            for (int k = 0; k < 3; ++k) {
                n.lo = glm::min(n.lo, v[3 * ids[i] + k]);
                n.hi = glm::max(n.hi, v[3 * ids[i] + k]);
            }
        n.sphere = glm::vec4((n.lo + n.hi) * 0.5f, glm::length(n.hi - n.lo) * 0.5f * 1.0001f);
        const auto me = std::uint32_t(nodes.size());
        nodes.push_back(n);
        if (e - b <= kClusterSize) return me;
        const std::size_t m = split(ids, b, e), m1 = split(ids, b, m), m2 = split(ids, m, e);
        const std::size_t cuts[5] = {b, m1, m, m2, e};
        for (int k = 0; k < 4; ++k)
            if (cuts[k + 1] > cuts[k]) {
                const std::uint32_t child = build(ids, cuts[k], cuts[k + 1]);
                nodes[me].children.push_back(child);
            }
        return me;
    }

    std::uint64_t tests(glm::vec3 o, glm::vec3 d, float tmax) const {
        std::uint64_t count = 0;
        std::vector<std::uint32_t> stack = {0};
        while (!stack.empty()) {
            const MedianNode& n = nodes[stack.back()];
            stack.pop_back();
            ++count;
            if (!rh_ray_may_hit(o, d, tmax, n.sphere) || !rh_ray_box_test(o, d, tmax, n.lo, n.hi)) continue;
            stack.insert(stack.end(), n.children.begin(), n.children.end());
        }
        return count;
    }
};

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: object_tree_study SCENE.gltf HITS.bin\n");
        return 2;
    }
    try {
        const Scene scene = flatten(load_gltf(argv[1]), FlattenOptions{});
        std::vector<glm::vec4> spheres;
        const std::vector<glm::vec3>& v = scene.positions;
        for (std::size_t t = 0; t < scene.triangle_count(); ++t)
            spheres.push_back(rh_triangle_sphere(v[3 * t], v[3 * t + 1], v[3 * t + 2]));
        const ObjectTree tree = build_object_tree(spheres, scene.bounds.lo, scene.bounds.hi, v);
        const ObjectTree every_4 = build_object_tree(spheres, scene.bounds.lo, scene.bounds.hi, v, true);
        MedianTree median{v, {}};
        std::vector<std::uint32_t> ids(scene.triangle_count());
        std::iota(ids.begin(), ids.end(), 0u);
        if (!ids.empty()) median.build(ids, 0, ids.size());

        std::ifstream in(argv[2], std::ios::binary);
        char magic[8] = {};
        if (!in.read(magic, 8) || std::string(magic, 6) != "RTHITS") {
            std::fprintf(stderr, "object_tree_study: %s: not a --dump-hits file\n", argv[2]);
            return 2;
        }
        struct Sums {
            std::uint64_t rays = 0, tree = 0, tree_hit = 0, every_4 = 0, every_4_hit = 0, median = 0, median_hit = 0;
        } sums[kRayKinds];
        HitRecord r;
        while (in.read(reinterpret_cast<char*>(&r), sizeof r)) {
            const RayKind kind = ray_kind(r.kind_light);
            if (kind == RayKind::Primary || kind == RayKind::Shadow || int(kind) >= kRayKinds) continue;
            const glm::vec3 o(r.origin[0], r.origin[1], r.origin[2]);
            const glm::vec3 d(r.direction[0], r.direction[1], r.direction[2]);
            const float to_hit = r.triangle >= 0 ? r.t * 1.0001f : INFINITY;   // a little past the hit: never short
            Sums& s = sums[int(kind)];
            ++s.rays;
            s.tree += tree_tests(tree, o, d, INFINITY);
            s.tree_hit += tree_tests(tree, o, d, to_hit);
            s.every_4 += tree_tests(every_4, o, d, INFINITY);
            s.every_4_hit += tree_tests(every_4, o, d, to_hit);
            if (!median.nodes.empty()) {
                s.median += median.tests(o, d, INFINITY);
                s.median_hit += median.tests(o, d, to_hit);
            }
        }
        std::printf("%s: %zu triangles; the tree %u levels, %zu nodes; every 4: %u levels, %zu nodes\n", argv[1],
                    scene.triangle_count(), tree.levels(), tree.nodes.size(), every_4.levels(), every_4.nodes.size());
        std::printf("| rays | count | tree | tree, to hit | every 4 | every 4, to hit | median | median, to hit |\n");
        std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
        for (int k = 0; k < kRayKinds; ++k) {
            const Sums& s = sums[k];
            if (s.rays == 0) continue;
            const double n = double(s.rays);
            std::printf("| %s | %llu | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f |\n", ray_kind_name(RayKind(k)),
                        static_cast<unsigned long long>(s.rays), double(s.tree) / n, double(s.tree_hit) / n,
                        double(s.every_4) / n, double(s.every_4_hit) / n, double(s.median) / n,
                        double(s.median_hit) / n);
        }
    } catch (const std::exception& e) {   // the scene's file: missing, malformed or too large (bad input)
        std::fprintf(stderr, "object_tree_study: %s\n", e.what());
        return 2;
    }
    return 0;
}
