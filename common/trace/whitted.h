// Whitted's recursive ray tracing (Whitted 1980) for the CPU, written once and used by stage 01 and by every test
// and script that needs the reference image. It is generic over the scalar type T (float or double geometry) and
// over the Tracer that finds hits, which is what each CPU technique provides:
//
//   struct Tracer {
//       bool closest(const Ray<T>& ray, Hit<T>& hit, RayCounters& counters) const;   // nearest hit, t < ray.tmax
//       bool occluded(const Ray<T>& ray, RayCounters& counters) const;              // any hit with t < ray.tmax
//   };
//
// docs/shading.md states the model; the GPU stages implement the same sum in passes
// (common/shaders/trace/shading.glsl).
#pragma once

#include <algorithm>
#include <optional>
#include <vector>

#include "hit_record.h"
#include "common/scene/effects.h"
#include "common/scene/scene.h"
#include "absorption.h"
#include "area_light.h"
#include "environment.h"
#include "intersect.h"
#include "normal_map.h"
#include "offset.h"
#include "opacity.h"
#include "shading.h"
#include "texture_transform.h"

namespace rt {

struct WhittedSettings {
    int max_depth = 5;
    float cutoff = kDefaultCutoff;
    FresnelMode fresnel = FresnelMode::Exact;
    OffsetMethod offset = OffsetMethod::Robust;
    float epsilon = kDefaultEpsilon;
    Effects effects;
    LightGrid light_grid;   // how each area light is sampled (--light-grid, --light-jitter)
};

// Where the rays of one camera sample go when hits are recorded (--dump-hits: the records of hit_record.h) or when
// the pixel is watched (--pixel: what each ray cost). Either pointer may be null.
struct HitLog {
    std::vector<HitRecord>* records;
    std::uint32_t sample = 0;
    std::uint32_t pixel = 0;   // y * width + x
    std::vector<RayWork>* work = nullptr;

    template <class T>
    void add(std::uint32_t path, RayKind kind, std::uint32_t light, const Ray<T>& ray, std::int32_t triangle,
             float t, std::uint64_t tests, std::uint32_t light_cell = 0) const {
        if (work) work->push_back(RayWork{sample, path, pack_kind_light(kind, light, light_cell), tests, 0});
        if (!records) return;
        HitRecord r;
        r.sample = sample;
        r.pixel = pixel;
        r.path = path;
        r.kind_light = pack_kind_light(kind, light, light_cell);
        r.triangle = triangle;
        r.t = t;
        for (int i = 0; i < 3; ++i) {
            r.origin[i] = float(ray.origin[i]);
            r.direction[i] = float(ray.direction[i]);
        }
        records->push_back(r);
    }
};

inline float max_component(const glm::vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }

// What a primary hit needs for shading, computed in T and handed to the shading code in float.
template <class T>
struct SurfacePoint {
    Vec3<T> position;          // interpolated from the vertices (more accurate than origin + t * direction)
    Vec3<T> geometric_normal;  // unit, facing the incoming ray
    glm::vec3 shading_normal;  // unit, on the same side as geometric_normal
    glm::vec2 uv;
    glm::vec4 color{1.0f};     // the vertex colour (COLOR_0), interpolated like uv; white when the scene has none
    bool front_face;           // the ray arrived from the side the triangle's winding calls outside
    std::uint32_t material;
};

template <class T>
SurfacePoint<T> surface_point(const Scene& scene, const Ray<T>& ray, const Hit<T>& hit) {
    const std::size_t i = std::size_t(hit.triangle) * 3;
    const Vec3<T> a(scene.positions[i]), b(scene.positions[i + 1]), c(scene.positions[i + 2]);
    const T w = T(1) - hit.u - hit.v;
    SurfacePoint<T> s;
    s.position = w * a + hit.u * b + hit.v * c;
    Vec3<T> ng = glm::cross(b - a, c - a);
    const T len = glm::length(ng);
    ng = len > T(0) ? ng / len : -Vec3<T>(ray.direction);   // a degenerate triangle only gets hit through rounding
    s.front_face = glm::dot(ng, ray.direction) < T(0);
    s.geometric_normal = s.front_face ? ng : -ng;
    const float wf = float(w), uf = float(hit.u), vf = float(hit.v);
    glm::vec3 ns = wf * scene.normals[i] + uf * scene.normals[i + 1] + vf * scene.normals[i + 2];
    const float ns_len = glm::length(ns);
    const glm::vec3 ngf(s.geometric_normal);
    ns = (ns_len > 0.0f && std::isfinite(ns_len)) ? ns / ns_len : ngf;
    // Shading normals interpolated across a curved mesh can face away from the viewer near silhouettes: turn them to
    // the geometric side so lighting and reflection stay on the visible side of the surface.
    s.shading_normal = glm::dot(ns, ngf) < 0.0f ? -ns : ns;
    s.uv = wf * scene.uvs[i] + uf * scene.uvs[i + 1] + vf * scene.uvs[i + 2];
    if (!scene.colors.empty()) s.color = vertex_color(scene, i, uf, vf);
    s.material = scene.material_ids[std::size_t(hit.triangle)];
    return s;
}

// A shadow ray's tmax: the distance from its origin to its light, infinite for a directional light. Every stage's
// shadow rays get it (the GPU stages' twin: common/shaders/wavefront/shade.comp), and tests/retrace_hits traces a
// dump's shadow rays again with it.
template <class T>
T shadow_tmax(const Light& light, const Vec3<T>& origin) {
    return light.type == LightType::Directional ? std::numeric_limits<T>::infinity()
                                                : glm::length(Vec3<T>(light.position) - origin);
}

// The tmax a recorded shadow ray (hit_record.h) was traced with, rebuilt from its record: to its punctual light
// (shadow_tmax) or to its area light's cell for its camera sample (area_shadow_tmax). For tools that trace a dump
// again (tests/retrace_hits, 03's Embree bench) with the stage's --offset, --epsilon and --light-grid.
inline float recorded_shadow_tmax(const Scene& scene, const LightGrid& grid, OffsetMethod offset, float epsilon,
                                  const HitRecord& r) {
    const std::uint32_t light = light_index(r.kind_light);
    const glm::vec3 origin(r.origin[0], r.origin[1], r.origin[2]);
    if (light < scene.lights.size()) return shadow_tmax(scene.lights[light], origin);
    const AreaSample sample = area_light_cell(scene, grid, light, light_sample(r.kind_light), {r.pixel, r.sample});
    return area_shadow_tmax(offset, epsilon, sample, origin, glm::vec3(r.direction[0], r.direction[1], r.direction[2]));
}

template <class T, class Tracer>
class Whitted {
public:
    // `shadow_tracer`, when given, traces the shadow rays (stage 01 with BLEND coverage: shadow rays keep the cut-out
    // at 0.5, opacity.h); otherwise `tracer` traces every ray.
    Whitted(const Scene& scene, const Tracer& tracer, const WhittedSettings& settings,
            const Tracer* shadow_tracer = nullptr)
        : scene_(scene),
          tracer_(tracer),
          shadow_tracer_(shadow_tracer ? *shadow_tracer : tracer),
          settings_(settings) {}

    // Radiance arriving along `ray`; `weight` is the product of the coefficients on the path so far (the path stops
    // spawning rays once a child's weight falls below the cut-off). With a `log`, every traced ray is recorded under
    // its `path` in the pixel's ray tree (hit_record.h: 1 for the primary ray, 2p and 2p + 1 for the reflection and
    // refraction children of path p; shadow rays carry their parent's path and their light's index). `kind` is the
    // ray's kind when its path does not say it (a transparency ray); by default camera rays are primary and children
    // reflection or refraction rays by their path's parity. `id` names the camera sample the ray belongs to
    // (--light-jitter's offsets depend on it).
    glm::vec3 radiance(const Ray<T>& ray, int depth, const glm::vec3& path_weight, RayCounters& counters,
                       const HitLog* log = nullptr, std::uint32_t path = 1,
                       std::optional<RayKind> kind = std::nullopt, PixelSample id = {}) const {
        Hit<T> hit;
        const std::uint64_t tests_before = counters.intersection_tests;
        const bool found = tracer_.closest(ray, hit, counters);
        // The tests by kind: only camera rays start at depth 0; children keep their path's parity (2p, 2p + 1) even
        // where the path number wraps.
        const RayKind ray_kind = kind ? *kind
                                 : depth == 0   ? RayKind::Primary
                                 : (path & 1u) ? RayKind::Refraction
                                               : RayKind::Reflection;
        const std::uint64_t tests = counters.intersection_tests - tests_before;
        counters.tests_by_kind[int(ray_kind)] += tests;
        if (log) {
            const RayKind logged = kind ? *kind
                                   : path == 1 ? RayKind::Primary
                                   : path & 1u ? RayKind::Refraction
                                               : RayKind::Reflection;
            log->add(path, logged, 0, ray, found ? hit.triangle : -1, found ? float(hit.t) : 0.0f, tests);
        }
        if (!found) return miss_radiance(scene_, glm::vec3(ray.direction));   // environment.h
        const SurfacePoint<T> sp = surface_point(scene_, ray, hit);

        // BLEND as coverage (docs/shading.md, "Alpha: cut-outs and blending"): the surface is shaded with weight
        // alpha, and a transparency ray continues the ray through it with weight 1 - alpha (depth + 1, path
        // 2p + 1: a BLEND surface does not refract, so the slot is free). Without Effects::blend BLEND is a cut-out.
        if (!settings_.effects.blend || scene_.materials[sp.material].alpha_mode != AlphaMode::Blend)
            return shade(ray, hit, sp, depth, path_weight, counters, log, path, false, id);
        const float alpha = surface_opacity(scene_, std::size_t(hit.triangle), hit.u, hit.v);
        glm::vec3 color = alpha * shade(ray, hit, sp, depth, path_weight * alpha, counters, log, path, true, id);
        const glm::vec3 through_weight = path_weight * (1.0f - alpha);
        if (depth < settings_.max_depth && max_component(through_weight) > settings_.cutoff) {
            Ray<T> through;   // the same direction, from the far side of the surface
            through.direction = ray.direction;
            through.origin = spawn_origin(sp, ray.direction);
            counters.rays[int(RayKind::Transparency)]++;
            color += (1.0f - alpha) * radiance(through, depth + 1, through_weight, counters, log, 2 * path + 1,
                                               RayKind::Transparency, id);
        }
        return color;
    }

private:
    // The hit's own light: emission, ambient, the lights its shadow rays reach, and its reflection and refraction
    // rays (none for a BLEND surface read as coverage: `blend_surface`).
    glm::vec3 shade(const Ray<T>& ray, const Hit<T>& hit, SurfacePoint<T> sp, int depth, const glm::vec3& path_weight,
                    RayCounters& counters, const HitLog* log, std::uint32_t path, bool blend_surface,
                    PixelSample id) const {
        const Material& material = scene_.materials[sp.material];
        // Absorption (docs/shading.md): a ray that reaches the back face of an absorbing volume travelled inside it
        // for hit.t; what comes back along it, and the weight its children inherit, keep exp(-sigma_a t).
        glm::vec3 absorbed(1.0f);
        if (settings_.effects.absorption && !sp.front_face)
            absorbed = transmittance(absorption_coefficient(material), float(hit.t));
        const glm::vec3 weight = path_weight * absorbed;
        if (settings_.effects.normal_maps && material.normal_texture >= 0) {
            const T w = T(1) - hit.u - hit.v;
            sp.shading_normal = normal_mapped(scene_, std::size_t(hit.triangle), float(w), float(hit.u),
                                              float(hit.v), sp.uv, glm::vec3(sp.geometric_normal),
                                              sp.shading_normal, material);
        }
        SurfaceTexels texels;
        if (settings_.effects.textures) {   // the textures and COLOR_0 (docs/shading.md, "Vertex colours")
            texels = sample_surface_textures(material, scene_.textures, sp.uv);
            texels.base *= sp.color;
        }
        SurfaceCoefficients s = surface_coefficients(material, texels);
        if (blend_surface) s.transmission = 0.0f;   // its see-through part is the transparency ray
        const glm::vec3 d = glm::vec3(ray.direction);
        const glm::vec3 n = sp.shading_normal;

        // Local illumination: emission, ambient (no ray: shading.h), and each light not blocked by a shadow ray:
        // the punctual lights, then each cell of each area light's grid (area_light.h) as a point light.
        glm::vec3 color = s.emissive + ambient_light(scene_.ambient, s.diffuse, n);
        const glm::vec3 p(sp.position);
        for (std::uint32_t light_index = 0; light_index < scene_.lights.size(); ++light_index) {
            const Light& light = scene_.lights[light_index];
            glm::vec3 to_light;
            float distance;
            const glm::vec3 incidence = light_incidence(light, p, n, to_light, distance);
            if (incidence == glm::vec3(0.0f)) continue;
            const auto tmax = [&](const Vec3<T>& origin) { return shadow_tmax(light, origin); };
            if (reaches_light(sp, to_light, tmax, light_index, 0, counters, log, path))
                color += shade_light(s, incidence, n, to_light, -d);
        }
        const LightGrid& grid = settings_.light_grid;
        for (std::uint32_t a = 0; a < scene_.area_lights.size(); ++a) {
            const AreaLight& area = scene_.area_lights[a];
            const auto light_index = std::uint32_t(scene_.lights.size() + a);
            for (std::uint32_t cell = 0; cell < grid.cells(); ++cell) {
                const AreaSample sample = area_light_cell(scene_, grid, light_index, cell, id);
                const glm::vec3 emission = area_light_emission(scene_, area, sample, settings_.effects.textures);
                Light point;
                if (!area_sample_as_point_light(area, sample, emission, grid.cells(), p, point)) continue;
                glm::vec3 to_light;
                float distance;
                const glm::vec3 incidence = light_incidence(point, p, n, to_light, distance);
                if (incidence == glm::vec3(0.0f)) continue;
                const Vec3<T> direction(to_light);
                const auto tmax = [&](const Vec3<T>& origin) {
                    return area_shadow_tmax(settings_.offset, T(settings_.epsilon), sample, origin, direction);
                };
                if (settings_.effects.shadows) counters.light_samples++;
                if (reaches_light(sp, to_light, tmax, light_index, cell, counters, log, path))
                    color += shade_light(s, incidence, n, to_light, -d);
            }
        }
        if (depth >= settings_.max_depth) return absorbed * color;

        // BEGIN EXERCISE 01.whitted_recursion: spawn the reflection ray (reflect_dir) and the refraction ray
        // (refract_dir, none at total internal reflection) when the scene's effects ask for them and the child's weight
        // stays above the cut-off; each starts at spawn_origin(sp, direction), counts in counters.rays, and adds
        // its coefficient times radiance(child, depth + 1, ...) with path 2 * path (reflection) or 2 * path + 1.
        // Reflection and refraction (docs/shading.md, "Secondary rays"). eta = n_incident / n_transmitted.
        const float cos_i = std::clamp(-glm::dot(d, n), 0.0f, 1.0f);
        const float eta = sp.front_face ? 1.0f / s.ior : s.ior;
        const float f = fresnel(settings_.fresnel, cos_i, eta);
        const ReflectRefract k = coefficients(s, sp.front_face, cos_i, f);

        if (settings_.effects.reflections && max_component(weight * k.reflection) > settings_.cutoff) {
            Ray<T> r;
            glm::vec3 dir = reflect_dir(d, n);
            // A shading normal far from the geometric one can send the reflection under the surface: use the
            // geometric normal then.
            if (glm::dot(dir, glm::vec3(sp.geometric_normal)) <= 0.0f) dir = reflect_dir(d, glm::vec3(sp.geometric_normal));
            r.direction = glm::normalize(Vec3<T>(dir));
            r.origin = spawn_origin(sp, r.direction);
            counters.rays[int(RayKind::Reflection)]++;
            color += k.reflection * radiance(r, depth + 1, weight * k.reflection, counters, log, 2 * path,
                                             std::nullopt, id);
        }
        if (settings_.effects.refractions && max_component(weight * k.refraction) > settings_.cutoff) {
            glm::vec3 dir;
            if (refract_dir(d, n, eta, dir)) {
                Ray<T> r;
                r.direction = glm::normalize(Vec3<T>(dir));
                r.origin = spawn_origin(sp, r.direction);
                counters.rays[int(RayKind::Refraction)]++;
                color += k.refraction * radiance(r, depth + 1, weight * k.refraction, counters, log,
                                                      2 * path + 1, std::nullopt, id);
            }
        }
        return absorbed * color;
        // STUB: (void)weight;
        // STUB: return absorbed * color;
        // END EXERCISE
    }

public:
    // Weights of the reflected and refracted rays (docs/shading.md): metals reflect their base colour; the
    // dielectric part reflects F and, where it transmits, refracts (1 - F), tinted by the base colour on entry.
    struct ReflectRefract {
        glm::vec3 reflection{0.0f};
        glm::vec3 refraction{0.0f};
    };
    static ReflectRefract coefficients(const SurfaceCoefficients& s, bool front_face, float cos_i, float f) {
        ReflectRefract k;
        // Metals: Schlick with the base colour as F0 (conductors have no single eta).
        const float m = 1.0f - cos_i;
        const glm::vec3 f_metal = s.base + (glm::vec3(1.0f) - s.base) * (m * m * m * m * m);
        const glm::vec3 metal = (1.0f - s.dielectric) * s.smoothness * f_metal;
        // Dielectrics: the Fresnel term for this ior, scaled by KHR_materials_specular relative to plain F0.
        const float r0 = f0_of(s.ior);
        const glm::vec3 spec_scale = r0 > 0.0f ? s.f0_dielectric / r0 : glm::vec3(0.0f);
        const glm::vec3 fd = glm::min(glm::vec3(1.0f), f * spec_scale);
        k.reflection = metal + s.dielectric * s.smoothness * fd;
        k.refraction = s.dielectric * s.transmission * (glm::vec3(1.0f) - fd) * (front_face ? s.base : glm::vec3(1.0f));
        return k;
    }

private:
    // Whether light from `to_light` reaches the point: without shadows always, else when the shadow ray from the
    // point (origin offset off the surface, tmax(origin) long) hits nothing. The ray is counted and logged as light
    // `light_index`'s (and, for an area light, its grid cell's).
    template <class Tmax>
    bool reaches_light(const SurfacePoint<T>& sp, const glm::vec3& to_light, const Tmax& tmax,
                       std::uint32_t light_index, std::uint32_t cell, RayCounters& counters, const HitLog* log,
                       std::uint32_t path) const {
        if (!settings_.effects.shadows) return true;
        Ray<T> shadow;
        shadow.direction = Vec3<T>(to_light);
        shadow.origin = spawn_origin(sp, shadow.direction);
        shadow.tmax = tmax(shadow.origin);
        counters.rays[int(RayKind::Shadow)]++;
        const std::uint64_t tests_before = counters.intersection_tests;
        const bool occluded = shadow_tracer_.occluded(shadow, counters);
        const std::uint64_t tests = counters.intersection_tests - tests_before;
        counters.tests_by_kind[int(RayKind::Shadow)] += tests;
        if (log) log->add(path, RayKind::Shadow, light_index, shadow, occluded ? 1 : -1, 0.0f, tests, cell);
        return !occluded;
    }

    static float f0_of(float ior) { const float r = (ior - 1.0f) / (ior + 1.0f); return r * r; }

    Vec3<T> spawn_origin(const SurfacePoint<T>& sp, const Vec3<T>& direction) const {
        return offset_ray_origin(settings_.offset, sp.position, sp.geometric_normal, direction, T(settings_.epsilon));
    }

    const Scene& scene_;
    const Tracer& tracer_;
    const Tracer& shadow_tracer_;
    WhittedSettings settings_;
};

}  // namespace rt
