#include "object_tree.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>

namespace rt {

namespace {
constexpr std::uint32_t kTriangleFlag = 0x80000000u;   // rh_common.glsl: RH_TRIANGLE_FLAG
float max_abs(glm::vec3 v) { return std::max(std::abs(v.x), std::max(std::abs(v.y), std::abs(v.z))); }
bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Bits 0..9 of v spread to every third bit (shaders/ot_build.comp: ot_spread_bits).
std::uint32_t spread_bits(std::uint32_t v) {
    v &= 0x3ffu;
    v = (v | (v << 16)) & 0x030000ffu;
    v = (v | (v << 8)) & 0x0300f00fu;
    v = (v | (v << 4)) & 0x030c30c3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

std::uint32_t morton_cell(float x, float lo, float scale) {
    const float f = (x - lo) * scale;
    if (!(f >= 0.0f)) return 0;   // below the box, or NaN
    if (f >= 1024.0f) return 1023;
    return std::uint32_t(f);
}

void add_level(ObjectTree& tree, std::uint32_t count) {
    tree.level_first.push_back(std::uint32_t(tree.nodes.size()));
    tree.level_count.push_back(count);
}
}  // namespace

const char* object_mode_name(ObjectMode mode) {
    switch (mode) {
    case ObjectMode::triangles: return "triangles";
    case ObjectMode::meshes: return "meshes";
    case ObjectMode::tree: return "tree";
    }
    return "?";
}

float morton_scale(glm::vec3 lo, glm::vec3 hi) {
    const double extent = std::max({double(hi.x) - lo.x, double(hi.y) - lo.y, double(hi.z) - lo.z});
    if (!(extent > 0.0) || !std::isfinite(extent)) return 0.0f;
    const float scale = float(1024.0 / extent);
    return std::isfinite(scale) ? scale : 0.0f;
}

std::uint32_t morton_code(glm::vec3 p, glm::vec3 lo, float scale) {
    return spread_bits(morton_cell(p.x, lo.x, scale)) << 2 | spread_bits(morton_cell(p.y, lo.y, scale)) << 1 |
           spread_bits(morton_cell(p.z, lo.z, scale));
}

// The box of the children's spheres, its middle, the largest reach from there; padded as rh_triangle_sphere
// (shaders/ot_build.comp: ot_union).
glm::vec4 sphere_union(const glm::vec4* s, std::size_t count) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (std::size_t k = 0; k < count; ++k) {
        lo = glm::min(lo, glm::vec3(s[k]) - s[k].w);
        hi = glm::max(hi, glm::vec3(s[k]) + s[k].w);
    }
    const glm::vec3 m = 0.5f * lo + 0.5f * hi;
    float r = 0.0f;
    for (std::size_t k = 0; k < count; ++k) r = std::max(r, glm::length(glm::vec3(s[k]) - m) + s[k].w);
    return glm::vec4(m, r * (1.0f + kRhPad) + kRhPad * std::max(max_abs(m), max_abs(hi - lo)) + 1e-30f);
}

glm::vec4 sphere_union(const std::vector<glm::vec4>& spheres, const std::uint32_t* order, std::uint32_t first,
                       std::uint32_t count) {
    std::vector<glm::vec4> kids;
    for (std::uint32_t k = 0; k < count; ++k) kids.push_back(spheres[order ? order[first + k] : first + k]);
    return sphere_union(kids.data(), kids.size());
}

std::uint32_t boundary_strength(std::uint32_t last_code, std::uint32_t next_first_code, std::uint32_t k) {
    const std::uint32_t x = last_code ^ next_first_code;
    if (x != 0) return 64u - std::uint32_t(std::countl_zero(x));   // 33..64: the highest bit the codes differ in
    return 32u - std::uint32_t(std::countl_zero(k ^ (k + 1u)));    // 1..32: equal codes, split by position
}

std::vector<std::uint32_t> group_heads(const std::vector<std::uint32_t>& first_code,
                                       const std::vector<std::uint32_t>& last_code, bool every_4) {
    const auto m = std::uint32_t(first_code.size());
    const auto strength = [&](std::uint32_t k) { return boundary_strength(last_code[k], first_code[k + 1], k); };
    // Boundary k (between nodes k and k + 1) is cut when the subtree it splits holds more than kObjectBranching
    // nodes: the nodes from just after the nearest boundary on its left at least as strong, to the nearest one on
    // its right stronger (a Cartesian tree of the strengths, ties to the left). Four steps each way decide it.
    std::vector<std::uint32_t> heads;
    if (m == 0) return heads;
    heads.push_back(0);
    for (std::uint32_t k = 0; k + 1 < m && !every_4; ++k) {
        const std::uint32_t s = strength(k);
        std::uint32_t left = 1, right = 1;   // nodes of the subtree on each side of the boundary
        while (left <= kObjectBranching && k >= left && strength(k - left) < s) ++left;
        while (right <= kObjectBranching && k + right + 1 < m && strength(k + right) <= s) ++right;
        if (left + right > kObjectBranching) heads.push_back(k + 1);
    }
    // At least halve the level: otherwise (codes far apart by powers of two, one node split off at a time) every
    // 4 nodes, as a Morton-blind grouping would.
    if (every_4 || 2 * std::uint64_t(heads.size()) > m) {
        heads.clear();
        for (std::uint32_t k = 0; k < m; k += kObjectBranching) heads.push_back(k);
    }
    return heads;
}

ObjectTree build_object_tree(const std::vector<glm::vec4>& spheres, glm::vec3 lo, glm::vec3 hi,
                             const std::vector<glm::vec3>& triangles, bool every_4) {
    ObjectTree tree;
    const std::uint32_t n = std::uint32_t(spheres.size());
    tree.order.resize(n);
    std::iota(tree.order.begin(), tree.order.end(), 0u);
    if (n == 0) return tree;
    const float scale = morton_scale(lo, hi);
    std::vector<std::uint32_t> codes(n);
    for (std::uint32_t i = 0; i < n; ++i) codes[i] = morton_code(glm::vec3(spheres[i]), lo, scale);
    std::stable_sort(tree.order.begin(), tree.order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return codes[a] < codes[b]; });
    // Each level's nodes and the codes they span (first, last): the sorted triangles, then each level's groups.
    std::vector<std::uint32_t> first_code(n), last_code(n);
    for (std::uint32_t i = 0; i < n; ++i) first_code[i] = last_code[i] = codes[tree.order[i]];
    std::uint32_t below_first = 0;
    for (std::uint32_t level = 1;; ++level) {
        const std::vector<std::uint32_t> heads = group_heads(first_code, last_code, every_4);
        const auto m = std::uint32_t(first_code.size()), groups = std::uint32_t(heads.size());
        add_level(tree, groups);
        std::vector<std::uint32_t> next_first(groups), next_last(groups);
        for (std::uint32_t j = 0; j < groups; ++j) {
            const std::uint32_t b = heads[j], e = j + 1 < groups ? heads[j + 1] : m;
            ObjectNode node;
            node.count = e - b;
            node.level = level;
            if (level == 1) {   // a cluster: triangles order[b, e) (ot_build.comp mode 1)
                node.first = b;
                node.sphere = sphere_union(spheres, tree.order.data(), node.first, node.count);
                if (!triangles.empty()) {   // the box of the cluster's vertices
                    glm::vec3 box_lo(INFINITY), box_hi(-INFINITY);
                    for (std::uint32_t k = 0; k < node.count; ++k)
                        for (std::size_t v = 0; v < 3; ++v) {
                            const glm::vec3 p = triangles[3 * std::size_t(tree.order[node.first + k]) + v];
                            box_lo = glm::min(box_lo, p);
                            box_hi = glm::max(box_hi, p);
                        }
                    node.box_lo = glm::vec4(box_lo, 0.0f);
                    node.box_hi = glm::vec4(box_hi, 0.0f);
                }
            } else {   // nodes [b, e) of the level below (mode 2)
                node.first = below_first + b;
                std::vector<glm::vec4> kids;
                for (std::uint32_t k = 0; k < node.count; ++k) kids.push_back(tree.nodes[node.first + k].sphere);
                node.sphere = sphere_union(kids.data(), kids.size());
                node.box_lo = glm::vec4(INFINITY, INFINITY, INFINITY, 0.0f);
                node.box_hi = glm::vec4(-INFINITY, -INFINITY, -INFINITY, 0.0f);
                for (std::uint32_t k = 0; k < node.count; ++k) {
                    node.box_lo = glm::min(node.box_lo, tree.nodes[node.first + k].box_lo);
                    node.box_hi = glm::max(node.box_hi, tree.nodes[node.first + k].box_hi);
                }
            }
            tree.nodes.push_back(node);
            next_first[j] = first_code[b];
            next_last[j] = last_code[e - 1];
        }
        below_first = tree.level_first.back();
        if (groups <= 1) break;
        first_code = std::move(next_first);
        last_code = std::move(next_last);
    }
    return tree;
}

ObjectTree mesh_objects(const std::vector<glm::vec4>& spheres,
                        const std::vector<std::pair<std::uint32_t, std::uint32_t>>& runs) {
    ObjectTree tree;
    tree.order.resize(spheres.size());
    std::iota(tree.order.begin(), tree.order.end(), 0u);
    if (runs.empty()) return tree;
    add_level(tree, std::uint32_t(runs.size()));
    for (const auto& [first, count] : runs) {
        ObjectNode node;
        node.first = first;
        node.count = count;
        node.level = 1;
        node.sphere = sphere_union(spheres, nullptr, first, count);
        tree.nodes.push_back(node);
    }
    return tree;
}

bool rh_ray_may_hit(glm::vec3 origin, glm::vec3 direction, float tmax, glm::vec4 s) {
    const float m = max_abs(direction);
    if (!finite(origin) || !finite(direction) || !(m > 0.0f)) return false;
    // BEGIN EXERCISE 04.cone_sphere_test: the single-ray form (the C++ twin of rh_common.glsl's rh_ray_may_hit):
    // rh_may_hit for a node of one ray (spread 0, no trigonometry), and the sphere out of reach beyond tmax.
    const glm::vec3 axis = glm::normalize(direction / m);
    const glm::vec3 centre(s);
    const glm::vec3 q = centre - origin;
    const float q_len = glm::length(q);
    const float margin = kRhPad * (q_len + s.w + max_abs(origin) + max_abs(centre));
    // rh_may_hit with spread 0: cos(0) = 1, sin(0) = 0.
    const float A = glm::dot(q, axis);
    const float B = glm::length(glm::cross(q, axis));
    const float dist = A <= 0.0f ? q_len : B;
    if (dist > s.w + margin) return false;   // A <= 0: the origin is the ray's nearest point to the centre
    // Every point the ray reaches is within tmax |d| of its origin; the sphere's nearest point is |q| - radius away.
    const float length = m * glm::length(direction / m);   // |d| without overflow or underflow
    return !(q_len - s.w - margin > tmax * length * (1.0f + kRhPad));
    // STUB: (void)tmax, (void)s;
    // STUB: return true;
    // END EXERCISE
}

bool rh_ray_box_may_hit(glm::vec3 origin, glm::vec3 direction, float tmax, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    return rh_ray_box_test(origin, direction, tmax, glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c)));
}

bool rh_ray_box_test(glm::vec3 origin, glm::vec3 direction, float tmax, glm::vec3 lo, glm::vec3 hi) {
    if (!finite(origin) || !finite(direction) || !(max_abs(direction) > 0.0f)) return false;
    const float pad = kRhPad * (max_abs(origin) + std::max(max_abs(lo), max_abs(hi))) + 1e-30f;
    float t_in = 0.0f, t_out = std::isfinite(tmax) ? tmax : INFINITY;   // NaN: no end, the pair is kept
    for (int i = 0; i < 3; ++i) {
        const float near = lo[i] - pad - origin[i], far = hi[i] + pad - origin[i];   // the slab, seen from the origin
        if (direction[i] == 0.0f) {   // parallel to the slab: inside it for every t, or for none
            if (near > 0.0f || far < 0.0f) return false;
            continue;
        }
        const float t_a = near / direction[i], t_b = far / direction[i];
        t_in = std::max(t_in, std::min(t_a, t_b));
        t_out = std::min(t_out, std::max(t_a, t_b));
    }
    return !(t_in > t_out * (1.0f + kRhPad) + 1e-30f);   // a NaN keeps the pair
}

bool rh_node_box_test(const RhNode& node, glm::vec3 lo, glm::vec3 hi) {
    if (node.empty()) return false;
    if (node.cone.w >= kRhAllDirections) return true;
    const glm::vec3 c(node.sphere), a(node.cone);
    const float r = node.sphere.w, ct = std::cos(node.cone.w), st = std::sin(node.cone.w);
    const float pad = kRhPad * (max_abs(c) + r + std::max(max_abs(lo), max_abs(hi))) + 1e-30f;
    float t_in = 0.0f, t_out = INFINITY;
    for (int i = 0; i < 3; ++i) {
        const float other_1 = a[(i + 1) % 3], other_2 = a[(i + 2) % 3];
        const float sin_alpha = std::sqrt(other_1 * other_1 + other_2 * other_2);   // cos alpha = a[i]
        // The range of d_i over the cone: cos(max(alpha - theta, 0)) and cos(min(alpha + theta, pi)), padded; a
        // bound of 0 moves off 0 outwards, so that neither division below is by 0.
        float d_hi = (a[i] <= ct ? a[i] * ct + sin_alpha * st : 1.0f) + kRhPad;
        float d_lo = (a[i] >= -ct ? a[i] * ct - sin_alpha * st : -1.0f) - kRhPad;
        if (d_hi == 0.0f) d_hi = 1e-30f;
        if (d_lo == 0.0f) d_lo = -1e-30f;
        // t d_lo <= hi + pad - (c - r): the rays' lowest point has not passed the slab's top; a positive d_lo ends
        // the half-line of t, a negative one starts it. t d_hi >= lo - pad - (c + r): their highest point has
        // reached its bottom.
        const float t_lo = (hi[i] + pad - (c[i] - r)) / d_lo, t_hi = (lo[i] - pad - (c[i] + r)) / d_hi;
        if (d_lo < 0.0f) t_in = std::max(t_in, t_lo);
        if (d_lo > 0.0f) t_out = std::min(t_out, t_lo);
        if (d_hi > 0.0f) t_in = std::max(t_in, t_hi);
        if (d_hi < 0.0f) t_out = std::min(t_out, t_hi);
    }
    return !(t_in > t_out * (1.0f + kRhPad) + 1e-30f);   // a NaN keeps the pair
}

bool rh_split_rays(const RhNode& node, glm::vec4 s) {
    if (node.cone.w >= kRhAllDirections) return true;
    const float distance = glm::length(glm::vec3(s) - glm::vec3(node.sphere));
    const float width = node.sphere.w + distance * std::sin(std::min(node.cone.w, 1.57079637f));
    return width > kSplitRaysWidth * s.w;
}

PairTraversal traverse_pairs(const std::vector<RhTraceRay>& rays, const std::vector<std::vector<RhNode>>& levels,
                             int branching_factor, const std::vector<glm::vec4>& spheres, const ObjectTree& tree,
                             ObjectMode mode, const std::vector<glm::vec3>& triangles) {
    PairTraversal out;
    if (levels.size() < 2 || spheres.empty()) return out;
    const std::size_t branching = std::size_t(branching_factor);
    struct Pair {
        std::uint32_t level, index, object;
    };
    std::vector<Pair> stack;
    const std::uint32_t top = std::uint32_t(levels.size() - 1);
    for (std::uint32_t j = 0; j < levels[top].size(); ++j) {
        if (mode == ObjectMode::triangles) {
            for (std::uint32_t t = 0; t < spheres.size(); ++t) stack.push_back({top, j, kTriangleFlag | t});
        } else if (tree.levels() > 0) {
            const std::uint32_t L = tree.levels() - 1;
            for (std::uint32_t k = 0; k < tree.level_count[L]; ++k) stack.push_back({top, j, tree.level_first[L] + k});
        }
    }
    while (!stack.empty()) {
        const Pair p = stack.back();
        stack.pop_back();
        const bool triangle = (p.object & kTriangleFlag) != 0;
        const glm::vec4 sphere = triangle ? spheres[p.object & ~kTriangleFlag] : tree.nodes[p.object].sphere;
        if (p.level == 0) {
            const RhTraceRay& r = rays[p.index];
            if (triangle) {
                const std::uint32_t t = p.object & ~kTriangleFlag;
                ++out.sphere_tests;
                if (!rh_ray_may_hit(r.origin, r.direction, r.tmax, sphere)) continue;
                if (!triangles.empty()) {
                    ++out.box_tests;
                    const glm::vec3* v = &triangles[3 * std::size_t(t)];
                    if (!rh_ray_box_may_hit(r.origin, r.direction, r.tmax, v[0], v[1], v[2])) continue;
                }
                out.exact.emplace_back(p.index, t);
                continue;
            }
            ++out.node_tests;
            if (!rh_ray_may_hit(r.origin, r.direction, r.tmax, sphere)) continue;
            const ObjectNode& node = tree.nodes[p.object];
            if (!triangles.empty() && !rh_ray_box_test(r.origin, r.direction, r.tmax, glm::vec3(node.box_lo),
                                                       glm::vec3(node.box_hi)))
                continue;
        } else {
            ++out.node_tests;
            const RhNode& rays_node = levels[p.level][p.index];
            if (!rh_may_hit(rays_node, sphere)) continue;
            if (!triangles.empty()) {   // the box too (--box-test on): the triangle's, or the object node's
                glm::vec3 lo, hi;
                if (triangle) {
                    const glm::vec3* v = &triangles[3 * std::size_t(p.object & ~kTriangleFlag)];
                    lo = glm::min(v[0], glm::min(v[1], v[2]));
                    hi = glm::max(v[0], glm::max(v[1], v[2]));
                } else {
                    lo = glm::vec3(tree.nodes[p.object].box_lo);
                    hi = glm::vec3(tree.nodes[p.object].box_hi);
                }
                if (!rh_node_box_test(rays_node, lo, hi)) continue;
            }
        }
        const bool split_rays =
            triangle || (p.level > 0 && mode == ObjectMode::tree && rh_split_rays(levels[p.level][p.index], sphere));
        if (split_rays) {
            const std::size_t first = p.index * branching;
            const std::size_t last = std::min(first + branching, levels[p.level - 1].size());
            for (std::size_t k = first; k < last; ++k) stack.push_back({p.level - 1, std::uint32_t(k), p.object});
        } else {
            const ObjectNode& node = tree.nodes[p.object];
            for (std::uint32_t k = 0; k < node.count; ++k)
                stack.push_back({p.level, p.index,
                                 node.level == 1 ? kTriangleFlag | tree.order[node.first + k] : node.first + k});
        }
    }
    return out;
}

}  // namespace rt
