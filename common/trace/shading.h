// The shading model every stage implements (docs/shading.md is the contract; common/shaders/trace/shading.glsl is the
// GLSL twin, kept equal by common/gpu/glsl_twins/glsl_twins_test.cpp). Everything here is linear RGB.
#pragma once

#include <algorithm>
#include <cmath>

#include "common/scene/scene.h"
#include "ray.h"

namespace rt {

enum class FresnelMode : int { Schlick = 0, Exact = 1 };

// Constants of the contract (docs/shading.md).
constexpr float kAmbient = 0.03f;          // ambient light, as a fraction of the diffuse colour
constexpr float kDefaultCutoff = 1e-3f;    // a path stops when its weight falls below this in every channel
constexpr float kPi = 3.14159265358979f;
// kMaxRadiance (scene.h) bounds the irradiance light_incidence returns and the emission surface_coefficients returns.
// The radiance one sample of a pixel carries, summed over its ray tree, saturates at 2^63 (9.2e18) in every stage:
// the GPU stages add it in 96-bit fixed point whose top bit is sticky (wavefront.glsl, WF_RADIANCE_MAX) and 01 clamps
// each sample to the same value, so an absurdly bright scene gives the same image on the CPU and the GPU.
constexpr float kMaxSampleRadiance = 9.2233720e18f;   // 2^63
static_assert(kMaxSampleRadiance == 0x1p63f);

// The hemisphere ambient (AmbientModel::Hemisphere, docs/shading.md "Ambient"): kAmbient times a weight that runs
// from kAmbientGround for a normal facing straight down to kAmbientGround + kAmbientRise = 1.6 facing straight up,
// linear in n.y. Averaged over all directions the weight is 1, so the scene is as bright overall as with the constant
// term; the 4:1 ratio between sky and ground shows the shape of what lies in shadow.
constexpr float kAmbientGround = 0.4f;
constexpr float kAmbientRise = 1.2f;

// The ambient light a surface of diffuse colour `diffuse` with unit shading normal n reflects. Constant:
// kAmbient * diffuse (the built-in scenes' default); none: 0. GLSL twin: ambient_light in shading.glsl, compiled for
// the scene's model only.
inline glm::vec3 ambient_light(AmbientModel model, const glm::vec3& diffuse, const glm::vec3& n) {
    switch (model) {
    case AmbientModel::None: return glm::vec3(0.0f);
    case AmbientModel::Hemisphere: {
        const float up = 0.5f * (1.0f + n.y);                   // 1 facing straight up, 0 straight down
        const float weight = kAmbientGround + kAmbientRise * up;
        return (kAmbient * weight) * diffuse;
    }
    case AmbientModel::Constant: break;
    }
    return kAmbient * diffuse;
}

// Mirror reflection of d about n (n unit length).
template <class T> Vec3<T> reflect_dir(const Vec3<T>& d, const Vec3<T>& n) { return d - T(2) * glm::dot(d, n) * n; }

// Snell's law. d: unit incident direction; n: unit normal on the incident side (dot(d, n) < 0); eta = n_i / n_t.
// Returns false under total internal reflection.
template <class T>
bool refract_dir(const Vec3<T>& d, const Vec3<T>& n, T eta, Vec3<T>& out) {
    const T cos_i = -glm::dot(d, n);
    const T sin2_t = eta * eta * std::max(T(0), T(1) - cos_i * cos_i);
    if (sin2_t >= T(1)) return false;
    const T cos_t = std::sqrt(T(1) - sin2_t);
    out = glm::normalize(eta * d + (eta * cos_i - cos_t) * n);
    return true;
}

// Exact Fresnel reflectance of an unpolarised wave at a dielectric boundary (average of the s and p terms).
// cos_i: cosine of the incident angle (>= 0); eta = n_i / n_t. Returns 1 under total internal reflection.
template <class T>
T fresnel_exact(T cos_i, T eta) {
    cos_i = std::clamp(cos_i, T(0), T(1));
    const T sin2_t = eta * eta * (T(1) - cos_i * cos_i);
    if (sin2_t >= T(1)) return T(1);
    const T cos_t = std::sqrt(T(1) - sin2_t);
    const T rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const T rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return T(0.5) * (rs * rs + rp * rp);
}

// Schlick's approximation (1994). Uses the cosine on the denser side, so it also gives 1 under total internal
// reflection: when leaving the denser medium (eta > 1) the transmitted angle's cosine is used.
template <class T>
T fresnel_schlick(T cos_i, T eta) {
    cos_i = std::clamp(cos_i, T(0), T(1));
    T r0 = (eta - T(1)) / (eta + T(1));
    r0 *= r0;
    if (r0 == T(0)) return T(0);   // matched indices: no interface, nothing reflects (Schlick alone gives (1-c)^5)
    T c = cos_i;
    if (eta > T(1)) {
        const T sin2_t = eta * eta * (T(1) - cos_i * cos_i);
        if (sin2_t >= T(1)) return T(1);
        c = std::sqrt(T(1) - sin2_t);
    }
    const T m = T(1) - c;
    return r0 + (T(1) - r0) * (m * m) * (m * m) * m;
}

template <class T>
T fresnel(FresnelMode mode, T cos_i, T eta) {
    return mode == FresnelMode::Exact ? fresnel_exact(cos_i, eta) : fresnel_schlick(cos_i, eta);
}

// sRGB transfer functions (IEC 61966-2-1).
inline float srgb_to_linear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
inline float linear_to_srgb(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

// Texture lookup with the texture's wrap modes (REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT); nearest or bilinear per the
// texture. Returns linear RGBA: colour channels
// sRGB-decoded, or (srgb = false, normal maps) like alpha, byte / 255.
glm::vec4 sample_texture(const Texture& tex, glm::vec2 uv, bool srgb = true);

// The same lookup for textures that hold data, not colour (metallicRoughnessTexture): bytes / 255, no sRGB decode.
glm::vec4 sample_texture_linear(const Texture& tex, glm::vec2 uv);

// What a material's textures say at one point, each scaling its factor (docs/shading.md): the base colour (RGBA),
// roughness (metallicRoughnessTexture's green), metallic (its blue), emission (emissiveTexture) and transmission
// (transmissionTexture's red). A texture the
// material does not have reads 1, which leaves the factor exactly as it is.
struct SurfaceTexels {
    glm::vec4 base{1.0f};
    float roughness = 1.0f;
    float metallic = 1.0f;
    glm::vec3 emissive{1.0f};
    float transmission = 1.0f;   // transmissionTexture's red
};
SurfaceTexels sample_surface_textures(const Material& m, const std::vector<Texture>& textures, glm::vec2 uv);

// Whitted coefficients of a surface point (docs/shading.md, "From glTF materials to Whitted coefficients").
struct SurfaceCoefficients {
    glm::vec3 diffuse{0};      // kd: Lambertian albedo
    glm::vec3 specular{0};     // ks: weight of the Blinn-Phong highlight
    float shininess = 0;       // Blinn-Phong exponent
    glm::vec3 mirror{0};       // kr before Fresnel: metallic part (already coloured) ...
    float smoothness = 0;      // s = (1 - roughness)^2: how mirror-like
    float dielectric = 0;      // (1 - metallic)
    float transmission = 0;    // fraction of the dielectric part that transmits
    glm::vec3 base{1};         // base colour (texture applied)
    glm::vec3 f0_dielectric{0.04f};
    glm::vec3 emissive{0};
    float ior = 1.5f;
};

SurfaceCoefficients surface_coefficients(const Material& m, const SurfaceTexels& texels);
// With the base colour texel only (materials without metallic-roughness or emissive textures).
inline SurfaceCoefficients surface_coefficients(const Material& m, const glm::vec4& base_texel) {
    SurfaceTexels t;
    t.base = base_texel;
    return surface_coefficients(m, t);
}

// Irradiance-like factor of one light at point p with unit normal n: returns the light's radiance scale times the
// cosine term and gives the unit direction to the light and the distance (infinite for directional lights).
// Zero when p is outside a spot cone, beyond range, or behind the surface.
glm::vec3 light_incidence(const Light& light, const glm::vec3& p, const glm::vec3& n, glm::vec3& to_light,
                          float& distance);

// Direct lighting of one light (not shadowed): Lambert plus Blinn-Phong highlight.
glm::vec3 shade_light(const SurfaceCoefficients& s, const glm::vec3& incidence, const glm::vec3& n,
                      const glm::vec3& to_light, const glm::vec3& to_eye);

// Primary ray through image position (x, y) in pixels (pixel centres at +0.5), y down.
template <class T>
Ray<T> camera_ray(const Camera& cam, int width, int height, T x, T y) {
    const T aspect = cam.aspect > 0 ? T(cam.aspect) : T(width) / T(height);
    const T ndc_x = T(2) * x / T(width) - T(1);
    const T ndc_y = T(1) - T(2) * y / T(height);
    const Vec3<T> right(cam.right), up(cam.up), forward(cam.forward), eye(cam.position);
    Ray<T> ray;
    if (cam.projection == Projection::Orthographic) {
        ray.origin = eye + right * (ndc_x * T(cam.xmag)) + up * (ndc_y * T(cam.ymag));
        ray.direction = forward;
    } else {
        const T h = std::tan(T(cam.yfov) * T(0.5));
        ray.origin = eye;
        ray.direction = glm::normalize(right * (ndc_x * h * aspect) + up * (ndc_y * h) + forward);
    }
    return ray;
}

}  // namespace rt
