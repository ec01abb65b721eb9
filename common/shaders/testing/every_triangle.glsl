// For pipeline tests of common/ code only (common/gpu/testing/pipeline_fixture.h): the plainest traversal, every ray
// against every triangle, closest hit strictly closer (ties to the lowest id) as every stage's. No stage traces with
// it: a stage's own traversal (02's brute_force.glsl and on) is graded by that stage's tests.
#include "common/shaders/wavefront/wavefront.glsl"
#include "common/shaders/trace/scene.glsl"
#include "common/shaders/trace/opacity.glsl"

bool fixture_hit(Ray ray, uint i, out float t, out float u, out float v) {
    vec3 a, b, c;
    load_triangle(i, a, b, c);
    return intersect_triangle(RT_INTERSECT_METHOD, ray, a, b, c, t, u, v);
}

bool trace_closest(Ray ray, out Hit hit) {
    hit = no_hit();
    for (uint i = 0u; i < rt_triangle_count; ++i) {
        float t, u, v;
        if (fixture_hit(ray, i, t, u, v) && t < hit.t && cutout_opaque(i, u, v)) {
            ray.tmax = t;
            hit.t = t;
            hit.u = u;
            hit.v = v;
            hit.triangle = int(i);
        }
    }
    wf_count_tests(rt_triangle_count);
    return hit.triangle >= 0;
}

bool trace_any(Ray ray) {
    for (uint i = 0u; i < rt_triangle_count; ++i) {
        float t, u, v;
        if (fixture_hit(ray, i, t, u, v) && cutout_opaque(i, u, v)) {
            wf_count_tests(i + 1u);
            return true;
        }
    }
    wf_count_tests(rt_triangle_count);
    return false;
}
