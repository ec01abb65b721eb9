#include "normal_map.h"

#include <cmath>

#include "shading.h"
#include "texture_transform.h"

namespace rt {

glm::vec3 decode_normal_texel(const glm::vec3& texel, float scale) {
    return (2.0f * texel - 1.0f) * glm::vec3(scale, scale, 1.0f);
}

bool tangent_to_world(const glm::vec3& n, const glm::vec4& tangent, const glm::vec3& m, glm::vec3& out) {
    const glm::vec3 t0(tangent);
    const glm::vec3 t1 = t0 - n * glm::dot(n, t0);
    const float t_len = glm::length(t1);
    if (!(t_len > 0.0f) || !std::isfinite(t_len)) return false;
    const glm::vec3 t = t1 / t_len;
    const glm::vec3 b = (tangent.w < 0.0f ? -1.0f : 1.0f) * glm::cross(n, t);
    const glm::vec3 p = m.x * t + m.y * b + m.z * n;
    const float p_len = glm::length(p);
    if (!(p_len > 0.0f) || !std::isfinite(p_len)) return false;
    out = p / p_len;
    return true;
}

glm::vec3 normal_mapped(const Scene& scene, std::size_t triangle, float w, float u, float v, const glm::vec2& uv,
                        const glm::vec3& geometric_normal, const glm::vec3& shading_normal, const Material& m) {
    const std::size_t i = triangle * 3;
    if (m.normal_texture < 0 || std::size_t(m.normal_texture) >= scene.textures.size() ||
        scene.tangents.size() < i + 3)
        return shading_normal;
    // The vertex normal in the mesh's own orientation (before surface_point turned it towards the ray): the
    // tangent frame is right-handed about it.
    const glm::vec3 ns = w * scene.normals[i] + u * scene.normals[i + 1] + v * scene.normals[i + 2];
    const float ns_len = glm::length(ns);
    if (!(ns_len > 0.0f) || !std::isfinite(ns_len)) return shading_normal;
    const glm::vec3 n = ns / ns_len;
    const glm::vec4 tangent = w * scene.tangents[i] + u * scene.tangents[i + 1] + v * scene.tangents[i + 2];
    const glm::vec4 texel = sample_texture(scene.textures[std::size_t(m.normal_texture)],
                                           transform_uv(m.normal_transform, uv), /*srgb=*/false);
    glm::vec3 mapped;
    if (!tangent_to_world(n, tangent, decode_normal_texel(glm::vec3(texel), m.normal_scale), mapped))
        return shading_normal;
    return glm::dot(mapped, geometric_normal) < 0.0f ? -mapped : mapped;
}

}  // namespace rt
