// GLSL twin of common/trace/opacity.h: alpha cut-outs (docs/shading.md, "Alpha: cut-outs and blending"). Every GPU
// traversal calls cutout_opaque where it accepts a candidate hit (brute_force.glsl, stage 03's grid.glsl, stage
// 04's rh_leaf.comp and rh_closest.glsl), and only under ENABLE_CUTOUTS (rt::gpu::effect_defines: the scene uses a
// MASK or BLEND material), so a scene without cut-outs compiles none of this and binds nothing more. opacity.h says
// why a traversal stays exact: a transparent hit is simply no hit, decided by the triangle and (u, v) alone.
// A shader may use at most 16 storage blocks (Mesa counts every declared one), so in a pass that has not included
// scene.glsl, it is included with RT_SCENE_MATERIALS_ONLY: uvs, material ids, materials and textures only.
// (The shader include step ignores #ifdef: a file included inside a disabled block counts as included, so a program
// must not include shading.glsl or scene.glsl after a traversal. The wavefront passes never do.)
#ifdef ENABLE_CUTOUTS
#ifndef RT_SCENE_ACCESS   // scene.glsl not included yet (stages 03-04): only the blocks the test reads
#define RT_SCENE_MATERIALS_ONLY
#endif
#include "shading.glsl"

// The base colour factor's alpha times the texture's alpha at the hit's uv, interpolated as surface_point
// (scene.glsl) does and sampled as the colour is (sample_texture), times the vertex colour's alpha.
float surface_opacity(uint triangle, float u, float v) {
    const Material m = rt_materials[rt_material_ids[triangle]];
    precise float alpha = m.base_color.a;
    if (m.base_color_texture >= 0) {
        const uint i = 3u * triangle;
        precise float w = 1.0 - u - v;
        precise vec2 uv = w * rt_uvs[i] + u * rt_uvs[i + 1u] + v * rt_uvs[i + 2u];
        alpha *= sample_texture(m.base_color_texture, rt_transform_uv(m.base_color_uv_matrix, m.base_color_uv_offset, uv)).a;
    }
#ifdef RT_VERTEX_COLORS
    alpha *= rt_vertex_color(triangle, u, v).a;   // COLOR_0's alpha, as surface_opacity (opacity.h)
#endif
    return alpha;
}

// Whether a hit at (u, v) counts: opacity >= the material's cutoff (alpha_cutoff holds alpha_test_cutoff: 0.5 for
// BLEND). OPAQUE materials skip the lookup. With BLEND read as coverage (ENABLE_BLEND), a BLEND surface counts
// wherever its opacity is above 0, except in the programs that trace shadow rays (RT_SHADOW_RAYS: the wavefront's
// shadow pass, a traversal's any-hit program), which keep the cut-out (opacity.h says why).
bool surface_opaque(uint triangle, float u, float v) {
    const Material m = rt_materials[rt_material_ids[triangle]];
    if (m.alpha_mode == RT_ALPHA_OPAQUE) return true;
    const float alpha = surface_opacity(triangle, u, v);
#if defined(ENABLE_BLEND) && !defined(RT_SHADOW_RAYS)
    if (m.alpha_mode == RT_ALPHA_BLEND) return alpha > 0.0;
#endif
    return alpha >= m.alpha_cutoff;
}
#endif

// The hook the traversals call on a candidate hit: always true without cut-outs (and then compiled away).
bool cutout_opaque(uint triangle, float u, float v) {
#ifdef ENABLE_CUTOUTS
    return surface_opaque(triangle, u, v);
#else
    return true;
#endif
}
