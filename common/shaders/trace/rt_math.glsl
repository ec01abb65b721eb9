// Vector helpers that evaluate exactly as glm does (same operations in the same order, never fused into FMAs:
// `precise`), so the GLSL twins round like their C++ originals. GLSL's built-in dot/normalize/length/mix may use
// FMAs, other orders or approximate reciprocals; use these in code that must match the CPU.

#define RT_INFINITY uintBitsToFloat(0x7f800000u)

float rt_dot(vec3 a, vec3 b) {               // glm: tmp = a * b; tmp.x + tmp.y + tmp.z
    precise vec3 t = a * b;
    precise float r = t.x + t.y + t.z;
    return r;
}
float rt_length(vec3 v) { precise float r = sqrt(rt_dot(v, v)); return r; }
vec3 rt_normalize(vec3 v) {                  // glm: v * inversesqrt(dot(v, v)), inversesqrt(x) = 1 / sqrt(x)
    precise float inv = 1.0 / sqrt(rt_dot(v, v));
    precise vec3 r = v * inv;
    return r;
}
vec3 rt_cross(vec3 x, vec3 y) {
    precise vec3 r = vec3(x.y * y.z - y.y * x.z, x.z * y.x - y.z * x.x, x.x * y.y - y.x * x.y);
    return r;
}
vec4 rt_mix(vec4 x, vec4 y, float a) {       // glm: x * (1 - a) + y * a
    precise vec4 r = x * (1.0 - a) + y * a;
    return r;
}
float rt_clamp(float v, float lo, float hi) { return v < lo ? lo : (hi < v ? hi : v); }   // std::clamp
bool rt_isfinite(float x) { return !isinf(x) && !isnan(x); }
