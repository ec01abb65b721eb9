// Random and adversarial ray sets, with triangles around them, for the hierarchy's property tests (CPU and GLSL).
#pragma once

#include <cmath>
#include <random>
#include <string>
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
inline bool exact_hit(const RhRay& r, const glm::vec3* v) {
    Ray<float> ray;
    ray.origin = r.origin;
    ray.direction = r.direction;
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

}  // namespace rt::ray_sets
