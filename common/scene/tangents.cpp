#include "tangents.h"

#include <cmath>

namespace rt {

namespace {

bool usable(const glm::vec3& v) {
    const float len = glm::length(v);
    return len > 0.0f && std::isfinite(len);
}

// Any unit vector orthogonal to unit n (n itself may be zero: then +X).
glm::vec3 any_orthogonal(const glm::vec3& n) {
    if (!usable(n)) return {1.0f, 0.0f, 0.0f};
    const glm::vec3 helper = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(helper - n * glm::dot(n, helper));
}

}  // namespace

std::vector<glm::vec4> generate_tangents(const Primitive& prim) {
    const std::size_t nv = prim.positions.size();
    const bool has_uvs = prim.uvs.size() == nv, has_normals = prim.normals.size() == nv;
    const std::size_t ni = prim.indices.empty() ? nv : prim.indices.size();
    std::vector<glm::vec3> along_u(nv, glm::vec3(0.0f)), up_v(nv, glm::vec3(0.0f)), faces(nv, glm::vec3(0.0f));
    for (std::size_t t = 0; t + 2 < ni; t += 3) {
        std::uint32_t idx[3];
        bool valid = true;
        for (int k = 0; k < 3; ++k) {
            idx[k] = prim.indices.empty() ? std::uint32_t(t + std::size_t(k)) : prim.indices[t + std::size_t(k)];
            valid = valid && idx[k] < nv;
        }
        if (!valid) continue;
        const glm::vec3 e1 = prim.positions[idx[1]] - prim.positions[idx[0]];
        const glm::vec3 e2 = prim.positions[idx[2]] - prim.positions[idx[0]];
        const glm::vec3 face = glm::cross(e1, e2);
        for (std::uint32_t i : idx) faces[i] += face;
        if (!has_uvs) continue;
        const glm::vec2 d1 = prim.uvs[idx[1]] - prim.uvs[idx[0]], d2 = prim.uvs[idx[2]] - prim.uvs[idx[0]];
        // P - P0 = dP/du (u - u0) + dP/dv (v - v0) on the triangle; solving for the two edges gives
        // dP/du = (e1 d2.v - e2 d1.v) / r and dP/dv = (e2 d1.u - e1 d2.u) / r with r = d1.u d2.v - d2.u d1.v.
        // Multiplying by |r| instead of dividing by r weights each triangle by its uv area and skips r = 0.
        const float r = d1.x * d2.y - d2.x * d1.y;
        if (!(r != 0.0f) || !std::isfinite(r)) continue;
        const float sign = r > 0.0f ? 1.0f : -1.0f;
        const glm::vec3 du = sign * (e1 * d2.y - e2 * d1.y), dv = sign * (e2 * d1.x - e1 * d2.x);
        if (!usable(du) || !usable(dv)) continue;
        for (std::uint32_t i : idx) {
            along_u[i] += du;
            up_v[i] -= dv;
        }
    }
    std::vector<glm::vec4> out(nv);
    for (std::size_t i = 0; i < nv; ++i) {
        glm::vec3 n = has_normals ? prim.normals[i] : faces[i];
        n = usable(n) ? glm::normalize(n) : glm::vec3(0.0f);
        const glm::vec3 t = along_u[i] - n * glm::dot(n, along_u[i]);
        if (!usable(t) || !usable(n)) {
            out[i] = glm::vec4(any_orthogonal(n), 1.0f);
            continue;
        }
        const glm::vec3 tu = glm::normalize(t);
        out[i] = glm::vec4(tu, glm::dot(glm::cross(n, tu), up_v[i]) < 0.0f ? -1.0f : 1.0f);
    }
    return out;
}

std::vector<glm::vec4> primitive_tangents(const Primitive& prim) {
    if (!prim.tangents.empty() && prim.tangents.size() == prim.positions.size()) return prim.tangents;
    return generate_tangents(prim);
}

}  // namespace rt
