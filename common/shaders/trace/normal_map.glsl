// Normal maps: the GLSL twin of common/trace/normal_map.{h,cpp} (docs/shading.md, "Normal maps"), operation for
// operation.
#include "shading.glsl"
#include "texture_transform.glsl"

// (2 texel - 1) * (scale, scale, 1) (rt::decode_normal_texel).
vec3 decode_normal_texel(vec3 texel, float scale) {
    precise vec3 m = (2.0 * texel - 1.0) * vec3(scale, scale, 1.0);
    return m;
}

// rt::tangent_to_world: Gram-Schmidt of the tangent against n, b = sign(w) cross(n, t), normalize(m.x t + m.y b +
// m.z n); false when the frame or the result degenerates.
bool tangent_to_world(vec3 n, vec4 tangent, vec3 m, out vec3 result) {
    result = vec3(0.0);
    const vec3 t0 = tangent.xyz;
    precise vec3 t1 = t0 - n * rt_dot(n, t0);
    const float t_len = rt_length(t1);
    if (!(t_len > 0.0) || !rt_isfinite(t_len)) return false;
    precise vec3 t = t1 / t_len;
    precise vec3 b = (tangent.w < 0.0 ? -1.0 : 1.0) * rt_cross(n, t);
    precise vec3 p = m.x * t + m.y * b + m.z * n;
    const float p_len = rt_length(p);
    if (!(p_len > 0.0) || !rt_isfinite(p_len)) return false;
    precise vec3 r = p / p_len;
    result = r;
    return true;
}

// rt::normal_mapped: the shading normal of a hit on `triangle` at barycentrics (w, u, v) for a material with a
// normal map, turned to the side of the geometric normal; shading_normal unchanged when the map cannot apply.
vec3 normal_mapped(uint triangle, float w, float u, float v, vec2 uv, vec3 geometric_normal, vec3 shading_normal,
                   Material m) {
    const uint i = 3u * triangle;
    const uint first_tangent = 3u * rt_triangle_count;
    if (m.normal_texture < 0 || uint(m.normal_texture) >= rt_texture_count ||
        uint(rt_normals.length()) < first_tangent + i + 3u)
        return shading_normal;
    precise vec3 ns = w * rt_normals[i].xyz + u * rt_normals[i + 1u].xyz + v * rt_normals[i + 2u].xyz;
    const float ns_len = rt_length(ns);
    if (!(ns_len > 0.0) || !rt_isfinite(ns_len)) return shading_normal;
    precise vec3 n = ns / ns_len;
    precise vec4 tangent = w * rt_normals[first_tangent + i] + u * rt_normals[first_tangent + i + 1u] +
                           v * rt_normals[first_tangent + i + 2u];
    const vec2 tuv = rt_transform_uv(m.normal_uv_matrix, m.normal_uv_offset, uv);
    const vec4 texel = sample_texture_decoded(m.normal_texture, tuv, false);
    const vec3 decoded = decode_normal_texel(texel.rgb, m.normal_scale);
    vec3 mapped;
    if (!tangent_to_world(n, tangent, decoded, mapped)) return shading_normal;
    return rt_dot(mapped, geometric_normal) < 0.0 ? -mapped : mapped;
}
