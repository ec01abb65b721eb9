// Alpha cut-outs (glTF alphaMode MASK, and BLEND as read by docs/shading.md, "Alpha: cut-outs and blending"): where
// a surface's opacity is below its material's cutoff, a ray passes through it as if the triangle were not there. A
// BLEND surface read as coverage (Effects::blend) is there wherever its opacity is above 0, for all but shadow rays.
// This is the one opacity test every traversal applies where it accepts a candidate hit: stage 01's brute force
// (brute_force_tracer.h), stage 03's CPU grid (uniform_grid.cpp); common/shaders/trace/opacity.glsl is its GLSL twin,
// used by every GPU traversal. Only scenes whose triangles use a MASK or BLEND material run it (Effects::cutouts).
//
// Why every traversal stays exact: the test only turns some hits of the ray/triangle test into misses, and whether
// a hit at barycentrics (u, v) is opaque depends on the triangle and (u, v) alone, never on tmax or on the other
// triangles. So "intersect, then keep the hit only where opaque" is itself a ray/triangle test with the property
// every traversal's argument relies on (a hit with t < tmax, and the same u, v, t whatever tmax lets it through),
// and the ties, tmax shrinking and early exits of each traversal give the same answer as brute force over it.
#pragma once

#include <cstddef>

#include "common/scene/scene.h"
#include "shading.h"
#include "texture_transform.h"

namespace rt {

// The threshold of a material's alpha test: alphaCutoff for MASK, 0.5 for BLEND (a cut-out at half coverage: shadow
// rays, and every ray without Effects::blend), and 0 for OPAQUE (every opacity passes).
inline float alpha_test_cutoff(const Material& m) {
    switch (m.alpha_mode) {
        case AlphaMode::Mask: return m.alpha_cutoff;
        case AlphaMode::Blend: return 0.5f;
        default: return 0.0f;
    }
}

// The vertex colour (COLOR_0) at barycentrics (u, v) of the triangle whose first vertex is i, as c0 + u (c1 - c0)
// + v (c2 - c0): a triangle of one colour gets exactly that colour (w c0 + u c0 + v c0 need not be c0 in float, as
// w + u + v need not be 1), so a white one leaves the base colour bit for bit. The GLSL twin: rt_vertex_color.
inline glm::vec4 vertex_color(const Scene& scene, std::size_t i, float u, float v) {
    const glm::vec4 c0 = scene.colors[i];
    return c0 + u * (scene.colors[i + 1] - c0) + v * (scene.colors[i + 2] - c0);
}

// Opacity at barycentrics (u, v) of a triangle: the base colour factor's alpha times the base colour texture's alpha
// at the hit's texture coordinates, interpolated exactly as surface_point (whitted.h) does and sampled as the colour
// is (sample_texture), so the test and the shading see the same texel; times the vertex colour's alpha (COLOR_0).
template <class T>
float surface_opacity(const Scene& scene, std::size_t triangle, T u, T v) {
    const Material& m = scene.materials[scene.material_ids[triangle]];
    float alpha = m.base_color.a;
    if (m.base_color_texture >= 0) {
        const std::size_t i = 3 * triangle;
        const T w = T(1) - u - v;
        const float wf = float(w), uf = float(u), vf = float(v);
        const glm::vec2 uv = wf * scene.uvs[i] + uf * scene.uvs[i + 1] + vf * scene.uvs[i + 2];
        alpha *= sample_texture(scene.textures[std::size_t(m.base_color_texture)], transform_uv(m.base_color_transform, uv)).a;
    }
    if (!scene.colors.empty()) alpha *= vertex_color(scene, 3 * triangle, float(u), float(v)).a;   // COLOR_0's
    return alpha;
}

// Whether a hit at (u, v) on the triangle counts: opacity >= cutoff (glTF: "rendered fully opaque" at the cutoff).
// With `blend_coverage` (Effects::blend, for every ray but shadow rays), a BLEND surface counts wherever it covers
// anything (opacity > 0): the hit is shaded with weight alpha and a transparency ray carries the rest (whitted.h).
// Shadow rays keep the cut-out at 0.5 for BLEND: Whitted's shadow rays are all or nothing, and a coverage-weighted
// shadow would need the product of (1 - alpha) over every BLEND surface on the segment, in one order that every
// traversal shares (docs/shading.md, "Alpha: cut-outs and blending").
template <class T>
bool surface_opaque(const Scene& scene, std::size_t triangle, T u, T v, bool blend_coverage = false) {
    const Material& m = scene.materials[scene.material_ids[triangle]];
    if (m.alpha_mode == AlphaMode::Opaque) return true;
    const float alpha = surface_opacity(scene, triangle, u, v);
    if (blend_coverage && m.alpha_mode == AlphaMode::Blend) return alpha > 0.0f;
    return alpha >= alpha_test_cutoff(m);
}

}  // namespace rt
