// Soft shadows from area lights (docs/shading.md, "Area lights"): each hit sends one shadow ray through each cell of
// an N x N grid over each area light, the light taken "as a grid to which we trace several shadow rays" (Reis, after
// Roger et al. 2007; ../shared/seeds). A sample is then a point light at a point of the light, with the share of the
// light's power that cell carries, so light_incidence and shade_light treat it as any other light. The grid is the
// same in every stage (the GLSL twin is common/shaders/trace/area_light.glsl): cell centres, or with --light-jitter
// the whole grid shifted by an offset that depends only on the pixel, its sample and the light.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "common/scene/scene.h"
#include "offset.h"
#include "shading.h"

namespace rt {

constexpr int kDefaultLightGrid = 4;   // --light-grid: 4 x 4 = 16 shadow rays per area light and hit
constexpr int kMaxLightGrid = 16;      // 256 cells: a ray names its cell in 8 bits (hit_record.h)

// How the area lights are sampled (--light-grid, --light-jitter).
struct LightGrid {
    int n = kDefaultLightGrid;
    bool jitter = false;
    std::uint32_t cells() const { return std::uint32_t(n) * std::uint32_t(n); }
};

// Which camera sample a shading point belongs to: what --light-jitter's offset is seeded with.
struct PixelSample {
    std::uint32_t pixel = 0;    // y * width + x
    std::uint32_t sample = 0;   // 0 .. spp - 1
};

// An integer hash (Wellons' "lowbias32"): every bit of the input moves about half of the output's. The same uint
// arithmetic in GLSL (area_light_hash) gives the same bits.
constexpr std::uint32_t area_light_hash(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// The grid's offset inside each cell, in [0, 1)^2: the centre (0.5, 0.5), or with jitter a point that depends on the
// pixel, its sample and the light only (the same in every stage; 24 bits, exact in float).
inline glm::vec2 light_grid_offset(const LightGrid& grid, PixelSample id, std::uint32_t light) {
    if (!grid.jitter) return glm::vec2(0.5f);
    const std::uint32_t h = area_light_hash(id.pixel ^ area_light_hash(id.sample ^ area_light_hash(light)));
    const std::uint32_t h2 = area_light_hash(h);
    return glm::vec2(float(h >> 8) * 0x1p-24f, float(h2 >> 8) * 0x1p-24f);
}

// Cell `cell` of the n x n grid (row-major: cell = j n + i) as a point of the unit square, `offset` inside the cell.
inline glm::vec2 light_grid_point(int n, std::uint32_t cell, glm::vec2 offset) {
    const float i = float(cell % std::uint32_t(n)), j = float(cell / std::uint32_t(n));
    return glm::vec2((i + offset.x) / float(n), (j + offset.y) / float(n));
}

// A point on an area light: where it is, the light's front normal there (unit) and its texture coordinates.
struct AreaSample {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    glm::vec2 uv{0.0f};
};

// The point of the light that the unit-square point q stands for, area preserving: on a parallelogram corner +
// q.x edge_u + q.y edge_v (a grid on the quad; the centre is its centroid); otherwise q.x picks triangle k by the
// area's running share (its stretch of [0, 1) rescaled to [0, 1)) and (s, t) = (sqrt(x), q.y) the point
// (1 - s) A + s (1 - t) B + s t C (Shirley & Chiu's square-to-triangle map).
inline AreaSample sample_area_light(const Scene& scene, const AreaLight& light, glm::vec2 q) {
    AreaSample s;
    if (light.parallelogram) {
        s.position = light.corner + q.x * light.edge_u + q.y * light.edge_v;
        s.normal = glm::normalize(glm::cross(light.edge_u, light.edge_v));
        s.uv = light.uv_corner + q.x * light.uv_edge_u + q.y * light.uv_edge_v;
        return s;
    }
    // The first triangle whose running share exceeds q.x (a binary search: a light may have many triangles).
    const float* cdf = scene.area_light_cdf.data() + light.cdf_first;
    std::uint32_t lo_k = 0, hi_k = light.triangle_count - 1;
    while (lo_k < hi_k) {
        const std::uint32_t mid = (lo_k + hi_k) / 2;
        if (q.x < cdf[mid]) hi_k = mid;
        else lo_k = mid + 1;
    }
    const std::uint32_t k = lo_k;
    const float lo = k > 0 ? cdf[k - 1] : 0.0f;
    const float x = std::clamp((q.x - lo) / (cdf[k] - lo), 0.0f, 1.0f);
    const float root = std::sqrt(x);
    const float u = root * (1.0f - q.y), v = root * q.y, w = 1.0f - u - v;
    const std::size_t i = 3 * std::size_t(light.first_triangle + k);
    const glm::vec3 a = scene.positions[i], b = scene.positions[i + 1], c = scene.positions[i + 2];
    s.position = w * a + u * b + v * c;
    s.normal = glm::normalize(glm::cross(b - a, c - a));
    s.uv = w * scene.uvs[i] + u * scene.uvs[i + 1] + v * scene.uvs[i + 2];
    return s;
}

// Cell `cell` of the grid of light `light_index` (in the lights' one numbering: an area light is light
// scene.lights.size() + a) for the camera sample `id`: what Whitted::shade aims its shadow ray at, and what
// tests/retrace_hits aims a dump's ray at again.
inline AreaSample area_light_cell(const Scene& scene, const LightGrid& grid, std::uint32_t light_index,
                                  std::uint32_t cell, PixelSample id) {
    const AreaLight& light = scene.area_lights[light_index - scene.lights.size()];
    return sample_area_light(scene, light, light_grid_point(grid.n, cell, light_grid_offset(grid, id, light_index)));
}

// The radiance the light emits at the sample: its material's emission, times its emissive texture there when
// textures are simulated (as the surface itself shows it), at most kMaxRadiance.
inline glm::vec3 area_light_emission(const Scene& scene, const AreaLight& light, const AreaSample& s, bool textures) {
    const Material& m = scene.materials[light.material];
    glm::vec3 texel(1.0f);
    if (textures && m.emissive_texture >= 0 && std::size_t(m.emissive_texture) < scene.textures.size())
        texel = glm::vec3(sample_texture(scene.textures[std::size_t(m.emissive_texture)], s.uv));
    return glm::min(m.emissive * texel, glm::vec3(kMaxRadiance));
}

// The sample as a point light for a surface point p: at the sample, the emission's colour, and the intensity
// L A cos(theta_l) / cells (L: the emission's largest channel; theta_l: between the light's normal and p), so that
// light_incidence gives L cos(theta_l) cos(theta) A / (cells d^2), the cell's share of the light's irradiance.
// False when the cell sends nothing to p: p behind a one-sided light (or edge-on), or a black texel.
inline bool area_sample_as_point_light(const AreaLight& light, const AreaSample& s, const glm::vec3& emission,
                                       std::uint32_t cells, const glm::vec3& p, Light& out) {
    const glm::vec3 d = p - s.position;
    const float length = std::sqrt(glm::dot(d, d));
    float cos_light = glm::dot(s.normal, d) / length;
    if (light.two_sided) cos_light = std::fabs(cos_light);
    const float peak = std::max({emission.r, emission.g, emission.b});
    if (!(cos_light > 0.0f) || !(peak > 0.0f)) return false;   // also NaN: p on the sample
    out = Light{};
    out.type = LightType::Point;
    out.position = s.position;
    out.color = emission / peak;
    out.intensity = peak * (light.area / float(cells)) * cos_light;
    return true;
}

// A shadow ray to a sample ends just short of it, so the light's own triangle never blocks it: at the sample moved
// off the light towards the ray's origin as a spawned ray's origin is moved off its surface (offset.h), less a
// relative 2^-13 of the length. The offset alone is not enough: a ray/triangle test's t carries the rounding of the
// whole ray (measured: a ray aimed through the shared diagonal of a quad light 3 units away met it 2e-6 beyond the
// offset target about half the time). pbrt shortens its shadow rays alike (ShadowEpsilon, 1e-4 of the segment).
constexpr float kShadowRayShortening = 0x1p-13f;

template <class T>
T area_shadow_tmax(OffsetMethod method, T epsilon, const AreaSample& s, const Vec3<T>& origin,
                   const Vec3<T>& direction) {
    const Vec3<T> target = offset_ray_origin(method, Vec3<T>(s.position), Vec3<T>(s.normal), -direction, epsilon);
    return glm::length(target - origin) * (T(1) - T(kShadowRayShortening));
}

}  // namespace rt
