// Rays and hits, templated on the scalar type so stage 01 can run in float or double (--precision).
#pragma once

#include <cstdint>
#include <limits>

#include <glm/glm.hpp>

namespace rt {

template <class T> using Vec3 = glm::vec<3, T, glm::defaultp>;
template <class T> using Vec2 = glm::vec<2, T, glm::defaultp>;

template <class T>
struct Ray {
    Vec3<T> origin{0};
    Vec3<T> direction{0, 0, -1};   // not necessarily unit length for intersection; the tracers keep it unit
    T tmax = std::numeric_limits<T>::infinity();
};

template <class T>
struct Hit {
    T t = std::numeric_limits<T>::infinity();
    T u = 0, v = 0;                // barycentrics of vertices 1 and 2: P = (1-u-v) A + u B + v C
    std::int32_t triangle = -1;    // -1 = miss
    bool valid() const { return triangle >= 0; }
};

// The kinds of rays a Whitted tracer casts, counted separately in the stats, recorded in hit records
// (hit_record.h) and, as WF_KIND_*, in the GPU stages' ray queues: one enum, one set of names. Transparency rays
// continue a ray through a BLEND surface (docs/shading.md, "Alpha: cut-outs and blending"); only scenes with BLEND
// materials cast them.
enum class RayKind : std::uint32_t { Primary = 0, Shadow = 1, Reflection = 2, Refraction = 3, Transparency = 4 };
constexpr int kRayKinds = 5;
// "primary", "shadow", "reflection", "refraction", "transparency": the keys of the stats JSON and the names in
// printouts.
constexpr const char* ray_kind_name(RayKind kind) {
    switch (kind) {
    case RayKind::Primary: return "primary";
    case RayKind::Shadow: return "shadow";
    case RayKind::Reflection: return "reflection";
    case RayKind::Refraction: return "refraction";
    case RayKind::Transparency: return "transparency";
    }
    return "unknown";
}

// Counters every stage reports: rays of each kind and ray/triangle intersection tests, in all and by the kind of ray
// that made them (indexed by RayKind). Each stage fills the total and the kinds from separate adds, so that the kinds
// sum to the total is a check on the stage (the stats' intersection_tests_by_kind; tests/run_cli_case.cmake).
struct RayCounters {
    std::uint64_t rays[kRayKinds] = {};
    std::uint64_t light_samples = 0;   // of the shadow rays, those towards a cell of an area light (area_light.h)
    std::uint64_t intersection_tests = 0;
    std::uint64_t tests_by_kind[kRayKinds] = {};
    void add(const RayCounters& o) {
        for (int i = 0; i < kRayKinds; ++i) rays[i] += o.rays[i];
        light_samples += o.light_samples;
        intersection_tests += o.intersection_tests;
        for (int i = 0; i < kRayKinds; ++i) tests_by_kind[i] += o.tests_by_kind[i];
    }
    std::uint64_t total_rays() const {
        std::uint64_t n = 0;
        for (int i = 0; i < kRayKinds; ++i) n += rays[i];
        return n;
    }
};

// True when every component is finite (no NaN, no Inf).
template <class V> bool all_finite(const V& v) {
    for (int i = 0; i < V::length(); ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}

}  // namespace rt
