// GLSL twins of common/trace/offset.h (float): where a secondary ray starts.
#include "rt_math.glsl"

#define RT_OFFSET_EPSILON 0
#define RT_OFFSET_ROBUST 1
#define RT_DEFAULT_EPSILON 1e-4

// Waechter & Binder (2019): move p along n by a number of ulps (integer arithmetic on the float bits), and by a small
// absolute amount near the origin. n points to the side the new ray leaves on.
vec3 offset_robust(vec3 p, vec3 n) {
    const float origin = 1.0 / 32.0;
    const float float_scale = 1.0 / 65536.0;
    const float int_scale = 8.0;      // offset.h explains why 8 and not W&B's 256
    vec3 result;
    for (int i = 0; i < 3; ++i) {
        precise float scaled = int_scale * n[i];
        const int of = rt_isfinite(n[i]) ? int(scaled) : 0;
        const int bits = floatBitsToInt(p[i]);
        const float moved = intBitsToFloat(bits + (p[i] < 0.0 ? -of : of));
        precise float near_origin = p[i] + float_scale * n[i];
        result[i] = abs(p[i]) < origin ? near_origin : moved;
    }
    return result;
}

vec3 offset_epsilon(vec3 p, vec3 n, float eps) {
    precise vec3 r = p + n * eps;
    return r;
}

// The knob: geometric_normal in any orientation, direction = the new ray's.
vec3 offset_ray_origin(int method, vec3 p, vec3 geometric_normal, vec3 direction, float eps) {
    const vec3 n = rt_dot(geometric_normal, direction) < 0.0 ? -geometric_normal : geometric_normal;
    return method == RT_OFFSET_ROBUST ? offset_robust(p, n) : offset_epsilon(p, n, eps);
}
