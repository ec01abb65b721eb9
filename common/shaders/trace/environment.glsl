// What a ray that leaves the scene brings back (docs/shading.md, "The environment"): twin of
// common/trace/environment.{h,cpp}, operation for operation (`precise`, no built-in atan), so both round alike.
// Include after scene.glsl. Without RT_ENVIRONMENT (no --environment) this is only the background colour: no
// texture is declared or bound, no lookup is compiled.
#ifdef RT_ENVIRONMENT
// The map as RGBA32F, row 0 = the image's top = +Y, read with texelFetch (our own bilinear, as the C++ does).
layout(binding = RT_TEXTURE_UNIT_ENVIRONMENT) uniform sampler2D rt_environment_map;

#define RT_ENV_PI 3.14159265358979

// Twin of rt::environment_atan2: Abramowitz & Stegun 4.4.47 on [0, 1], then the octant.
float rt_environment_atan2(float y, float x) {
    const float ax = abs(x), ay = abs(y);
    const float hi = ax > ay ? ax : ay;
    const float lo = ax > ay ? ay : ax;
    if (hi == 0.0) return 0.0;
    precise float r = lo / hi;
    precise float r2 = r * r;
    precise float a = r * (0.9998660 + r2 * (-0.3302995 + r2 * (0.1801410 + r2 * (-0.0851330 + r2 * 0.0208351))));
    if (ay > ax) a = 0.5 * RT_ENV_PI - a;
    if (x < 0.0) a = RT_ENV_PI - a;
    return y < 0.0 ? -a : a;
}

// Twin of rt::environment_uv: -Z is the image's centre (u = 0.5), u grows towards +X, v = 0 straight up.
vec2 rt_environment_uv(vec3 d, vec2 rotation) {
    const float c = rotation.x, s = rotation.y;
    precise float x = d.x * c - d.z * s;
    precise float z = d.x * s + d.z * c;
    precise float u = 0.5 + rt_environment_atan2(x, -z) / (2.0 * RT_ENV_PI);
    precise float v = rt_environment_atan2(sqrt(x * x + z * z), d.y) / RT_ENV_PI;
    return vec2(u, v);
}

vec4 rt_environment_texel(ivec2 size, int x, int y) {
    x = x < 0 ? x + size.x : (x >= size.x ? x - size.x : x);   // wrap in u
    y = y < 0 ? 0 : (y >= size.y ? size.y - 1 : y);           // clamp in v
    return texelFetch(rt_environment_map, ivec2(x, y), 0);
}

// Twin of rt::sample_environment: bilinear between the four texel centres around (u, v).
vec3 rt_sample_environment(vec2 uv) {
    const ivec2 size = textureSize(rt_environment_map, 0);
    if (size.x <= 0 || size.y <= 0 || !rt_isfinite(uv.x) || !rt_isfinite(uv.y)) return vec3(0.0);
    const float u = uv.x < 0.0 ? 0.0 : (uv.x > 1.0 ? 1.0 : uv.x);
    const float v = uv.y < 0.0 ? 0.0 : (uv.y > 1.0 ? 1.0 : uv.y);
    precise float sx = u * float(size.x) - 0.5, sy = v * float(size.y) - 0.5;
    const float x0f = floor(sx), y0f = floor(sy);
    precise float ax = sx - x0f, ay = sy - y0f;
    const int x0 = int(x0f), y0 = int(y0f);
    const vec4 top = rt_mix(rt_environment_texel(size, x0, y0), rt_environment_texel(size, x0 + 1, y0), ax);
    const vec4 bottom = rt_mix(rt_environment_texel(size, x0, y0 + 1), rt_environment_texel(size, x0 + 1, y0 + 1), ax);
    return rt_mix(top, bottom, ay).rgb;
}
#endif

// Twin of rt::miss_radiance.
vec3 rt_miss_radiance(vec3 direction) {
#ifdef RT_ENVIRONMENT
    return rt_sample_environment(rt_environment_uv(direction, rt_environment_rotation));
#else
    return rt_background;
#endif
}
