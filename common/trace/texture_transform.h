// KHR_texture_transform (docs/shading.md, "Texture transform"): uv' = offset + R S uv, glTF's matrix product
// T * R * S with R = [cos sin; -sin cos] and S = diag(scale). The GLSL twin is rt_transform_uv in
// common/shaders/trace/normal_map.glsl, reading the matrix this file computes (GpuMaterial).
#pragma once

#include <cmath>

#include "common/scene/scene.h"

namespace rt {

// The 2x2 part R S as (a, b, c, d): u' = a u + b v + offset.x, v' = c u + d v + offset.y. Computed once on the CPU
// (std::cos, std::sin) for both implementations, so the GPU needs no trigonometry.
inline glm::vec4 uv_matrix(const TextureTransform& t) {
    const float c = std::cos(t.rotation), s = std::sin(t.rotation);
    return {c * t.scale.x, s * t.scale.y, -s * t.scale.x, c * t.scale.y};
}

// The identity transform gives uv back exactly (1 u + 0 v + 0 = u for finite uv).
inline glm::vec2 transform_uv(const glm::vec4& m, const glm::vec2& offset, const glm::vec2& uv) {
    return {m.x * uv.x + m.y * uv.y + offset.x, m.z * uv.x + m.w * uv.y + offset.y};
}

inline glm::vec2 transform_uv(const TextureTransform& t, const glm::vec2& uv) {
    return transform_uv(uv_matrix(t), t.offset, uv);
}

}  // namespace rt
