// Test support for the hard-case suites: the meshes and rays that the CPU suites (through stage 01's brute-force
// tracer: 01_naive/intersect_watertight_test.cpp, offset_test.cpp, shading_hard_cases_test.cpp,
// whitted_hard_cases_test.cpp; the ray/triangle tests alone: common/trace/intersect_inputs_test.cpp) and their GLSL
// twin (common/gpu/glsl_twins/hard_cases_glsl_test.cpp) share, so both run the same cases:
//   closed meshes       closed_sphere(), closed_cube() and their topology (shared vertices and edges by position)
//   watertight rays     rays_at_shared_vertices_and_edges(): aimed exactly at the shared vertices and edges
//   placement           sphere_at() / thin_slab_at(): a scene at coordinates OFFSET and of size SCALE, and where
//                       float can represent it (sphere_representable, robust_offset_bound)
//   broken inputs       broken_triangles(), broken_rays(): zero-area triangles, NaN/Inf vertices, NaN/zero rays
//   ties                with_coincident_copies(): every triangle twice, so every hit is a tie at equal t
// Header-only, for tests.
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/scene.h"
#include "intersect.h"
#include "offset.h"
#include "ray.h"

namespace rt::hard_cases {

// ---------------------------------------------------------------------------------------------------------------
// Names and values the suites print and loop over.

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr IntersectMethod kMethods[] = {IntersectMethod::Moller, IntersectMethod::Watertight};
constexpr OffsetMethod kOffsets[] = {OffsetMethod::Epsilon, OffsetMethod::Robust};

inline const char* name_of(IntersectMethod m) { return m == IntersectMethod::Moller ? "moller" : "watertight"; }
inline const char* name_of(OffsetMethod m) { return m == OffsetMethod::Epsilon ? "epsilon" : "robust"; }
template <class T> const char* precision_name() { return sizeof(T) == sizeof(float) ? "float" : "double"; }

// ---------------------------------------------------------------------------------------------------------------
// Scenes and sampling.

// One triangle in the z = 0 plane facing +z, lit from +z, with the given vertex normals.
inline Scene lit_triangle(const glm::vec3& vertex_normal) {
    Scene s;
    s.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    s.normals = {vertex_normal, vertex_normal, vertex_normal};
    s.uvs = {{0, 0}, {1, 0}, {0, 1}};
    s.material_ids = {0};
    Material white;
    white.metallic = 0.0f;
    s.materials = {white};
    Light light;
    light.position = {0, 0, 2};
    light.intensity = 8.0f;
    s.lights = {light};
    return s;
}

// An asset holding `primitives`, each under its own root node placed by `translation` and `rotation`, with one
// white diffuse material (the primitives' material index 0).
inline SceneAsset asset_of(std::vector<Primitive> primitives, const glm::vec3& translation = glm::vec3(0.0f),
                           const glm::quat& rotation = glm::quat(1.0f, 0.0f, 0.0f, 0.0f)) {
    SceneAsset asset;
    asset.name = "hard case";
    Material white;
    white.metallic = 0.0f;
    asset.materials.push_back(white);
    for (Primitive& p : primitives) {
        p.material = 0;
        Mesh mesh;
        mesh.primitives.push_back(std::move(p));
        asset.meshes.push_back(std::move(mesh));
        Node node;
        node.mesh = int(asset.meshes.size() - 1);
        node.translation = translation;
        node.rotation = rotation;
        asset.nodes.push_back(node);
        asset.roots.push_back(int(asset.nodes.size() - 1));
    }
    return asset;
}

inline Scene flatten_without_light(const SceneAsset& asset) {
    FlattenOptions options;
    options.add_default_light = false;
    return flatten(asset, options);
}

template <class T> Vec3<T> corner(const Scene& s, std::size_t triangle, int k) {
    return Vec3<T>(s.positions[3 * triangle + std::size_t(k)]);
}

// Unit normal by the winding (outward for the closed meshes of builtin_scenes.h, which wind counter-clockwise).
template <class T> Vec3<T> winding_normal(const Scene& s, std::size_t triangle) {
    const Vec3<T> a = corner<T>(s, triangle, 0), b = corner<T>(s, triangle, 1), c = corner<T>(s, triangle, 2);
    return glm::normalize(glm::cross(b - a, c - a));
}

template <class T> Vec3<T> random_unit(std::mt19937& rng) {
    std::normal_distribution<double> gauss;
    for (;;) {
        const glm::dvec3 v(gauss(rng), gauss(rng), gauss(rng));
        const double len = glm::length(v);
        if (len > 1e-6) return Vec3<T>(v / len);
    }
}

// A random unit direction on the outer side of every plane in `normals` (dot > min_cos with each): a ray coming
// from there towards a point where these faces meet enters a convex solid there instead of grazing it.
template <class T> Vec3<T> direction_outside(const std::vector<Vec3<T>>& normals, T min_cos, std::mt19937& rng) {
    Vec3<T> mean(0);
    for (const Vec3<T>& n : normals) mean += n;
    mean = glm::normalize(mean);
    for (int tries = 0; tries < 10000; ++tries) {
        const Vec3<T> d = glm::normalize(mean + T(0.9) * random_unit<T>(rng));
        bool outside = true;
        for (const Vec3<T>& n : normals) outside = outside && glm::dot(d, n) > min_cos;
        if (outside) return d;
    }
    return mean;
}

// A ray from `distance` away along `from` aimed exactly at `target`, as exactly as T allows: the direction is
// computed in double from the origin as rounded to T.
template <class T> Ray<T> ray_aimed_at(const Vec3<T>& target, const Vec3<T>& from, T distance) {
    Ray<T> ray;
    ray.origin = Vec3<T>(glm::dvec3(target) + glm::dvec3(from) * double(distance));
    ray.direction = Vec3<T>(glm::normalize(glm::dvec3(target) - glm::dvec3(ray.origin)));
    return ray;
}

// Random barycentrics kept a little away from the edges: (w, u, v) with each >= 0.05.
inline glm::dvec3 interior_barycentrics(std::mt19937& rng) {
    std::exponential_distribution<double> e;
    glm::dvec3 b(e(rng), e(rng), e(rng));
    b /= b.x + b.y + b.z;
    return 0.85 * b + glm::dvec3(0.05);
}

// ---------------------------------------------------------------------------------------------------------------
// Closed meshes and the rays aimed at their shared vertices and edges.

using PositionKey = std::array<float, 3>;
inline PositionKey key_of(const glm::vec3& p) { return {p.x, p.y, p.z}; }

// The vertices and edges of a triangle soup, matched by exact position, with the triangles around each.
struct MeshTopology {
    std::map<PositionKey, std::vector<std::size_t>> vertices;
    std::map<std::pair<PositionKey, PositionKey>, std::vector<std::size_t>> edges;   // (smaller, larger) key
    bool closed() const {
        for (const auto& [edge, triangles] : edges)
            if (triangles.size() != 2) return false;
        return !edges.empty();
    }
};

inline MeshTopology topology_of(const Scene& s) {
    MeshTopology topo;
    for (std::size_t t = 0; t < s.triangle_count(); ++t)
        for (int k = 0; k < 3; ++k) {
            const PositionKey a = key_of(s.positions[3 * t + std::size_t(k)]);
            const PositionKey b = key_of(s.positions[3 * t + std::size_t((k + 1) % 3)]);
            topo.vertices[a].push_back(t);
            topo.edges[a < b ? std::make_pair(a, b) : std::make_pair(b, a)].push_back(t);
        }
    return topo;
}

// Rays from outside a closed convex mesh aimed exactly at each shared vertex (directions_per_vertex of them) and at
// points on each shared edge: its midpoint and random fractions along it (each from directions_per_point
// directions). Each comes from the outer side of every face around its target, so in exact arithmetic it enters the
// solid there: a closed, watertight test cannot miss it. The origins lie from 1 to 10^4 mesh sizes away (log-uniform):
// the rounding error of Moller-Trumbore's edge tests grows with the distance from the origin to the triangle (Embree's
// verify test puts its plane at 1e5 for the same reason).
template <class T>
std::vector<Ray<T>> rays_at_shared_vertices_and_edges(const Scene& s, int directions_per_vertex, int points_per_edge,
                                                      int directions_per_point, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> fraction(0.0, 1.0), log_distance(0.0, 4.0);
    const T size = T(s.bounds.diagonal());
    auto distance = [&](std::mt19937& r) { return std::pow(10.0, log_distance(r)); };
    const MeshTopology topo = topology_of(s);
    auto normals_of = [&](const std::vector<std::size_t>& triangles) {
        std::vector<Vec3<T>> normals;
        for (std::size_t t : triangles) normals.push_back(winding_normal<T>(s, t));
        return normals;
    };
    std::vector<Ray<T>> rays;
    for (const auto& [position, triangles] : topo.vertices) {
        const Vec3<T> target{T(position[0]), T(position[1]), T(position[2])};
        const std::vector<Vec3<T>> normals = normals_of(triangles);
        for (int i = 0; i < directions_per_vertex; ++i)
            rays.push_back(ray_aimed_at(target, direction_outside(normals, T(0.05), rng), size * T(distance(rng))));
    }
    for (const auto& [edge, triangles] : topo.edges) {
        const Vec3<T> a{T(edge.first[0]), T(edge.first[1]), T(edge.first[2])};
        const Vec3<T> b{T(edge.second[0]), T(edge.second[1]), T(edge.second[2])};
        const std::vector<Vec3<T>> normals = normals_of(triangles);
        for (int i = 0; i < points_per_edge; ++i) {
            const T f = i == 0 ? T(0.5) : T(fraction(rng));
            const Vec3<T> target = a + f * (b - a);
            for (int j = 0; j < directions_per_point; ++j)
                rays.push_back(ray_aimed_at(target, direction_outside(normals, T(0.05), rng), size * T(distance(rng))));
        }
    }
    return rays;
}

// The sphere of the Whitted scene's tessellation (48 x 24, shared seam column and pole vertices), turned and moved
// off the axes so that no coordinate is special.
inline Scene closed_sphere() {
    return flatten_without_light(asset_of({make_uv_sphere({0, 0, 0}, 1.0f, 48, 24, 0)}, {0.37f, 1.1f, -0.6f},
                                          glm::angleAxis(0.6f, glm::normalize(glm::vec3(1, 2, 3)))));
}

inline Scene closed_cube() {
    const glm::quat turn = glm::angleAxis(0.9f, glm::normalize(glm::vec3(-2, 1, 3)));
    return flatten_without_light(
        asset_of({make_box({-0.37f, 0.11f, -1.3f}, {0.52f, 0.93f, -0.21f}, 0)}, {0.2f, -0.3f, 0.45f}, turn));
}

// Ray counts of the watertight cases (directions per vertex, points per edge, directions per point).
struct WatertightRayCounts {
    int directions_per_vertex, points_per_edge, directions_per_point;
};
constexpr WatertightRayCounts kSphereRays{4, 3, 2};
constexpr WatertightRayCounts kCubeRays{400, 200, 8};
constexpr unsigned kWatertightSeed = 7;

// ---------------------------------------------------------------------------------------------------------------
// Placement at an offset and a scale.

constexpr double kPlacementOffsets[] = {1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6};        // sphere centres (OFFSET x 3)
constexpr double kPlacementScales[] = {1e-3, 1e-2, 1e-1, 1.0, 1e1, 1e2, 1e3};   // sphere radii, slab widths
constexpr double kWallOffsets[] = {0.0, 1.0, 1e2, 1e4};                         // thin-wall slab centres

// One float unit in the last place at magnitude x.
inline double ulp_at(double x) {
    const float f = float(std::abs(x));
    return double(std::nextafter(f, std::numeric_limits<float>::infinity()) - f);
}

// The most the robust offset moves a coordinate of magnitude x (offset.h): int_scale ulps, or float_scale near the
// origin.
inline double robust_offset_bound(double x) {
    return std::abs(x) < double(RobustOffsetConstants<float>::origin)
               ? double(RobustOffsetConstants<float>::float_scale)
               : double(RobustOffsetConstants<float>::int_scale) * ulp_at(x);
}

// A scene at `offset` of size `scale` is only meaningful in float when the geometry spans many float steps: the
// sphere's radius must hold at least 1024 ulps of its coordinates (then the robust offset, a few ulps, stays
// far below the radius). Smaller scenes far out cannot even be modelled in float.
inline bool sphere_representable(double offset, double scale) { return scale >= 1024.0 * ulp_at(offset + scale); }

// The glass-like sphere of the self-intersection cases: radius `scale`, centred at (offset, offset, offset), 24 x 12.
inline Scene sphere_at(double offset, double scale) {
    return flatten_without_light(asset_of({make_uv_sphere(glm::vec3(float(offset)), float(scale), 24, 12, 0)}));
}

// The seed of the (offset, scale) cell of the self-intersection table.
inline unsigned sphere_seed(double offset, double scale) {
    return unsigned(std::hash<double>()(offset * 31.0 + scale));
}

// A thin slab, a closed box `scale` wide and 0.05 * scale thick (along y), centred at (offset, offset, offset).
inline Scene thin_slab_at(double offset, double scale) {
    const float half = float(scale / 2), half_thickness = float(0.025 * scale);
    const glm::vec3 c{float(offset)};
    return flatten_without_light(
        asset_of({make_box(c - glm::vec3(half, half_thickness, half), c + glm::vec3(half, half_thickness, half), 0)}));
}

// A wall thinner than the robust offset cannot be left correctly by any float offset.
inline bool wall_representable(double offset, double scale) {
    return 0.05 * scale > robust_offset_bound(offset + scale);
}

inline unsigned wall_seed(double offset, double scale) {
    return unsigned(std::hash<double>()(offset * 17.0 + scale));
}

// ---------------------------------------------------------------------------------------------------------------
// Broken inputs.

template <class T> struct TriangleCase {
    const char* name;
    Vec3<T> a, b, c;
};

template <class T> std::vector<TriangleCase<T>> broken_triangles() {
    const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
    return {
        {"three equal vertices", {0.2, 0.3, 0}, {0.2, 0.3, 0}, {0.2, 0.3, 0}},
        {"two equal vertices", {0, 0, 0}, {1, 1, 0}, {1, 1, 0}},
        {"NaN vertex", {0, 0, 0}, {1, 0, 0}, {nan, 1, 0}},
        {"+Inf vertex", {0, 0, 0}, {inf, 0, 0}, {0, 1, 0}},
        {"-Inf vertex", {0, 0, 0}, {1, 0, 0}, {0, -inf, 0}},
        {"all Inf", {inf, inf, inf}, {-inf, inf, 0}, {inf, -inf, -inf}},
    };
}

template <class T> std::vector<std::pair<const char*, Ray<T>>> broken_rays() {
    const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
    return {
        {"NaN direction", Ray<T>{{0.2, 0.2, 1}, {nan, 0, -1}}},
        {"all-NaN direction", Ray<T>{{0.2, 0.2, 1}, {nan, nan, nan}}},
        {"zero direction", Ray<T>{{0.2, 0.2, 1}, {0, 0, 0}}},
        {"Inf direction", Ray<T>{{0.2, 0.2, 1}, {0, 0, -inf}}},
        {"NaN origin", Ray<T>{{nan, 0.2, 1}, {0, 0, -1}}},
        {"Inf origin", Ray<T>{{0.2, 0.2, inf}, {0, 0, -1}}},
    };
}

// Counts of spawned rays and of those that failed (re-hit their surface, or leaked), per kind.
struct Tally {
    std::size_t rays = 0, failures = 0;
    void add(bool failed) { ++rays; failures += failed ? 1 : 0; }
    double rate() const { return rays ? double(failures) / double(rays) : 0.0; }
};

struct SpawnTallies {
    Tally shadow, reflection, refraction_in, refraction_out;
    std::size_t failures() const {
        return shadow.failures + reflection.failures + refraction_in.failures + refraction_out.failures;
    }
    std::size_t rays() const { return shadow.rays + reflection.rays + refraction_in.rays + refraction_out.rays; }
    double rate() const { return rays() ? double(failures()) / double(rays()) : 0.0; }
};

// A primary ray from outside aimed at a random interior point of a random triangle of `s` (a closed mesh of size
// `scale`), coming from within 78 degrees of the triangle's normal, starting 3 * scale away.
template <class T> struct AimedRay {
    Ray<T> ray;
    std::size_t triangle;       // the triangle it is aimed at
    glm::dvec3 barycentrics;    // the point aimed at, in that triangle
};
template <class T> AimedRay<T> primary_ray_at_random_triangle(const Scene& s, double scale, std::mt19937& rng) {
    std::uniform_int_distribution<std::size_t> pick(0, s.triangle_count() - 1);
    const std::size_t t = pick(rng);
    const glm::dvec3 b = interior_barycentrics(rng);
    const Vec3<T> target = T(b.x) * corner<T>(s, t, 0) + T(b.y) * corner<T>(s, t, 1) + T(b.z) * corner<T>(s, t, 2);
    return {ray_aimed_at(target, direction_outside<T>({winding_normal<T>(s, t)}, T(0.2), rng), T(3 * scale)), t, b};
}

// Every triangle of the scene twice: the copy (same vertices; every other one in reverse order, so its winding is
// the opposite) gets a higher id, so every hit is a tie at equal t, which must go to the lowest id in every stage.
inline Scene with_coincident_copies(Scene s) {
    const std::size_t n = s.triangle_count();
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t order[3] = {0, i % 2 ? 2u : 1u, i % 2 ? 1u : 2u};
        for (std::size_t k : order) {
            s.positions.push_back(s.positions[3 * i + k]);
            s.normals.push_back(s.normals[3 * i + k]);
            s.uvs.push_back(s.uvs[3 * i + k]);
            if (!s.tangents.empty()) s.tangents.push_back(s.tangents[3 * i + k]);
        }
        s.material_ids.push_back(s.material_ids[i]);
    }
    return s;
}

}  // namespace rt::hard_cases
