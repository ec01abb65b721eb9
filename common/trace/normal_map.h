// Normal maps (docs/shading.md, "Normal maps"): a tangent-space normal texture bends the shading normal, never the
// geometric normal (ray offsets and the below-the-surface test keep using that). The GLSL twin is
// common/shaders/trace/normal_map.glsl; the tangents come from the file or from common/scene/tangents.h.
#pragma once

#include <cstddef>

#include "common/scene/scene.h"

namespace rt {

// A texel of a normal texture (linear, each channel byte / 255) to a tangent-space direction, not normalised:
// (2 texel - 1) * (scale, scale, 1), glTF 2.0's normalTexture.scale.
glm::vec3 decode_normal_texel(const glm::vec3& texel, float scale);

// The mapped normal in world space from the interpolated vertex normal n (unit, the mesh's own orientation), the
// interpolated tangent (xyz, w = handedness) and the decoded texel m: with t the tangent made orthogonal to n
// (Gram-Schmidt) and b = sign(w) cross(n, t), normalize(m.x t + m.y b + m.z n). Returns false (and leaves `out`)
// when the frame or the result degenerates (a tangent parallel to n, a zero texel direction, non-finite values).
bool tangent_to_world(const glm::vec3& n, const glm::vec4& tangent, const glm::vec3& m, glm::vec3& out);

// The shading normal of a hit on triangle `triangle` at barycentrics (w, u, v) with texture coordinates uv, for a
// material with a normal map: the mapped normal turned to the side of the geometric normal (which faces the ray),
// as surface_point turns interpolated normals; `shading_normal` unchanged when the map cannot be applied.
glm::vec3 normal_mapped(const Scene& scene, std::size_t triangle, float w, float u, float v, const glm::vec2& uv,
                        const glm::vec3& geometric_normal, const glm::vec3& shading_normal, const Material& m);

}  // namespace rt
