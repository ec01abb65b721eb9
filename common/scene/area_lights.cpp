#include "area_lights.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rt {

namespace {

glm::dvec3 vertex(const Scene& scene, std::uint32_t triangle, int k) {
    return glm::dvec3(scene.positions[3 * std::size_t(triangle) + std::size_t(k)]);
}

double max_abs(const glm::dvec3& v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }

// Whether triangles t and t + 1 form a parallelogram: they share an edge (two vertices bit for bit, as flatten
// writes a shared index), the two other corners sum to the shared ones within 2 ulps of the largest coordinate (the
// samples then lie on the triangles within the robust offset's 8 ulps), both face the same way, and the texture
// coordinates are as affine over it. Fills the corner and edges so that cross(edge_u, edge_v) is the front.
bool as_parallelogram(const Scene& scene, std::uint32_t t, AreaLight& light) {
    const std::size_t a = 3 * std::size_t(t), b = a + 3;
    int shared[3] = {-1, -1, -1};   // for each vertex of triangle t, the vertex of t + 1 it equals
    int count = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (scene.positions[a + std::size_t(i)] == scene.positions[b + std::size_t(j)]) shared[i] = j, ++count;
    if (count != 2) return false;
    int x0 = 0;
    while (shared[x0] >= 0) ++x0;
    if (shared[(x0 + 1) % 3] == shared[(x0 + 2) % 3]) return false;   // a degenerate triangle t + 1
    int d0 = (x0 + 1) % 3, d1 = (x0 + 2) % 3;   // (x0, d0, d1) in triangle t's winding: cross(d0 - x0, d1 - x0) is its front
    const int x1 = 3 - shared[d0] - shared[d1];
    const glm::dvec3 px0 = vertex(scene, t, x0), pd0 = vertex(scene, t, d0), pd1 = vertex(scene, t, d1);
    const glm::dvec3 px1 = vertex(scene, t + 1, x1);
    const double scale = std::max({max_abs(px0), max_abs(pd0), max_abs(pd1), max_abs(px1)});
    if (max_abs(px0 + px1 - pd0 - pd1) > scale * 0x1p-22) return false;
    const glm::dvec3 n0 = glm::cross(pd0 - px0, pd1 - px0);
    const glm::dvec3 n1 = glm::cross(vertex(scene, t + 1, 1) - vertex(scene, t + 1, 0),
                                     vertex(scene, t + 1, 2) - vertex(scene, t + 1, 0));
    if (!(glm::dot(n0, n1) > 0.0)) return false;   // wound against each other: not one surface facing one way
    const glm::dvec2 ux0(scene.uvs[a + std::size_t(x0)]), ud0(scene.uvs[a + std::size_t(d0)]);
    const glm::dvec2 ud1(scene.uvs[a + std::size_t(d1)]), ux1(scene.uvs[b + std::size_t(x1)]);
    const glm::dvec2 uv_error = glm::abs(ux0 + ux1 - ud0 - ud1);
    const double uv_scale = std::max({1.0, glm::length(ud0 - ux0), glm::length(ud1 - ux0)});
    if (std::max(uv_error.x, uv_error.y) > uv_scale * 0x1p-20) return false;
    light.parallelogram = true;
    light.corner = glm::vec3(px0);
    light.edge_u = glm::vec3(pd0 - px0);
    light.edge_v = glm::vec3(pd1 - px0);
    light.uv_corner = glm::vec2(ux0);
    light.uv_edge_u = glm::vec2(ud0 - ux0);
    light.uv_edge_v = glm::vec2(ud1 - ux0);
    return true;
}

}  // namespace

void add_area_light(Scene& scene, std::uint32_t first, std::uint32_t count, std::uint32_t material,
                    std::string name) {
    if (count == 0) return;
    std::vector<double> areas(count);
    double total = 0.0;
    for (std::uint32_t k = 0; k < count; ++k) {
        const glm::dvec3 a = vertex(scene, first + k, 0), b = vertex(scene, first + k, 1), c = vertex(scene, first + k, 2);
        const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
        areas[k] = std::isfinite(area) ? area : 0.0;
        total += areas[k];
    }
    if (!(total > 0.0) || !std::isfinite(float(total))) return;
    AreaLight light;
    light.name = std::move(name);
    light.first_triangle = first;
    light.triangle_count = count;
    light.material = material;
    light.area = float(total);
    light.two_sided = scene.materials[material].double_sided;
    if (count == 2 && as_parallelogram(scene, first, light)) {
        scene.area_lights.push_back(std::move(light));
        return;
    }
    light.cdf_first = std::uint32_t(scene.area_light_cdf.size());
    double running = 0.0;
    for (std::uint32_t k = 0; k < count; ++k) {
        running += areas[k];
        scene.area_light_cdf.push_back(k + 1 == count ? 1.0f : float(running / total));
    }
    scene.area_lights.push_back(std::move(light));
}

}  // namespace rt
