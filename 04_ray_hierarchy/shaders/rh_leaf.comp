#version 450 core
// The leaves: the exact ray/triangle test (common/shaders/intersect.glsl, as brute force) on each surviving
// (ray, triangle) pair of a chunk. Shadow rays (RH_SHADOW): any hit blocks the light. Closest hits: step 1 of
// rh_closest.glsl. The chunk's tests are added to the global counter once, by the CPU, which knows their number
// (rh_fold.comp, mode 6), not by an atomic per pair; only the heatmap needs one per pair, on the ray's pixel.
#include "rh_common.glsl"
#include "rh_triangles.glsl"
#include "rh_pairs.glsl"
#include "opacity.glsl"
#ifndef RH_SHADOW
#include "rh_closest.glsl"
#endif

layout(local_size_x = 64) in;

#ifdef RH_SHADOW
layout(std430, binding = WF_BINDING_RESULTS) buffer Occluded { uint rh_occluded[]; };
#endif

uniform uint rh_count;          // pairs in the chunk
uniform uint rh_group_first;    // wf_rays_in index of the group's ray 0
uniform uint rh_batch_first;    // wf_rays_in index of the batch's ray 0 (results and state are per batch ray)

void main() {
    const uint i = rt_global_index();
    if (i >= rh_count) return;
    const uvec2 p = rh_pair(i);
    const uint ray_index = rh_group_first + p.x;
    const WavefrontRay r = wf_rays_in[ray_index];
    const uint slot = ray_index - rh_batch_first;
    vec3 a, b, c;
    rh_load_triangle(p.y, a, b, c);
    float t, u, v;
    const bool hit = intersect_triangle(RT_INTERSECT_METHOD, wf_ray(r), a, b, c, t, u, v) && cutout_opaque(p.y, u, v);
#ifdef RH_SHADOW
    if (hit) rh_occluded[slot] = 1u;
#else
    if (hit) {
        const uint bits = floatBitsToUint(t);
        const uint before = atomicMin(rh_state[slot].min_t, bits);
        if (rh_near(t, min(before, bits))) rh_hits[atomicAdd(rh_info[1], 1u)] = uvec4(slot, p.y, bits, 0u);
    }
#endif
#if defined(COUNT_TESTS) && defined(RECORD_TESTS_PER_PIXEL)
    if (r.pixel != WF_NO_PIXEL) atomicAdd(wf_tests_per_pixel[r.pixel], 1u);
#endif
}
