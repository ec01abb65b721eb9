#include "ray_hierarchy.h"

#include <algorithm>
#include <cmath>

namespace rt {

namespace {
float max_abs(glm::vec3 v) { return std::max(std::abs(v.x), std::max(std::abs(v.y), std::abs(v.z))); }
bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
[[maybe_unused]] float angle(glm::vec3 a, glm::vec3 b) { return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)); }
}  // namespace

bool valid_branching(int branching) { return branching == 4 || branching == 8 || branching == 16; }

RhNode rh_leaf(glm::vec3 origin, glm::vec3 direction) {
    const float m = max_abs(direction);
    if (!finite(origin) || !finite(direction) || !(m > 0.0f)) return RhNode{};
    return RhNode{glm::vec4(origin, 0.0f), glm::vec4(glm::normalize(direction / m), 0.0f)};
}

// rh_common.glsl explains the union and why it is conservative.
RhNode rh_union(const RhNode* kids, std::size_t count) {
    // BEGIN EXERCISE 04.node_union: the C++ twin of rh_common.glsl's rh_union (the CPU tests grade this one, the
    // GLSL tests check the other): the same sphere and cone, padded the same way, empty children skipped.
    const float inf = INFINITY;
    glm::vec3 lo(inf), hi(-inf), axis_sum(0.0f), first_axis(1.0f, 0.0f, 0.0f);
    bool any = false, all_directions = false;
    for (std::size_t i = 0; i < count; ++i) {
        if (kids[i].empty()) continue;
        if (!any) first_axis = glm::vec3(kids[i].cone);
        any = true;
        lo = glm::min(lo, glm::vec3(kids[i].sphere));
        hi = glm::max(hi, glm::vec3(kids[i].sphere));
        axis_sum += glm::vec3(kids[i].cone);
        all_directions = all_directions || kids[i].cone.w >= kRhAllDirections;
    }
    if (!any) return RhNode{};
    const glm::vec3 c = 0.5f * lo + 0.5f * hi;
    const float len = glm::length(axis_sum);
    const glm::vec3 axis = (len > 0.0f && std::isfinite(len)) ? axis_sum / len : first_axis;
    float radius = 0.0f, spread = 0.0f;
    for (std::size_t i = 0; i < count; ++i) {
        if (kids[i].empty()) continue;
        radius = std::max(radius, glm::length(glm::vec3(kids[i].sphere) - c) + kids[i].sphere.w);
        spread = std::max(spread, angle(axis, glm::vec3(kids[i].cone)) + kids[i].cone.w);
    }
    radius = radius * (1.0f + kRhPad) + kRhPad * std::max(max_abs(c), max_abs(hi - lo)) + 1e-30f;
    spread = spread * (1.0f + kRhPad) + kRhPad;
    if (all_directions || !(spread < kRhAllDirections)) spread = 3.14159274f;
    return RhNode{glm::vec4(c, radius), glm::vec4(axis, spread)};
    // STUB: return count > 0 ? kids[0] : RhNode{};
    // END EXERCISE
}

glm::vec4 rh_triangle_sphere(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    const glm::vec3 m = 0.5f * lo + 0.5f * hi;
    const float r = std::max(glm::length(a - m), std::max(glm::length(b - m), glm::length(c - m)));
    return glm::vec4(m, r * (1.0f + kRhPad) + kRhPad * std::max(max_abs(m), max_abs(hi - lo)) + 1e-30f);
}

bool rh_may_hit(const RhNode& node, glm::vec4 s) {
    if (node.empty()) return false;
    if (node.cone.w >= kRhAllDirections) return true;   // every direction: the rays reach everything
    // BEGIN EXERCISE 04.cone_sphere_test: the C++ twin of rh_common.glsl's rh_may_hit: the same test, the same
    // margin, the same answer on every input.
    const glm::vec3 axis(node.cone), centre(node.sphere);
    const glm::vec3 q = glm::vec3(s) - centre;
    const float q_len = glm::length(q);
    const float reach = node.sphere.w + s.w;
    const float margin = kRhPad * (q_len + reach + max_abs(centre) + max_abs(glm::vec3(s)));
    const float A = glm::dot(q, axis);
    const float B = glm::length(glm::cross(q, axis));
    const float ct = std::cos(node.cone.w), st = std::sin(node.cone.w);
    const float sin_part = B * ct - A * st;
    const float cos_part = A * ct + B * st;
    const float dist = cos_part <= 0.0f ? q_len : sin_part;
    const bool far = sin_part > 0.0f && dist > reach + margin;
    return !far;
    // STUB: (void)s;
    // STUB: return false;
    // END EXERCISE
}

std::vector<std::vector<RhNode>> rh_build(const std::vector<RhRay>& rays, int branching, int max_levels) {
    std::vector<std::vector<RhNode>> levels(1);
    for (const RhRay& r : rays) levels[0].push_back(rh_leaf(r.origin, r.direction));
    const std::size_t b = std::size_t(branching);
    // At least one level above the rays (as the GPU build), then up to a single root or the limit.
    const auto more = [&] { return max_levels <= 0 || int(levels.size()) <= max_levels; };
    while (levels.size() == 1 || (levels.back().size() > 1 && more())) {
        const std::vector<RhNode>& below = levels.back();
        std::vector<RhNode> level((below.size() + b - 1) / b);
        for (std::size_t j = 0; j < level.size(); ++j)
            level[j] = rh_union(&below[j * b], std::min(b, below.size() - j * b));
        levels.push_back(std::move(level));
    }
    return levels;
}

bool rh_contains(const RhNode& node, glm::vec3 origin, glm::vec3 direction) {
    if (node.empty()) return false;
    const glm::dvec3 c(node.sphere), o(origin), axis(node.cone);
    if (glm::length(o - c) > double(node.sphere.w)) return false;
    if (node.cone.w >= kRhAllDirections) return true;
    const glm::dvec3 d = glm::normalize(glm::dvec3(direction) / double(max_abs(direction)));
    const double a = std::atan2(glm::length(glm::cross(d, axis)), glm::dot(d, axis));
    return a <= double(node.cone.w);
}

}  // namespace rt
