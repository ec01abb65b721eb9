// The reference tracer: no acceleration structure, every ray is tested against every triangle. It is the technique
// of stage 01 and the reference every test of a faster structure compares with.
//   closest():  keep the nearest hit, shrinking tmax as hits are found. Ties at equal t go to the lowest triangle id
//               (the exact hit checks between stages rely on it): triangles are tested in id order and a later one
//               replaces the hit only when strictly closer.
//   occluded(): shadow rays only need to know whether anything blocks the light, so stop at the first hit.
// With cut-outs (Effects::cutouts), a hit where the surface is transparent is no hit (opacity.h); with
// `blend_coverage` (Effects::blend, for the closest-hit tracer), a BLEND surface is hit wherever it covers anything.
#pragma once

#include <vector>

#include "common/scene/scene.h"
#include "common/trace/intersect.h"
#include "common/trace/opacity.h"

namespace rt {

template <class T>
class BruteForceTracer {
public:
    BruteForceTracer(const Scene& scene, IntersectMethod method, bool cutouts = false, bool blend_coverage = false)
        : method_(method), cutouts_(cutouts ? &scene : nullptr), blend_coverage_(blend_coverage) {
        vertices_.reserve(scene.positions.size());
        for (const glm::vec3& p : scene.positions) vertices_.emplace_back(p);   // converted to T once
    }

    bool closest(const Ray<T>& ray, Hit<T>& hit, RayCounters& counters) const {
        // BEGIN EXERCISE 01.closest_hit: test the ray against every triangle (vertices_[3i], [3i + 1], [3i + 2]) with
        // the chosen method (intersect_watertight or intersect_moller); pass each hit where opaque(i, u, v) (alpha
        // cut-outs) to record(), which keeps it only when strictly closer and shrinks r.tmax. Add the tests made to
        // counters.intersection_tests.
        Ray<T> r = ray;
        const std::size_t n = vertices_.size() / 3;
        counters.intersection_tests += n;
        if (method_ == IntersectMethod::Watertight) {
            const WatertightRay<T> w(r.direction);
            for (std::size_t i = 0; i < n; ++i) {
                T t, u, v;
                if (intersect_watertight(r, w, vertices_[3 * i], vertices_[3 * i + 1], vertices_[3 * i + 2], t, u, v) &&
                    opaque(i, u, v))
                    record(r, hit, i, t, u, v);
            }
        } else {
            for (std::size_t i = 0; i < n; ++i) {
                T t, u, v;
                if (intersect_moller(r, vertices_[3 * i], vertices_[3 * i + 1], vertices_[3 * i + 2], t, u, v) &&
                    opaque(i, u, v))
                    record(r, hit, i, t, u, v);
            }
        }
        return hit.valid();
        // STUB: (void)ray, (void)hit, (void)counters;
        // STUB: return false;
        // END EXERCISE
    }

    bool occluded(const Ray<T>& ray, RayCounters& counters) const {
        // BEGIN EXERCISE 01.any_hit: a shadow ray only needs to know whether some triangle is hit with t < tmax
        // (where opaque(i, u, v)): stop at the first one. Count the tests actually made.
        const std::size_t n = vertices_.size() / 3;
        const WatertightRay<T> w(ray.direction);
        for (std::size_t i = 0; i < n; ++i) {
            T t, u, v;
            const bool hit = method_ == IntersectMethod::Watertight
                                 ? intersect_watertight(ray, w, vertices_[3 * i], vertices_[3 * i + 1], vertices_[3 * i + 2], t, u, v)
                                 : intersect_moller(ray, vertices_[3 * i], vertices_[3 * i + 1], vertices_[3 * i + 2], t, u, v);
            if (hit && opaque(i, u, v)) {
                counters.intersection_tests += i + 1;   // early exit: count only the tests made
                return true;
            }
        }
        counters.intersection_tests += n;
        return false;
        // STUB: (void)ray, (void)counters;
        // STUB: return false;
        // END EXERCISE
    }

private:
    bool opaque(std::size_t i, T u, T v) const {
        return !cutouts_ || surface_opaque(*cutouts_, i, u, v, blend_coverage_);
    }

    static void record(Ray<T>& r, Hit<T>& hit, std::size_t i, T t, T u, T v) {
        // The watertight test compares t with tmax before dividing, so rounding may let an equal t through: keep the
        // earlier (lower id) triangle then.
        if (!(t < hit.t)) return;
        r.tmax = t;   // later triangles must beat this hit
        hit.t = t;
        hit.u = u;
        hit.v = v;
        hit.triangle = std::int32_t(i);
    }

    IntersectMethod method_;
    const Scene* cutouts_;   // the scene whose opacity the hits pass (opacity.h), or null: every hit counts
    bool blend_coverage_;    // BLEND surfaces are hit wherever opacity > 0 (not for shadow rays: opacity.h)
    std::vector<Vec3<T>> vertices_;
};

}  // namespace rt
