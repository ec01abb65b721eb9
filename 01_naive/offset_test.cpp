// The spawn offsets (offset.h) with stage 01's brute-force tracer: shadow, reflection and refraction rays spawned from
// a hit never re-hit the surface they leave with the robust offset, at coordinates from 1e-4 to 1e6 and scales from
// 1e-3 to 1e3; the fixed epsilon fails where its 1e-4 is below a float step or above a wall's thickness (both
// measured and printed: run build/tests/unit_tests_01_naive --gtest_filter='SelfIntersection*').
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "01_naive/brute_force_tracer.h"
#include "common/trace/hard_cases.h"
#include "common/trace/intersect.h"
#include "common/trace/offset.h"
#include "common/trace/shading.h"
#include "common/trace/whitted.h"

namespace rt {
namespace {

using namespace hard_cases;   // the meshes, rays and placements shared with the GLSL suite

// A glass-like sphere of radius `scale` centred at (offset, offset, offset). Rays from outside hit it; from each hit
// point the rays Whitted spawns leave with the origin offset_ray_origin() gives them (as Whitted's spawn_origin):
//   shadow      towards a random direction above the surface   must hit nothing (the sphere is convex)
//   reflection  mirror direction                                must hit nothing
//   refraction  into the sphere                                 must reach the far side (t > scale / 4), not its
//               own surface again nor escape
//   leaving     refracted out again at the far side             must hit nothing
template <class T>
SpawnTallies spawn_from_sphere(OffsetMethod method, double offset, double scale, int primaries, unsigned seed) {
    const Scene s = sphere_at(offset, scale);
    const BruteForceTracer<T> tracer(s, IntersectMethod::Watertight);
    std::mt19937 rng(seed);
    const T eps = T(kDefaultEpsilon), eta = T(1.5);
    RayCounters counters;
    SpawnTallies tally;
    auto spawn = [&](const SurfacePoint<T>& sp, const Vec3<T>& direction) {
        Ray<T> r;
        r.direction = direction;
        r.origin = offset_ray_origin(method, sp.position, sp.geometric_normal, direction, eps);
        return r;
    };
    for (int i = 0; i < primaries; ++i) {
        const Ray<T> primary = primary_ray_at_random_triangle<T>(s, scale, rng).ray;
        Hit<T> hit;
        if (!tracer.closest(primary, hit, counters)) continue;   // cannot happen (watertight); nothing to spawn
        const SurfacePoint<T> sp = surface_point(s, primary, hit);

        Hit<T> h;
        const Ray<T> shadow = spawn(sp, direction_outside<T>({sp.geometric_normal}, T(0.1), rng));
        tally.shadow.add(tracer.closest(shadow, h = {}, counters));
        const Ray<T> mirror = spawn(sp, glm::normalize(reflect_dir(primary.direction, sp.geometric_normal)));
        tally.reflection.add(tracer.closest(mirror, h = {}, counters));

        Vec3<T> inward;
        if (!refract_dir(primary.direction, sp.geometric_normal, T(1) / eta, inward)) continue;
        const Ray<T> inside = spawn(sp, inward);
        Hit<T> far_side;
        const bool reached = tracer.closest(inside, far_side, counters) && far_side.t > T(scale / 4);
        tally.refraction_in.add(!reached);
        if (!reached) continue;
        const SurfacePoint<T> exit = surface_point(s, inside, far_side);
        Vec3<T> outward;
        if (!refract_dir(inside.direction, exit.geometric_normal, eta, outward)) continue;   // internal reflection
        tally.refraction_out.add(tracer.closest(spawn(exit, outward), h = {}, counters));
    }
    return tally;
}

TEST(SelfIntersection, SpawnedRaysNeverRehitTheirSurfaceAtAnyOffsetOrScale) {
    const auto& offsets = kPlacementOffsets;
    const auto& scales = kPlacementScales;
    const int primaries = 300;
    std::printf("[ self-hits ] failure rate of spawned shadow/reflection/refraction rays off a sphere of radius SCALE "
                "at (OFFSET, OFFSET, OFFSET), float; epsilon = %g; '-' = not representable in float\n"
                "  offset \\ scale", double(kDefaultEpsilon));
    for (double scale : scales) std::printf("  %15.0e", scale);
    std::printf("\n");
    std::map<std::pair<double, double>, SpawnTallies> epsilon_float;
    for (double offset : offsets) {
        std::printf("  %-13.0e  ", offset);
        for (double scale : scales) {
            if (!sphere_representable(offset, scale)) {
                std::printf("  %15s", "-");
                continue;
            }
            const unsigned seed = sphere_seed(offset, scale);
            for (OffsetMethod method : kOffsets) {
                const SpawnTallies f = spawn_from_sphere<float>(method, offset, scale, primaries, seed);
                const SpawnTallies d = spawn_from_sphere<double>(method, offset, scale, primaries, seed);
                if (method == OffsetMethod::Epsilon) epsilon_float[{offset, scale}] = f;
                if (method == OffsetMethod::Robust) {
                    EXPECT_EQ(f.failures(), 0u) << "robust, float, offset " << offset << ", scale " << scale
                                                << ": shadow " << f.shadow.failures << ", reflection "
                                                << f.reflection.failures << ", refraction in "
                                                << f.refraction_in.failures << ", out " << f.refraction_out.failures;
                    EXPECT_EQ(d.failures(), 0u) << "robust, double, offset " << offset << ", scale " << scale;
                    EXPECT_GT(f.refraction_out.rays, 0u);
                }
            }
            const SpawnTallies& e = epsilon_float[{offset, scale}];
            char cell[32];
            std::snprintf(cell, sizeof cell, "eps %4.1f%% rob 0", 100.0 * e.rate());
            std::printf("  %15s", cell);
        }
        std::printf("\n");
    }
    // Where the fixed epsilon is known to fail: at 1e4 a float step is 2^-10 ~ 1e-3 > 1e-4, so p + eps n rounds back
    // to p and about half the spawned rays start under the surface (acne), for every kind of ray.
    for (auto [offset, scale] : {std::pair{1e4, 1.0}, std::pair{1e6, 1e3}, std::pair{1e4, 1e3}}) {
        const SpawnTallies& e = epsilon_float.at({offset, scale});
        std::printf("[ self-hits ] epsilon at offset %g, scale %g: shadow %.1f%%, reflection %.1f%%, refraction in "
                    "%.1f%%, leaving %.1f%% of %zu rays fail\n", offset, scale, 100 * e.shadow.rate(),
                    100 * e.reflection.rate(), 100 * e.refraction_in.rate(), 100 * e.refraction_out.rate(), e.rays());
        EXPECT_GT(e.shadow.failures, 0u) << "offset " << offset << ", scale " << scale;
        EXPECT_GT(e.reflection.failures, 0u) << "offset " << offset << ", scale " << scale;
        EXPECT_GT(e.refraction_in.failures, 0u) << "offset " << offset << ", scale " << scale;
    }
    RecordProperty("epsilon_failure_rate_at_1e4", std::to_string(epsilon_float.at({1e4, 1.0}).rate()));
    // Near the origin at a human scale a fixed epsilon is fine: that is why it is taught.
    EXPECT_EQ(epsilon_float.at({1.0, 1.0}).failures(), 0u);
}

// A thin slab (a closed box 0.05 * scale thick) at (offset, offset, offset). Rays from above hit its top face; the
// ray refracted into it must be stopped by the bottom face. A fixed epsilon larger than the thickness starts that ray
// below the bottom face: it escapes, and light leaks through the wall. Counts the rays that are not.
template <class T>
Tally leaks_through_thin_wall(OffsetMethod method, double offset, double scale, int rays, unsigned seed) {
    const Scene s = thin_slab_at(offset, scale);
    float bottom = kInf, top = -kInf;
    for (const glm::vec3& p : s.positions) bottom = std::min(bottom, p.y), top = std::max(top, p.y);
    auto on_plane = [&](std::int32_t triangle, float y) {
        for (int k = 0; k < 3; ++k)
            if (s.positions[3 * std::size_t(triangle) + std::size_t(k)].y != y) return false;
        return true;
    };
    const BruteForceTracer<T> tracer(s, IntersectMethod::Watertight);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> across(-0.4, 0.4);
    RayCounters counters;
    Tally tally;
    for (int i = 0; i < rays; ++i) {
        const Vec3<T> target(T(offset + scale * across(rng)), T(top), T(offset + scale * across(rng)));
        const Vec3<T> from = direction_outside<T>({Vec3<T>(0, 1, 0)}, T(0.3), rng);
        const Ray<T> primary = ray_aimed_at(target, from, T(2 * scale));
        Hit<T> hit;
        if (!tracer.closest(primary, hit, counters) || !on_plane(hit.triangle, top)) continue;
        const SurfacePoint<T> sp = surface_point(s, primary, hit);
        Vec3<T> inward;
        if (!refract_dir(primary.direction, sp.geometric_normal, T(1) / T(1.5), inward)) continue;
        Ray<T> through;
        through.direction = inward;
        through.origin = offset_ray_origin(method, sp.position, sp.geometric_normal, inward, T(kDefaultEpsilon));
        Hit<T> other_side;
        tally.add(!(tracer.closest(through, other_side, counters) && on_plane(other_side.triangle, bottom)));
    }
    return tally;
}

TEST(SelfIntersection, RaysIntoAThinWallAreStoppedByItsOtherFace) {
    const auto& offsets = kWallOffsets;
    const auto& scales = kPlacementScales;
    std::printf("[ thin wall ] rays refracted into a slab 0.05*SCALE thick at OFFSET that escape through its far face, "
                "float; epsilon = %g; '-' = wall thinner than the robust offset: no float offset helps\n"
                "  offset \\ scale", double(kDefaultEpsilon));
    for (double scale : scales) std::printf("  %15.0e", scale);
    std::printf("\n");
    std::map<std::pair<double, double>, Tally> epsilon_leaks;
    for (double offset : offsets) {
        std::printf("  %-13.0e  ", offset);
        for (double scale : scales) {
            if (!wall_representable(offset, scale)) {
                std::printf("  %15s", "-");
                continue;
            }
            const unsigned seed = wall_seed(offset, scale);
            const Tally e = leaks_through_thin_wall<float>(OffsetMethod::Epsilon, offset, scale, 200, seed);
            const Tally r = leaks_through_thin_wall<float>(OffsetMethod::Robust, offset, scale, 200, seed);
            const Tally rd = leaks_through_thin_wall<double>(OffsetMethod::Robust, offset, scale, 200, seed);
            epsilon_leaks[{offset, scale}] = e;
            EXPECT_GT(r.rays, 100u);
            EXPECT_EQ(r.failures, 0u) << "robust, float, offset " << offset << ", scale " << scale;
            EXPECT_EQ(rd.failures, 0u) << "robust, double, offset " << offset << ", scale " << scale;
            char cell[32];
            std::snprintf(cell, sizeof cell, "eps %5.1f%% rob 0", 100.0 * e.rate());
            std::printf("  %15s", cell);
        }
        std::printf("\n");
    }
    // 0.05 mm thick at 1 mm scale: thinner than the 0.1 mm epsilon, so every refracted ray starts past the wall.
    for (double offset : {0.0, 1.0}) {
        const Tally& e = epsilon_leaks.at({offset, 1e-3});
        EXPECT_EQ(e.failures, e.rays) << "offset " << offset;
        EXPECT_GT(e.rays, 100u);
    }
    // A wall twice as thick as epsilon stops it.
    EXPECT_EQ(epsilon_leaks.at({0.0, 1e-2}).failures, 0u);
    RecordProperty("epsilon_leak_rate_at_scale_1e-3", std::to_string(epsilon_leaks.at({0.0, 1e-3}).rate()));
}

}  // namespace
}  // namespace rt
