#version 450 core
// The leaves: each (ray, triangle) pair of a chunk (the other pairs of the chunk are rh_cull.comp's) gets two cheap
// per-ray tests first, the ray against the triangle's bounding sphere (rh_ray_may_hit; --sphere-test off skips it,
// as the papers do) and then against its box (rh_ray_box_may_hit; --box-test off skips it), both computed from the
// vertices here, so no buffer more is bound; and only then the exact ray/triangle test
// (common/shaders/trace/intersect.glsl, as brute force). Shadow rays (RH_SHADOW): any hit blocks the light. Closest
// hits: step 1 of rh_closest.glsl. Each work group adds its exact tests to rh_info once (the CPU adds the batch's to
// the pipeline's test counter, rh_fold.comp mode 6); only the heatmap needs one atomic per test, on the ray's pixel.
#include "rh_common.glsl"
#include "rh_triangles.glsl"
#include "rh_pairs.glsl"
#include "common/shaders/trace/opacity.glsl"
#include "rh_info.glsl"
#ifndef RH_SHADOW
#include "rh_closest.glsl"
#endif

layout(local_size_x = 64) in;

#ifdef RH_SHADOW
layout(std430, binding = WF_BINDING_RESULTS) buffer Occluded { uint rh_occluded[]; };
#endif

uniform uint rh_group_first;    // wf_rays_in index of the group's ray 0
uniform uint rh_batch_first;    // wf_rays_in index of the batch's ray 0 (results and state are per batch ray)
uniform uint rh_sphere_test;    // 1: the sphere test first (--sphere-test on); 0: no sphere test
uniform uint rh_box_test;       // 1: then the box test (--box-test on); 0: no box test
#ifndef RH_SHADOW
uniform uint rh_hit_room;       // the hit list's entries (a speculative batch marks a hit past them)
#endif

// The group's leaf pairs, box tests and exact tests, 8-bit fields of one word (64 pairs a group), so that a pair adds
// its counts with one shared atomic instead of three, as in rh_cull.comp (04's README, "The traversal").
shared uint rh_group_counts;
#define RH_COUNT_LEAF 1u
#define RH_COUNT_BOX (1u << 8)
#define RH_COUNT_EXACT (1u << 16)

void main() {
    if (gl_LocalInvocationIndex == 0u) rh_group_counts = 0u;
    barrier();
    const uint i = rt_global_index();
    const uvec2 p = i < rh_chunk_count() && !rh_overflowed() ? rh_pair(i) : uvec2(0xffffffffu, 0u);
    if (rh_ray_level(p.x) == 0u && rh_is_triangle(p.y)) {
        uint counts = RH_COUNT_LEAF;
        const uint ray_index = rh_group_first + rh_ray_index(p.x);
        const uint triangle = p.y & ~RH_TRIANGLE_FLAG;
        const WavefrontRay r = wf_rays_in[ray_index];
        const uint slot = ray_index - rh_batch_first;
        vec3 a, b, c;
        rh_load_triangle(triangle, a, b, c);
        bool may_hit =
            rh_sphere_test == 0u || rh_ray_may_hit(r.origin, r.direction, r.tmax, rh_triangle_sphere(a, b, c));
        if (may_hit && rh_box_test == 1u) {
            counts += RH_COUNT_BOX;
            may_hit = rh_ray_box_may_hit(r.origin, r.direction, r.tmax, a, b, c);
        }
        if (may_hit) {
            counts += RH_COUNT_EXACT;
            float t, u, v;
            const bool hit =
                intersect_triangle(RT_INTERSECT_METHOD, wf_ray(r), a, b, c, t, u, v) && cutout_opaque(triangle, u, v);
#ifdef RH_SHADOW
            if (hit) rh_occluded[slot] = 1u;
#else
            if (hit) {
                const uint bits = floatBitsToUint(t);
                const uint before = atomicMin(rh_state[slot].min_t, bits);
                if (rh_near(t, min(before, bits))) {
                    const uint at = atomicAdd(rh_info[RH_INFO_HITS], 1u);
                    if (at < rh_hit_room)
                        rh_hits[at] = uvec4(slot, triangle, bits, 0u);
                    else
                        rh_mark_overflow();
                }
            }
#endif
#if defined(COUNT_TESTS) && defined(RECORD_TESTS_PER_PIXEL)
            if (r.pixel != WF_NO_PIXEL) atomicAdd(wf_tests_per_pixel[r.pixel], 1u);
#endif
#if defined(COUNT_TESTS) && defined(WATCH_PIXEL)
            wf_watch(r.pixel, r.path, wf_kind_light(wf_kind(r), r.light, r.light_sample), 1u, 1u);   // --pixel: an exact test, a leaf pair
        } else {
            wf_watch(r.pixel, r.path, wf_kind_light(wf_kind(r), r.light, r.light_sample), 0u, 1u);   // a leaf pair a cheap test culled
#endif
        }
        atomicAdd(rh_group_counts, counts);
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        const uint c = rh_group_counts;
        rh_add64(RH_INFO_EXACT, (c >> 16) & 0xffu);
        rh_add64(RH_INFO_LEAF_PAIRS, c & 0xffu);
        rh_add64(RH_INFO_BOX_TESTS, (c >> 8) & 0xffu);
    }
}
