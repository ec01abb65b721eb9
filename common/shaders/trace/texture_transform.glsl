// KHR_texture_transform: the GLSL twin of rt::transform_uv (common/trace/texture_transform.h; docs/shading.md,
// "Texture transform"). The matrix (a, b, c, d) comes precomputed per material (GpuMaterial *_uv_matrix).

// uv' = (a u + b v, c u + d v) + offset; the identity gives uv back exactly.
vec2 rt_transform_uv(vec4 m, vec2 offset, vec2 uv) {
    precise float u = m.x * uv.x + m.y * uv.y + offset.x;
    precise float v = m.z * uv.x + m.w * uv.y + offset.y;
    return vec2(u, v);
}
