// Random and adversarial ray sets, with triangles around them, for the hierarchy's property tests (CPU and GLSL).
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "common/trace/intersect.h"
#include "ray_hierarchy.h"

namespace rt::ray_sets {

struct Case {
    std::string name;
    std::vector<RhRay> rays;
    std::vector<glm::vec3> triangles;   // 3 per triangle
};

inline glm::vec3 unit(std::mt19937& g) {
    std::normal_distribution<float> n;
    for (;;) {
        const glm::vec3 v(n(g), n(g), n(g));
        if (glm::length(v) > 1e-3f) return glm::normalize(v);
    }
}

// Rays with origins in a box of size `scale` around `centre`; triangles of size ~scale/4 in a box twice as big.
inline Case make(const std::string& name, int rays, float scale, glm::vec3 centre, unsigned seed) {
    std::mt19937 g(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Case c{name, {}, {}};
    const glm::vec3 shared_origin = centre + scale * glm::vec3(0.3f, -0.2f, 0.1f);
    const glm::vec3 shared_dir = unit(g);
    for (int i = 0; i < rays; ++i) {
        glm::vec3 o = centre + scale * glm::vec3(u(g), u(g), u(g));
        glm::vec3 d = unit(g);
        if (name == "coherent") d = glm::normalize(shared_dir + 0.15f * unit(g));
        if (name == "identical") o = shared_origin, d = shared_dir;
        if (name == "one_origin") o = shared_origin;
        if (name == "one_plane") o.z = centre.z, d.z = 0.0f;
        if (name == "opposite") d = (i % 2 ? -1.0f : 1.0f) * shared_dir;
        if (name == "invalid" && i % 3 == 1) {
            const float bad[4] = {0.0f, NAN, INFINITY, -0.0f};
            d = glm::vec3(bad[i % 4]);
            if (i % 9 == 4) o = glm::vec3(NAN);
        }
        if (name == "tiny_directions") d *= 1e-30f;
        if (name == "huge_directions") d *= 1e30f;
        c.rays.push_back({o, d});
    }
    for (int t = 0; t < 64; ++t) {
        const glm::vec3 p = centre + 2.0f * scale * glm::vec3(u(g), u(g), u(g));
        for (int k = 0; k < 3; ++k) c.triangles.push_back(p + 0.25f * scale * unit(g) * (0.2f + std::abs(u(g))));
    }
    return c;
}

// Whether the exact test hits triangle v[0..2] with the ray (either method: the property must hold for both).
inline bool exact_hit(const RhRay& r, const glm::vec3* v, float tmax = INFINITY) {
    Ray<float> ray;
    ray.origin = r.origin;
    ray.direction = r.direction;
    ray.tmax = tmax;
    float t, u, w;
    return intersect_watertight(ray, WatertightRay<float>(r.direction), v[0], v[1], v[2], t, u, w) ||
           intersect_moller(ray, v[0], v[1], v[2], t, u, w);
}

inline std::vector<Case> all() {
    std::vector<Case> cases;
    unsigned seed = 1;
    for (const char* name : {"random", "coherent", "identical", "one_origin", "one_plane", "opposite", "invalid",
                             "tiny_directions", "huge_directions"})
        cases.push_back(make(name, 203, 1.0f, glm::vec3(0.0f), seed++));
    cases.push_back(make("huge_coordinates", 203, 1e3f, glm::vec3(3e6f, -2e6f, 1e6f), seed++));
    cases.push_back(make("tiny_coordinates", 203, 1e-6f, glm::vec3(2e-6f), seed++));
    Case coherent_huge = make("coherent", 203, 1e4f, glm::vec3(-5e7f, 1e7f, 0.0f), seed++);
    coherent_huge.name = "coherent_huge_coordinates";
    cases.push_back(coherent_huge);
    return cases;
}

// Rays [first, last) of the n rays under node j of hierarchy level `level` (branching rays per node).
inline std::pair<std::size_t, std::size_t> leaves_under(std::size_t j, std::size_t level, int branching,
                                                        std::size_t n) {
    std::size_t span = 1;
    for (std::size_t l = 0; l < level; ++l) span *= std::size_t(branching);
    return {std::min(n, j * span), std::min(n, (j + 1) * span)};
}

// all(), and two beams (origins in a patch of 1% of a triangle's size, directions within about 10 degrees; one near
// the origin, one at huge coordinates), whose nodes are small beside the triangles: where a box culls pairs the
// cone+sphere test keeps.
inline std::vector<Case> with_beams() {
    std::vector<Case> cases = all();
    std::mt19937 g(5);
    for (Case beam : {cases[0], cases[9]}) {
        beam.name += "_beam";
        const glm::vec3 centre = beam.rays[0].origin, axis = unit(g);
        const float size = glm::length(beam.triangles[0] - beam.triangles[1]);
        for (RhRay& r : beam.rays) {
            r.origin = centre + 0.01f * size * unit(g);
            r.direction = glm::normalize(axis + 0.15f * unit(g));
        }
        cases.push_back(beam);
    }
    return cases;
}

// The triangles, then each again flattened onto an axis plane through its first vertex (x, y, z in turn): walls,
// whose boxes have no depth, and are far tighter than their spheres.
inline std::vector<glm::vec3> with_walls(const std::vector<glm::vec3>& triangles) {
    std::vector<glm::vec3> out = triangles;
    for (std::size_t k = 0; k < triangles.size(); ++k) {
        const int axis = int(k / 3 % 3);
        glm::vec3 p = triangles[k];
        p[axis] = triangles[k / 3 * 3][axis];
        out.push_back(p);
    }
    return out;
}

// One ray aimed at one triangle's vertex, edge or inside: the cases where a cheap test grazes the exact test's hit.
struct AimedRay {
    RhRay ray;
    float tmax = INFINITY;
    glm::vec3 v[3];   // the triangle
};

// Axis-aligned (a box of zero depth), slanted, needle and point triangles near the origin, far from it and tiny;
// 40 rays at each from some way off, along an axis, along an edge, unbounded or ending beyond the triangle.
inline std::vector<AimedRay> aimed_rays(unsigned seed = 21) {
    std::mt19937 g(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), w(0.0f, 1.0f);
    std::vector<AimedRay> out;
    for (const auto& [scale, centre] : {std::pair<float, glm::vec3>{1.0f, glm::vec3(0.0f)},
                                        {100.0f, glm::vec3(4e6f, -3e6f, 1e6f)},
                                        {1e-5f, glm::vec3(3e-5f)}}) {
        for (int t = 0; t < 400; ++t) {
            AimedRay a;
            const glm::vec3 p = centre + scale * glm::vec3(u(g), u(g), u(g));
            const glm::vec3 e1 = scale * unit(g), e2 = scale * unit(g);
            a.v[0] = p;
            a.v[1] = p + e1;
            a.v[2] = p + e2;
            if (t % 4 == 0) a.v[1].z = a.v[2].z = p.z;   // flat in z
            if (t % 4 == 1) a.v[2] = p + 2.0f * e1;      // a needle
            if (t % 8 == 2) a.v[1] = a.v[2] = p;         // a point
            for (int k = 0; k < 40; ++k) {
                const float s = k % 5 == 0 ? 0.0f : w(g), r = k % 3 == 0 ? 0.0f : w(g) * (1.0f - s);
                const glm::vec3 target = a.v[0] + s * (a.v[1] - a.v[0]) + r * (a.v[2] - a.v[0]);
                glm::vec3 d = k % 7 == 0 ? glm::vec3(0.0f, 0.0f, 1.0f) : unit(g);
                if (k % 11 == 0) d = glm::normalize(a.v[1] - a.v[0] + glm::vec3(0.0f, 0.0f, 1e-3f * scale));
                a.ray = {target - 3.0f * scale * d, d};
                a.tmax = k % 6 == 0 ? 3.0f * scale : INFINITY;
                out.push_back(a);
            }
        }
    }
    return out;
}

}  // namespace rt::ray_sets
