// GLSL twin of the shading model (common/trace/shading.h, shading.cpp, and Whitted::coefficients of whitted.h);
// docs/shading.md is the contract. Everything is linear RGB. Written operation for operation like the C++ code with
// `precise`, so results are bit-identical where GLSL's arithmetic is IEEE-exact (add, mul, div and sqrt on
// llvmpipe); pow() and the cone cosines differ: cosines come precomputed from the CPU (Light.cos_inner/cos_outer),
// pow is the GPU's (unit tests allow a relative error for shade_light).
#include "scene.glsl"
#include "texture_transform.glsl"

#define RT_FRESNEL_SCHLICK 0
#define RT_FRESNEL_EXACT 1

const float RT_AMBIENT = 0.03;
const float RT_DEFAULT_CUTOFF = 1e-3;
const float RT_PI = 3.14159265358979;
const float RT_MAX_RADIANCE = 1e20;   // kMaxRadiance: largest irradiance of a light and emitted radiance

// Twin of rt::ambient_light for the scene's ambient model, chosen at compile time: RT_AMBIENT_NONE,
// RT_AMBIENT_HEMISPHERE, or neither for the constant term (rt::gpu::Wavefront sets them from the scene).
const float RT_AMBIENT_GROUND = 0.4;   // kAmbientGround
const float RT_AMBIENT_RISE = 1.2;     // kAmbientRise
vec3 ambient_light(vec3 diffuse, vec3 n) {
#if defined(RT_AMBIENT_NONE)
    return vec3(0.0);
#elif defined(RT_AMBIENT_HEMISPHERE)
    precise float up = 0.5 * (1.0 + n.y);
    precise float weight = RT_AMBIENT_GROUND + RT_AMBIENT_RISE * up;
    precise vec3 a = (RT_AMBIENT * weight) * diffuse;
    return a;
#else
    precise vec3 a = RT_AMBIENT * diffuse;
    return a;
#endif
}

// Mirror reflection of d about n (n unit length).
vec3 reflect_dir(vec3 d, vec3 n) {
    precise vec3 r = d - 2.0 * rt_dot(d, n) * n;
    return r;
}

// Snell's law; d unit, n on the incident side, eta = n_i / n_t. False under total internal reflection.
bool refract_dir(vec3 d, vec3 n, float eta, out vec3 dir) {
    dir = vec3(0.0);
    precise float cos_i = -rt_dot(d, n);
    precise float sin2_t = eta * eta * max(0.0, 1.0 - cos_i * cos_i);
    if (sin2_t >= 1.0) return false;
    precise float cos_t = sqrt(1.0 - sin2_t);
    precise vec3 t = eta * d + (eta * cos_i - cos_t) * n;
    dir = rt_normalize(t);
    return true;
}

float fresnel_exact(float cos_i, float eta) {
    cos_i = rt_clamp(cos_i, 0.0, 1.0);
    precise float sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if (sin2_t >= 1.0) return 1.0;
    precise float cos_t = sqrt(1.0 - sin2_t);
    precise float rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    precise float rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    precise float r = 0.5 * (rs * rs + rp * rp);
    return r;
}

float fresnel_schlick(float cos_i, float eta) {
    cos_i = rt_clamp(cos_i, 0.0, 1.0);
    precise float r0 = (eta - 1.0) / (eta + 1.0);
    r0 *= r0;
    if (r0 == 0.0) return 0.0;   // matched indices: no interface, nothing reflects (Schlick alone gives (1-c)^5)
    float c = cos_i;
    if (eta > 1.0) {
        precise float sin2_t = eta * eta * (1.0 - cos_i * cos_i);
        if (sin2_t >= 1.0) return 1.0;
        precise float ct = sqrt(1.0 - sin2_t);
        c = ct;
    }
    precise float m = 1.0 - c;
    precise float r = r0 + (1.0 - r0) * (m * m) * (m * m) * m;
    return r;
}

float fresnel(int mode, float cos_i, float eta) {
    return mode == RT_FRESNEL_EXACT ? fresnel_exact(cos_i, eta) : fresnel_schlick(cos_i, eta);
}

// ---------------------------------------------------------------------------------------------------------------
// Textures (wrap modes REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT per axis; nearest or bilinear per texture; sRGB decoded
// through the same table as the CPU; shading.cpp's fold, texel_index and sample).

#define RT_WRAP_REPEAT 0
#define RT_WRAP_CLAMP_TO_EDGE 1
#define RT_WRAP_MIRRORED_REPEAT 2
int rt_wrap_s(TextureInfo info) { return (info.sampler >> 1) & 3; }
int rt_wrap_t(TextureInfo info) { return (info.sampler >> 3) & 3; }

// A texture coordinate folded into [0, 1] by its wrap mode (c - 2 floor(c / 2) and 2 - m are exact in float).
float rt_fold(float c, int wrap) {
    if (wrap == RT_WRAP_CLAMP_TO_EDGE) return clamp(c, 0.0, 1.0);
    if (wrap == RT_WRAP_MIRRORED_REPEAT) {
        precise float m = c - 2.0 * floor(0.5 * c);
        return m <= 1.0 ? m : 2.0 - m;
    }
    precise float f = c - floor(c);
    return f;
}

// A texel index on one axis of n texels: REPEAT wraps any integer, negative included (((x % n) + n) % n); the other
// modes fold the coordinate into [0, 1] first, so an index is at most one past an edge and reads the edge texel.
int rt_texel_index(int x, int n, int wrap) {
    if (wrap != RT_WRAP_REPEAT) return clamp(x, 0, n - 1);
    return x >= 0 ? x % n : (n - 1) - ((-(x + 1)) % n);
}

// srgb: decode the colour channels from sRGB (colour textures), else every channel byte / 255 like alpha (data:
// normal maps, metallicRoughnessTexture, transmissionTexture).
vec4 rt_texel(TextureInfo info, int x, int y, bool srgb) {
    x = rt_texel_index(x, info.width, rt_wrap_s(info));
    y = rt_texel_index(y, info.height, rt_wrap_t(info));
    const uvec4 p = rt_texel_bytes(info, x, y);
    if (!srgb) return vec4(rt_alpha_lut[p.r], rt_alpha_lut[p.g], rt_alpha_lut[p.b], rt_alpha_lut[p.a]);
    return vec4(rt_srgb_lut[p.r], rt_srgb_lut[p.g], rt_srgb_lut[p.b], rt_alpha_lut[p.a]);
}

vec4 sample_texture_decoded(int texture_index, vec2 uv, bool srgb) {
    const TextureInfo info = rt_texture_info(texture_index);
    if (info.width <= 0 || info.height <= 0 || !rt_isfinite(uv.x) || !rt_isfinite(uv.y)) return vec4(1.0);
    precise vec2 f = vec2(rt_fold(uv.x, rt_wrap_s(info)), rt_fold(uv.y, rt_wrap_t(info)));
    precise float fx = f.x * float(info.width), fy = f.y * float(info.height);
    if ((info.sampler & 1) != 0) return rt_texel(info, int(fx), int(fy), srgb);
    precise float sx = fx - 0.5, sy = fy - 0.5;
    const float x0f = floor(sx), y0f = floor(sy);
    precise float ax = sx - x0f, ay = sy - y0f;
    const int x0 = int(x0f), y0 = int(y0f);
    const vec4 top = rt_mix(rt_texel(info, x0, y0, srgb), rt_texel(info, x0 + 1, y0, srgb), ax);
    const vec4 bottom = rt_mix(rt_texel(info, x0, y0 + 1, srgb), rt_texel(info, x0 + 1, y0 + 1, srgb), ax);
    return rt_mix(top, bottom, ay);
}

vec4 sample_texture(int texture_index, vec2 uv) { return sample_texture_decoded(texture_index, uv, true); }
vec4 sample_texture_linear(int texture_index, vec2 uv) { return sample_texture_decoded(texture_index, uv, false); }

// What a material's textures say at one point (rt::SurfaceTexels / sample_surface_textures in shading.cpp): each
// scales its factor; a texture the material does not have reads 1.
struct SurfaceTexels {
    vec4 base;
    float roughness;
    float metallic;
    vec3 emissive;
    float transmission;
};

SurfaceTexels surface_texels(vec4 base) { return SurfaceTexels(base, 1.0, 1.0, vec3(1.0), 1.0); }

SurfaceTexels sample_surface_textures(Material m, vec2 uv) {
    SurfaceTexels t = surface_texels(vec4(1.0));
    if (m.base_color_texture >= 0)
        t.base = sample_texture(m.base_color_texture, rt_transform_uv(m.base_color_uv_matrix, m.base_color_uv_offset, uv));
    if (m.metallic_roughness_texture >= 0) {
        const vec4 mr = sample_texture_linear(m.metallic_roughness_texture, uv);
        t.roughness = mr.g;
        t.metallic = mr.b;
    }
    if (m.emissive_texture >= 0) t.emissive = sample_texture(m.emissive_texture, uv).rgb;
    if (m.transmission_texture >= 0) t.transmission = sample_texture_linear(m.transmission_texture, uv).r;
    return t;
}

// ---------------------------------------------------------------------------------------------------------------
// Whitted coefficients of a surface point (docs/shading.md).

struct SurfaceCoefficients {
    vec3 diffuse;
    vec3 specular;
    float shininess;
    vec3 mirror;
    float smoothness;
    float dielectric;
    float transmission;
    vec3 base;
    vec3 f0_dielectric;
    vec3 emissive;
    float ior;
};

SurfaceCoefficients surface_coefficients(Material m, SurfaceTexels tex) {
    SurfaceCoefficients s;
    precise float textured_metallic = m.metallic * tex.metallic;
    precise float textured_roughness = m.roughness * tex.roughness;
    const float metallic = rt_clamp(textured_metallic, 0.0, 1.0);
    const float roughness = rt_clamp(textured_roughness, 0.0, 1.0);
    precise vec3 base = m.base_color.rgb * tex.base.rgb;
    s.base = base;
    precise float dielectric = 1.0 - metallic;
    s.dielectric = dielectric;
    precise float textured_transmission = m.transmission * tex.transmission;
    s.transmission = rt_clamp(textured_transmission, 0.0, 1.0);
    precise float smoothness = (1.0 - roughness) * (1.0 - roughness);
    s.smoothness = smoothness;
    s.ior = m.ior > 0.0 ? m.ior : 1.5;
    precise float r0 = (s.ior - 1.0) / (s.ior + 1.0);
    precise vec3 f0 = r0 * r0 * m.specular * m.specular_color;
    s.f0_dielectric = min(vec3(1.0), f0);
    precise vec3 diffuse = s.base * s.dielectric * (1.0 - s.transmission) + s.base * (metallic * (1.0 - s.smoothness));
    s.diffuse = diffuse;
    precise vec3 mirror = s.base * metallic * s.smoothness;
    s.mirror = mirror;
    precise float alpha = max(roughness * roughness, 0.1);
    precise float shininess = 2.0 / (alpha * alpha) - 2.0;
    s.shininess = shininess;
    precise vec3 specular = s.smoothness * (metallic * s.base + s.dielectric * s.f0_dielectric);
    s.specular = specular;
    precise vec3 emissive = m.emissive * tex.emissive;
    s.emissive = min(emissive, vec3(RT_MAX_RADIANCE));
    return s;
}

// With the base colour texel only (surface_coefficients(Material, vec4) in shading.h).
SurfaceCoefficients surface_coefficients(Material m, vec4 base_texel) {
    return surface_coefficients(m, surface_texels(base_texel));
}

// Irradiance-like factor of one light at p with unit normal n (light_incidence in shading.cpp): the light's
// radiance scale times the cosine term; to_light (unit) and distance (infinite for directional lights) are set.
vec3 light_incidence(Light light, vec3 p, vec3 n, out vec3 to_light, out float distance) {
    to_light = vec3(0.0);
    distance = 0.0;
    precise float scale = min(light.intensity, RT_MAX_RADIANCE);
    if (light.type == RT_LIGHT_DIRECTIONAL) {
        to_light = -rt_normalize(light.direction);
        distance = RT_INFINITY;
    } else {
        precise vec3 d = light.position - p;
        const float d2 = rt_dot(d, d);
        if (!(d2 > 0.0)) return vec3(0.0);
        precise float dist = sqrt(d2);
        distance = dist;
        precise vec3 tl = vec3(d.x / dist, d.y / dist, d.z / dist);
        to_light = tl;
        scale = min(scale / d2, RT_MAX_RADIANCE);
        if (light.range > 0.0) {
            // (Arguments of user functions are computed into precise locals first: `precise` does not reach
            // through a call, and the compiler may otherwise reassociate r * r * r * r.)
            precise float r = dist / light.range;
            precise float window = 1.0 - r * r * r * r;
            const float w = rt_clamp(window, 0.0, 1.0);
            scale *= w * w;
        }
        if (light.type == RT_LIGHT_SPOT) {
            const float cos_outer = light.cos_outer, cos_inner = light.cos_inner;
            const float cd = rt_dot(rt_normalize(light.direction), -to_light);
            precise float ramp = (cd - cos_outer) / max(cos_inner - cos_outer, 1e-4);
            const float t = rt_clamp(ramp, 0.0, 1.0);
            scale *= t * t;
        }
    }
    const float cos_theta = rt_dot(n, to_light);
    if (!(cos_theta > 0.0) || !(scale > 0.0)) return vec3(0.0);
    precise vec3 r = light.color * (scale * cos_theta);
    return r;
}

// Direct lighting of one light (not shadowed): Lambert plus the normalised Blinn-Phong highlight.
vec3 shade_light(SurfaceCoefficients s, vec3 incidence, vec3 n, vec3 to_light, vec3 to_eye) {
    precise vec3 brdf = s.diffuse / RT_PI;
    if (s.smoothness > 0.0) {
        precise vec3 half_vector = to_light + to_eye;
        const vec3 h = rt_normalize(half_vector);
        const float cos_h = rt_dot(n, h);
        const float nh = cos_h > 0.0 ? cos_h : 0.0;   // also 0 for NaN (eye exactly opposite the light: h = 0)
        brdf += s.specular * ((s.shininess + 8.0) / (8.0 * RT_PI)) * pow(nh, s.shininess);
    }
    precise vec3 r = brdf * incidence;
    return r;
}

// Weights of the reflected and refracted rays (Whitted::coefficients in whitted.h): metals reflect their base
// colour (Schlick with F0 = base); the dielectric part reflects F and, where it transmits, refracts (1 - F).
struct ReflectRefract {
    vec3 reflection;
    vec3 refraction;
};

float rt_f0_of(float ior) {
    precise float r = (ior - 1.0) / (ior + 1.0);
    precise float r2 = r * r;
    return r2;
}

ReflectRefract reflect_refract_coefficients(SurfaceCoefficients s, bool front_face, float cos_i, float f) {
    ReflectRefract k;
    precise float m = 1.0 - cos_i;
    precise vec3 f_metal = s.base + (vec3(1.0) - s.base) * (m * m * m * m * m);
    precise vec3 metal = (1.0 - s.dielectric) * s.smoothness * f_metal;
    const float r0 = rt_f0_of(s.ior);
    precise vec3 scaled = s.f0_dielectric / r0;
    const vec3 spec_scale = r0 > 0.0 ? scaled : vec3(0.0);
    precise vec3 fs = f * spec_scale;
    const vec3 fd = min(vec3(1.0), fs);
    precise vec3 reflection = metal + s.dielectric * s.smoothness * fd;
    precise vec3 refraction = s.dielectric * s.transmission * (vec3(1.0) - fd) * (front_face ? s.base : vec3(1.0));
    k.reflection = reflection;
    k.refraction = refraction;
    return k;
}
