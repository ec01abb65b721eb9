// The reference traversal (stage 02's, and the one every faster traversal is checked against): no acceleration
// structure, as in stage 01 (brute_force_tracer.h). Every ray is tested against every triangle. The wavefront
// pipeline (common/gpu/pipeline/wavefront.h) calls these from its trace pass (closest hit) and its shadow pass (any
// hit); stages 03-05 plug in a faster traversal instead. Shader path: "02_raster_hybrid/shaders/brute_force.glsl".
#include "common/shaders/wavefront/wavefront.glsl"
#include "common/shaders/trace/scene.glsl"
#include "common/shaders/trace/opacity.glsl"

bool intersect_scene_triangle(Ray ray, WatertightRay w, uint i, out float t, out float u, out float v) {
    vec3 a, b, c;
    load_triangle(i, a, b, c);
#if RT_INTERSECT_METHOD == RT_INTERSECT_WATERTIGHT
    return intersect_watertight(ray, w, a, b, c, t, u, v);
#else
    return intersect_moller(ray, a, b, c, t, u, v);
#endif
}

// Nearest hit among triangles [first, end): keep the closest so far, shrinking tmax so later triangles must beat
// it. As the CPU's brute_force_tracer.h, a hit replaces the kept one only when strictly closer: the watertight test
// compares t with tmax before dividing (T_scaled < tmax * det), so rounding may let an equal t through, and without
// the check a later triangle would take the tie. With it, ties at equal t go to the lowest triangle id (hit starts at
// t = +inf). `hit` may hold the closest of earlier triangles (a sliced traversal, brute_force_slice.comp): the
// result is the same as one loop over all of them.
void closest_hit_among(Ray ray, WatertightRay w, uint first, uint end, inout Hit hit) {
    // BEGIN EXERCISE 01.closest_hit: the GLSL twin of BruteForceTracer::closest (stages 02-05 trace with it): test
    // triangles [first, end) with intersect_scene_triangle, keep a hit only when strictly closer than hit.t and
    // cutout_opaque(i, u, v), shrink ray.tmax, and count the tests made with wf_count_tests.
    if (hit.triangle >= 0) ray.tmax = hit.t;
    for (uint i = first; i < end; ++i) {
        float t, u, v;
        if (intersect_scene_triangle(ray, w, i, t, u, v) && t < hit.t && cutout_opaque(i, u, v)) {
            ray.tmax = t;
            hit.t = t;
            hit.u = u;
            hit.v = v;
            hit.triangle = int(i);
        }
    }
    wf_count_tests(end - first);
    // STUB: wf_count_tests(0u);
    // END EXERCISE
}

// Whether any triangle of [first, end) is hit: shadow rays only need to know whether anything blocks the light, so
// stop at the first hit (and count only the tests made).
bool any_hit_among(Ray ray, WatertightRay w, uint first, uint end) {
    // BEGIN EXERCISE 01.any_hit: the GLSL twin of BruteForceTracer::occluded: stop at the first triangle of
    // [first, end) hit (where cutout_opaque) and count only the tests made (wf_count_tests).
    for (uint i = first; i < end; ++i) {
        float t, u, v;
        if (intersect_scene_triangle(ray, w, i, t, u, v) && cutout_opaque(i, u, v)) {
            wf_count_tests(i + 1u - first);
            return true;
        }
    }
    wf_count_tests(end - first);
    return false;
    // STUB: return false;
    // END EXERCISE
}

// The per-ray traversal: one loop over every triangle. (Mesa's llvmpipe cuts an invocation's loops short after
// 65,535 iterations, so on llvmpipe this serves scenes below that; stage 02 traces in slices, brute_force_slice.comp.)
bool trace_closest(Ray ray, out Hit hit) {
    hit = no_hit();
    closest_hit_among(ray, watertight_ray(ray.direction), 0u, rt_triangle_count, hit);
    return hit.triangle >= 0;
}

bool trace_any(Ray ray) { return any_hit_among(ray, watertight_ray(ray.direction), 0u, rt_triangle_count); }
