#include "shading.h"

#include "texture_transform.h"

#include <algorithm>
#include <array>

namespace rt {

namespace {

// sRGB -> linear for all 256 byte values, computed once.
const std::array<float, 256>& srgb_table() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[std::size_t(i)] = srgb_to_linear(float(i) / 255.0f);
        return t;
    }();
    return table;
}

// A texture coordinate folded into [0, 1] by its wrap mode (glTF 2.0, 3.8.4.3): REPEAT keeps its fractional part
// (first, so huge coordinates do not lose the texel position to float rounding), CLAMP_TO_EDGE clamps it,
// MIRRORED_REPEAT reflects every other period (c - 2 floor(c / 2) is exact in float, so is 2 - m).
float fold(float c, Wrap wrap) {
    if (wrap == Wrap::ClampToEdge) return std::clamp(c, 0.0f, 1.0f);
    if (wrap == Wrap::MirroredRepeat) {
        const float m = c - 2.0f * std::floor(0.5f * c);
        return m <= 1.0f ? m : 2.0f - m;
    }
    return c - std::floor(c);
}

// A texel index on one axis of n texels: REPEAT wraps any integer, negative included; with the other modes the
// coordinate is folded into [0, 1], so an index is at most one texel past an edge (a bilinear neighbour, or the
// nearest texel at exactly 1), and that reads the edge texel (clamped, or mirrored about the edge).
int texel_index(int x, int n, Wrap wrap) {
    return wrap == Wrap::Repeat ? ((x % n) + n) % n : std::clamp(x, 0, n - 1);
}

glm::vec4 texture_texel(const Texture& tex, int x, int y, bool srgb) {
    x = texel_index(x, tex.width, tex.wrap_s);
    y = texel_index(y, tex.height, tex.wrap_t);
    const std::uint8_t* p = &tex.rgba8[(std::size_t(y) * std::size_t(tex.width) + std::size_t(x)) * 4];
    if (!srgb) return glm::vec4(float(p[0]), float(p[1]), float(p[2]), float(p[3])) / 255.0f;
    const auto& lut = srgb_table();
    return {lut[p[0]], lut[p[1]], lut[p[2]], float(p[3]) / 255.0f};
}

glm::vec4 sample(const Texture& tex, glm::vec2 uv, bool srgb) {
    if (tex.width <= 0 || tex.height <= 0 || !std::isfinite(uv.x) || !std::isfinite(uv.y)) return glm::vec4(1.0f);
    uv = glm::vec2(fold(uv.x, tex.wrap_s), fold(uv.y, tex.wrap_t));
    const float fx = uv.x * float(tex.width), fy = uv.y * float(tex.height);
    if (tex.nearest) return texture_texel(tex, int(fx), int(fy), srgb);
    // Bilinear between the four texel centres around (fx, fy).
    const float sx = fx - 0.5f, sy = fy - 0.5f;
    const float x0f = std::floor(sx), y0f = std::floor(sy);
    const float ax = sx - x0f, ay = sy - y0f;
    const int x0 = int(x0f), y0 = int(y0f);
    const glm::vec4 top = glm::mix(texture_texel(tex, x0, y0, srgb), texture_texel(tex, x0 + 1, y0, srgb), ax);
    const glm::vec4 bottom = glm::mix(texture_texel(tex, x0, y0 + 1, srgb), texture_texel(tex, x0 + 1, y0 + 1, srgb), ax);
    return glm::mix(top, bottom, ay);
}

}  // namespace

glm::vec4 sample_texture(const Texture& tex, glm::vec2 uv, bool srgb) { return sample(tex, uv, srgb); }
glm::vec4 sample_texture_linear(const Texture& tex, glm::vec2 uv) { return sample(tex, uv, false); }

SurfaceTexels sample_surface_textures(const Material& m, const std::vector<Texture>& textures, glm::vec2 uv) {
    SurfaceTexels t;
    const auto has = [&](int i) { return i >= 0 && std::size_t(i) < textures.size(); };
    if (has(m.base_color_texture))
        t.base = sample_texture(textures[std::size_t(m.base_color_texture)], transform_uv(m.base_color_transform, uv));
    if (has(m.metallic_roughness_texture)) {
        const glm::vec4 mr = sample_texture_linear(textures[std::size_t(m.metallic_roughness_texture)], uv);
        t.roughness = mr.g;
        t.metallic = mr.b;
    }
    if (has(m.emissive_texture)) t.emissive = glm::vec3(sample_texture(textures[std::size_t(m.emissive_texture)], uv));
    if (has(m.transmission_texture))
        t.transmission = sample_texture_linear(textures[std::size_t(m.transmission_texture)], uv).r;
    return t;
}

SurfaceCoefficients surface_coefficients(const Material& m, const SurfaceTexels& tex) {
    SurfaceCoefficients s;
    const float metallic = std::clamp(m.metallic * tex.metallic, 0.0f, 1.0f);
    const float roughness = std::clamp(m.roughness * tex.roughness, 0.0f, 1.0f);
    s.base = glm::vec3(m.base_color) * glm::vec3(tex.base);
    s.dielectric = 1.0f - metallic;
    s.transmission = std::clamp(m.transmission * tex.transmission, 0.0f, 1.0f);
    s.smoothness = (1.0f - roughness) * (1.0f - roughness);
    s.ior = m.ior > 0.0f ? m.ior : 1.5f;
    // Dielectric reflectance at normal incidence, scaled by KHR_materials_specular.
    const float r0 = (s.ior - 1.0f) / (s.ior + 1.0f);
    s.f0_dielectric = glm::min(glm::vec3(1.0f), r0 * r0 * m.specular * m.specular_color);
    // Lambertian: the dielectric's diffuse part, plus the part of a metal's reflectance too rough for a mirror ray
    // (1 - smoothness): Whitted traces no glossy lobe, so a rough metal reflects its colour diffusely instead of not at
    // all (docs/shading.md). For metallic 0 the second term is 0 and kd is the dielectric's part alone, to the bit.
    s.diffuse = s.base * s.dielectric * (1.0f - s.transmission) + s.base * (metallic * (1.0f - s.smoothness));
    s.mirror = s.base * metallic * s.smoothness;
    // Highlight: Blinn-Phong lobe whose exponent follows roughness (alpha = roughness^2, exponent 2/alpha^2 - 2);
    // only smooth surfaces get one, weighted by their reflectance at normal incidence.
    const float alpha = std::max(roughness * roughness, 0.1f);   // floor keeps mirror highlights a few pixels wide
    s.shininess = 2.0f / (alpha * alpha) - 2.0f;
    s.specular = s.smoothness * (metallic * s.base + s.dielectric * s.f0_dielectric);
    s.emissive = glm::min(m.emissive * tex.emissive, glm::vec3(kMaxRadiance));
    return s;
}

glm::vec3 light_incidence(const Light& light, const glm::vec3& p, const glm::vec3& n, glm::vec3& to_light,
                          float& distance) {
    float scale = std::min(light.intensity, kMaxRadiance);
    if (light.type == LightType::Directional) {
        to_light = -glm::normalize(light.direction);
        distance = std::numeric_limits<float>::infinity();
    } else {
        const glm::vec3 d = light.position - p;
        const float d2 = glm::dot(d, d);
        if (!(d2 > 0.0f)) return glm::vec3(0.0f);
        distance = std::sqrt(d2);
        to_light = d / distance;
        scale = std::min(scale / d2, kMaxRadiance);        // inverse-square law; d2 may be tiny
        if (light.range > 0.0f) {
            // glTF's recommended smooth window: clamp(1 - (d/range)^4, 0, 1)^2.
            const float r = distance / light.range;
            const float w = std::clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
            scale *= w * w;
        }
        if (light.type == LightType::Spot) {
            // KHR_lights_punctual: linear ramp in cosine between the outer and inner cone, squared.
            const float cos_outer = std::cos(light.outer_cone), cos_inner = std::cos(light.inner_cone);
            const float cd = glm::dot(glm::normalize(light.direction), -to_light);
            const float t = std::clamp((cd - cos_outer) / std::max(cos_inner - cos_outer, 1e-4f), 0.0f, 1.0f);
            scale *= t * t;
        }
    }
    const float cos_theta = glm::dot(n, to_light);
    if (!(cos_theta > 0.0f) || !(scale > 0.0f)) return glm::vec3(0.0f);
    return light.color * (scale * cos_theta);
}

glm::vec3 shade_light(const SurfaceCoefficients& s, const glm::vec3& incidence, const glm::vec3& n,
                      const glm::vec3& to_light, const glm::vec3& to_eye) {
    glm::vec3 brdf = s.diffuse / kPi;
    if (s.smoothness > 0.0f) {
        const glm::vec3 h = glm::normalize(to_light + to_eye);
        const float cos_h = glm::dot(n, h);
        const float nh = cos_h > 0.0f ? cos_h : 0.0f;   // also 0 for NaN (eye exactly opposite the light: h = 0)
        // Normalised Blinn-Phong: (e + 8) / (8 pi) keeps the lobe's energy roughly constant as it sharpens.
        brdf += s.specular * ((s.shininess + 8.0f) / (8.0f * kPi)) * std::pow(nh, s.shininess);
    }
    return brdf * incidence;
}

}  // namespace rt
