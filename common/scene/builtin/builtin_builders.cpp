// The small builders every built-in scene file uses (builtin_builders.h), and the sphere and box that the tests use
// too (builtin_scenes.h).
#include "builtin_builders.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "builtin_scenes.h"

namespace rt {

namespace {
constexpr float kPi = 3.14159265358979f;
}  // namespace

Material diffuse(const std::string& name, glm::vec3 color) {
    Material m;
    m.name = name;
    m.base_color = glm::vec4(color, 1.0f);
    m.metallic = 0.0f;
    m.roughness = 1.0f;
    return m;
}

Material mirror(const std::string& name, glm::vec3 color) {
    Material m;
    m.name = name;
    m.base_color = glm::vec4(color, 1.0f);
    m.metallic = 1.0f;
    m.roughness = 0.0f;
    return m;
}

Material glass(const std::string& name) {
    Material m;
    m.name = name;
    m.base_color = glm::vec4(1.0f);
    m.metallic = 0.0f;
    m.roughness = 0.0f;
    m.transmission = 1.0f;
    m.ior = 1.5f;
    return m;
}

Material emitter(const std::string& name, glm::vec3 radiance) {
    Material m = diffuse(name, glm::vec3(0.9f));
    m.emissive = radiance;
    return m;
}

int add_mesh(SceneAsset& a, const std::string& name, Primitive p) {
    Mesh m;
    m.name = name;
    m.primitives.push_back(std::move(p));
    a.meshes.push_back(std::move(m));
    return int(a.meshes.size() - 1);
}

int add_node(SceneAsset& a, Node n, bool root) {
    a.nodes.push_back(std::move(n));
    const int index = int(a.nodes.size() - 1);
    if (root) a.roots.push_back(index);
    return index;
}

glm::quat look_rotation(const glm::vec3& eye, const glm::vec3& target) {
    const glm::vec3 forward = glm::normalize(target - eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, forward);
    return glm::normalize(glm::quat_cast(glm::mat3(right, up, -forward)));
}

void add_camera(SceneAsset& a, const glm::vec3& eye, const glm::vec3& target, float yfov_degrees) {
    Camera c;
    c.name = "camera";
    c.yfov = glm::radians(yfov_degrees);
    c.znear = 0.01f;
    a.cameras.push_back(c);
    Node n;
    n.name = "camera";
    n.camera = int(a.cameras.size() - 1);
    n.translation = eye;
    n.rotation = look_rotation(eye, target);
    add_node(a, n);
}

void add_point_light(SceneAsset& a, const glm::vec3& position, float intensity) {
    Light l;
    l.name = "light";
    l.type = LightType::Point;
    l.intensity = intensity;
    a.lights.push_back(l);
    Node n;
    n.name = "light";
    n.light = int(a.lights.size() - 1);
    n.translation = position;
    add_node(a, n);
}

int add_material(SceneAsset& a, const Material& m) {
    a.materials.push_back(m);
    return int(a.materials.size() - 1);
}

int add_mesh_node(SceneAsset& a, const std::string& name, Primitive p) {
    Node n;
    n.name = name;
    n.mesh = add_mesh(a, name, std::move(p));
    return add_node(a, n);
}

// A quad centred at c spanning c +- u +- v, facing cross(u, v), indexed; uv from (0,0) to (uv_scale, uv_scale).
Primitive make_quad(const glm::vec3& c, const glm::vec3& u, const glm::vec3& v, float uv_scale, int material) {
    Primitive p;
    p.material = material;
    const glm::vec3 n = glm::normalize(glm::cross(u, v));
    p.positions = {c - u - v, c + u - v, c + u + v, c - u + v};
    p.normals = {n, n, n, n};
    p.uvs = {{0, uv_scale}, {uv_scale, uv_scale}, {uv_scale, 0}, {0, 0}};
    p.indices = {0, 1, 2, 0, 2, 3};
    return p;
}

// A UV sphere: (segments + 1) columns x (rings + 1) rows of vertices, theta from the north pole (row 0) to the south
// pole, phi around +Y. The seam column repeats column 0 and every pole vertex repeats the exact pole position, so
// triangles meeting there share identical positions (the mesh is closed). At the poles only one triangle per segment
// is emitted (no degenerate ones).
Primitive make_uv_sphere(const glm::vec3& center, float radius, int segments, int rings, int material) {
    segments = std::max(segments, 3);
    rings = std::max(rings, 2);
    Primitive p;
    p.material = material;
    const auto columns = std::uint32_t(segments + 1);
    for (int i = 0; i <= rings; ++i) {
        const float theta = kPi * float(i) / float(rings);
        for (int j = 0; j <= segments; ++j) {
            const float phi = 2.0f * kPi * float(j % segments) / float(segments);
            glm::vec3 dir(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
            if (i == 0) dir = glm::vec3(0, 1, 0);
            if (i == rings) dir = glm::vec3(0, -1, 0);
            p.positions.push_back(center + radius * dir);
            p.normals.push_back(dir);
            const float u = (i == 0 || i == rings) ? (float(j) + 0.5f) / float(segments) : float(j) / float(segments);
            p.uvs.push_back({u, float(i) / float(rings)});
        }
    }
    // Counter-clockwise seen from outside: a (row i, col j), c (row i+1, col j), d (i+1, j+1), b (i, j+1).
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const std::uint32_t a = std::uint32_t(i) * columns + std::uint32_t(j), b = a + 1;
            const std::uint32_t c = a + columns, d = c + 1;
            if (i != rings - 1) p.indices.insert(p.indices.end(), {a, c, d});   // degenerate at the south pole
            if (i != 0) p.indices.insert(p.indices.end(), {a, d, b});           // degenerate at the north pole
        }
    }
    return p;
}

Primitive make_box(const glm::vec3& lo, const glm::vec3& hi, int material) {
    Primitive p;
    p.material = material;
    const glm::vec3 c = 0.5f * (lo + hi), h = 0.5f * (hi - lo);
    // Each face: outward normal n and in-plane axes u, v with cross(u, v) = n, so the quad is counter-clockwise.
    const glm::vec3 faces[6][3] = {
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},
        {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}, {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
    };
    for (const auto& f : faces) {
        const glm::vec3 n = f[0], u = f[1] * h, v = f[2] * h, fc = c + n * h;
        const auto base = std::uint32_t(p.positions.size());
        p.positions.insert(p.positions.end(), {fc - u - v, fc + u - v, fc + u + v, fc - u + v});
        p.normals.insert(p.normals.end(), {n, n, n, n});
        p.uvs.insert(p.uvs.end(), {{0, 1}, {1, 1}, {1, 0}, {0, 0}});
        p.indices.insert(p.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    return p;
}

}  // namespace rt
