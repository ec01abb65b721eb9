// GLSL twin of common/trace/area_light.h: an area light's grid of samples, each a point light (docs/shading.md, "Area
// lights"). Written operation for operation like the C++ with `precise`, so the samples, their light and their
// shadow rays' ends round alike. Compiled only for a scene with area lights (RT_AREA_LIGHTS: rt::gpu::Wavefront).
#include "shading.glsl"
#include "offset.glsl"

#ifdef RT_AREA_LIGHTS
// The area lights (GpuAreaLight, 6 vec4 each), then the running areas of those that are not parallelograms, one
// float each (GpuScene::upload). Declared only for a scene that has area lights, and only here (scene.glsl says why).
layout(std430, binding = RT_BINDING_AREA_LIGHTS) readonly buffer SceneAreaLights { vec4 rt_area_light_data[]; };

#define RT_AREA_LIGHT_PARALLELOGRAM 1u   // kAreaLightParallelogram
#define RT_AREA_LIGHT_TWO_SIDED 2u       // kAreaLightTwoSided

struct AreaLight {                   // GpuAreaLight (gpu_scene.h), rt_area_light_data[6a .. 6a + 5]
    vec3 corner; float area;
    vec3 edge_u; uint first_triangle;
    vec3 edge_v; uint triangle_count;
    vec2 uv_corner; vec2 uv_edge_u;
    vec2 uv_edge_v; uint material; uint flags;
    uint cdf_first;
};

AreaLight rt_area_light(uint a) {
    const uint i = 6u * a;
    const vec4 v0 = rt_area_light_data[i], v1 = rt_area_light_data[i + 1u], v2 = rt_area_light_data[i + 2u];
    const vec4 v3 = rt_area_light_data[i + 3u], v4 = rt_area_light_data[i + 4u], v5 = rt_area_light_data[i + 5u];
    return AreaLight(v0.xyz, v0.w, v1.xyz, floatBitsToUint(v1.w), v2.xyz, floatBitsToUint(v2.w), v3.xy, v3.zw,
                     v4.xy, floatBitsToUint(v4.z), floatBitsToUint(v4.w), floatBitsToUint(v5.x));
}

// The running share of the area, entry k (Scene::area_light_cdf), after the lights' records.
float rt_area_light_cdf(uint k) {
    const uint at = 24u * rt_area_light_count + k;
    return rt_area_light_data[at / 4u][at % 4u];
}

uint area_light_hash(uint x) {   // rt::area_light_hash
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

// rt::light_grid_offset: the cell centres, or with --light-jitter an offset seeded by pixel, sample and light.
vec2 light_grid_offset(bool jitter, uint pixel, uint sample_index, uint light) {
    if (!jitter) return vec2(0.5);
    const uint h = area_light_hash(pixel ^ area_light_hash(sample_index ^ area_light_hash(light)));
    const uint h2 = area_light_hash(h);
    const float unit = 5.9604644775390625e-08;   // 2^-24
    precise vec2 o = vec2(float(h >> 8u) * unit, float(h2 >> 8u) * unit);
    return o;
}

vec2 light_grid_point(uint n, uint cell, vec2 offset) {   // rt::light_grid_point
    const float i = float(cell % n), j = float(cell / n);
    precise vec2 q = vec2((i + offset.x) / float(n), (j + offset.y) / float(n));
    return q;
}

struct AreaSample {
    vec3 position;
    vec3 normal;   // the light's front, unit
    vec2 uv;
};

// rt::sample_area_light: a parallelogram's grid, or a triangle picked by area and Shirley & Chiu's map.
AreaSample sample_area_light(AreaLight light, vec2 q) {
    AreaSample s;
    if ((light.flags & RT_AREA_LIGHT_PARALLELOGRAM) != 0u) {
        precise vec3 p = light.corner + q.x * light.edge_u + q.y * light.edge_v;
        s.position = p;
        s.normal = rt_normalize(rt_cross(light.edge_u, light.edge_v));
        precise vec2 uv = light.uv_corner + q.x * light.uv_edge_u + q.y * light.uv_edge_v;
        s.uv = uv;
        return s;
    }
    uint lo_k = 0u, hi_k = light.triangle_count - 1u;
    while (lo_k < hi_k) {
        const uint mid = (lo_k + hi_k) / 2u;
        if (q.x < rt_area_light_cdf(light.cdf_first + mid)) hi_k = mid;
        else lo_k = mid + 1u;
    }
    const uint k = lo_k;
    const float lo = k > 0u ? rt_area_light_cdf(light.cdf_first + k - 1u) : 0.0;
    precise float stretched = (q.x - lo) / (rt_area_light_cdf(light.cdf_first + k) - lo);
    const float x = rt_clamp(stretched, 0.0, 1.0);
    precise float root = sqrt(x);
    precise float u = root * (1.0 - q.y), v = root * q.y;
    precise float w = 1.0 - u - v;
    const uint i = 3u * (light.first_triangle + k);
    const vec3 a = rt_positions[i].xyz, b = rt_positions[i + 1u].xyz, c = rt_positions[i + 2u].xyz;
    precise vec3 p = w * a + u * b + v * c;
    s.position = p;
    precise vec3 ba = b - a, ca = c - a;
    s.normal = rt_normalize(rt_cross(ba, ca));
    precise vec2 uv = w * rt_uvs[i] + u * rt_uvs[i + 1u] + v * rt_uvs[i + 2u];
    s.uv = uv;
    return s;
}

// rt::area_light_emission: the material's emission times its emissive texture there (with textures).
vec3 area_light_emission(AreaLight light, AreaSample s) {
    const Material m = rt_materials[light.material];
    vec3 texel = vec3(1.0);
#ifdef ENABLE_TEXTURES
    if (m.emissive_texture >= 0) texel = sample_texture(m.emissive_texture, s.uv).rgb;
#endif
    precise vec3 e = m.emissive * texel;
    return min(e, vec3(RT_MAX_RADIANCE));
}

// rt::area_sample_as_point_light: the sample as a point light of intensity L A cos(theta_l) / cells for p.
bool area_sample_as_point_light(AreaLight light, AreaSample s, vec3 emission, uint cells, vec3 p, out Light point) {
    point = Light(vec3(0.0), RT_LIGHT_POINT, vec3(0.0), 0.0, vec3(0.0), 0.0, 0.0, 0.0, 1.0, 1.0);
    precise vec3 d = p - s.position;
    precise float len = sqrt(rt_dot(d, d));
    precise float cosine = rt_dot(s.normal, d) / len;
    float cos_light = cosine;
    if ((light.flags & RT_AREA_LIGHT_TWO_SIDED) != 0u) cos_light = abs(cos_light);
    const float peak = max(max(emission.r, emission.g), emission.b);
    if (!(cos_light > 0.0) || !(peak > 0.0)) return false;
    point.position = s.position;
    precise vec3 color = emission / peak;
    point.color = color;
    precise float intensity = peak * (light.area / float(cells)) * cos_light;
    point.intensity = intensity;
    return true;
}

// rt::area_shadow_tmax: the sample moved off the light towards the origin, less 2^-13 of the length.
const float RT_SHADOW_RAY_SHORTENING = 1.220703125e-04;   // 2^-13, kShadowRayShortening
float area_shadow_tmax(int offset_method, float epsilon, AreaSample s, vec3 origin, vec3 direction) {
    const vec3 target = offset_ray_origin(offset_method, s.position, s.normal, -direction, epsilon);
    precise vec3 to_target = target - origin;
    precise float tmax = rt_length(to_target) * (1.0 - RT_SHADOW_RAY_SHORTENING);
    return tmax;
}
#endif
