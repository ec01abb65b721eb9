#version 450 core
// The closest-hit bookkeeping of a batch of rays (rh_closest.glsl), one mode per dispatch:
//   0 init     per ray: no hit yet;
//   1 select   per listed hit: within the tie range of its ray's closest t and not folded yet -> the lowest such
//              triangle becomes the ray's `next` (atomicMin); rh_info[2] = 1 if any ray has one. Nothing in a
//              speculative batch that ran out of room (rh_info.glsl: RH_INFO_OVERFLOW): its rounds change nothing,
//              and the fold starts over once its groups were traced again;
//   2 step     per ray: folds `next` as brute force would (tmax = the kept hit's t; replaced only when strictly
//              closer), counting the test; a ray without a `next` is left as it is, so a round more than needed
//              changes nothing (the CPU reads the flag only every few rounds);
//   3 resolve  per ray: the result (WavefrontTraceResult; triangle -1 for a miss);
//   4 prune    per listed hit: rh_keep[i] = 1 if it is still within the tie range (hits left behind by a closer one
//              are dropped from the list when it fills up: they can no longer matter).
//   5 scatter  per listed hit: the kept ones to rh_hits_out[offset] (rh_keep bound to the scan of mode 4's flags).
// (The leaves' exact tests reach the pipeline's test counters through rh_tally.comp.)
#include "rh_common.glsl"
#include "rh_triangles.glsl"
#include "rh_closest.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = WF_BINDING_RESULTS) writeonly buffer Results { WavefrontTraceResult rh_results[]; };
layout(std430, binding = RH_BINDING_OFFSETS) buffer Keep { uint rh_keep[]; };
layout(std430, binding = RH_BINDING_PAIRS) writeonly buffer HitsOut { uvec4 rh_hits_out[]; };

uniform uint rh_mode;
uniform uint rh_count;
uniform uint rh_batch_first;

void main() {
    const uint i = rt_global_index();
    if (i >= rh_count) return;
    if (rh_mode == 1u && (i >= rh_info[RH_INFO_HITS] || rh_overflowed())) return;   // indirect: the list's length
    if (rh_mode == 0u) {
        rh_state[i] = RhRayState(0x7f800000u, 0u, 0xffffffffu, -1, RT_INFINITY, 0.0, 0.0, 0u);
    } else if (rh_mode == 1u) {
        const uvec4 h = rh_hits[i];
        const RhRayState s = rh_state[h.x];
        if (h.y >= s.cursor && rh_near(uintBitsToFloat(h.z), s.min_t)) {
            atomicMin(rh_state[h.x].next, h.y);
            rh_info[2] = 1u;
        }
    } else if (rh_mode == 2u) {
        RhRayState s = rh_state[i];
        if (s.next == 0xffffffffu) return;
        const WavefrontRay r = wf_rays_in[rh_batch_first + i];
        Ray ray = wf_ray(r);
        if (s.triangle >= 0) ray.tmax = s.t;
        float t, u, v;
        if (rh_intersect(ray, s.next, t, u, v) && t < s.t) {
            s.triangle = int(s.next);
            s.t = t;
            s.u = u;
            s.v = v;
        }
        s.cursor = s.next + 1u;
        s.next = 0xffffffffu;
        rh_state[i] = s;
        atomicAdd(rh_info[4u + wf_kind(r)], 1u);
        wf_count_tests(1u);
        wf_flush_ray_tests(r);
    } else if (rh_mode == 3u) {
        const RhRayState s = rh_state[i];
        WavefrontTraceResult result;
        result.triangle = s.triangle;
        result.t = s.triangle >= 0 ? s.t : 0.0;
        result.u = s.triangle >= 0 ? s.u : 0.0;
        result.v = s.triangle >= 0 ? s.v : 0.0;
        rh_results[i] = result;
    } else if (rh_mode == 4u) {
        const uvec4 h = rh_hits[i];
        rh_keep[i] = rh_near(uintBitsToFloat(h.z), rh_state[h.x].min_t) ? 1u : 0u;
    } else {
        const uvec4 h = rh_hits[i];   // rh_keep holds the exclusive scan of mode 4's flags now
        if (rh_near(uintBitsToFloat(h.z), rh_state[h.x].min_t)) rh_hits_out[rh_keep[i]] = h;
    }
}
