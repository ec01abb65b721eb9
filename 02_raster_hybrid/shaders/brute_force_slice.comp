#version 450 core
// Stage 02's traversal as a batch traversal (traversal.h: Traversal::trace_batch): brute force over a
// pass' whole queue, one slice of triangles [bf_slice_first, bf_slice_first + bf_slice_count) per dispatch. Each
// ray's result carries over from slice to slice (the closest hit so far, or whether it is already blocked), and the
// slices go in increasing triangle order, so the hits, ties and test counts are exactly those of one loop over all
// triangles (brute_force.glsl's trace_closest / trace_any). Why slices: a GPU invocation should not loop without
// bound; Mesa's llvmpipe even ends its loops silently after 65,535 iterations (docs/gpu.md, "Known limit"), so one
// loop over a 100,000-triangle scene cannot be traced there. ANY_HIT selects the shadow variant.
#include "brute_force.glsl"

layout(local_size_x = 64) in;

uniform uint bf_slice_first, bf_slice_count;

#ifdef ANY_HIT
layout(std430, binding = WF_BINDING_RESULTS) buffer BfOccluded { uint bf_occluded[]; };
#else
layout(std430, binding = WF_BINDING_RESULTS) buffer BfResults { WavefrontTraceResult bf_results[]; };
#endif

void main() {
    const uint i = rt_global_index();
    if (i >= wf_input_count) return;
    const WavefrontRay r = wf_rays_in[wf_input_first + i];
    const Ray ray = wf_ray(r);
    const WatertightRay w = watertight_ray(ray.direction);
    const uint first = bf_slice_first, end = bf_slice_first + bf_slice_count;
#ifdef ANY_HIT
    const bool blocked = first > 0u && bf_occluded[i] != 0u;   // by an earlier slice: no more tests
    bf_occluded[i] = blocked || any_hit_among(ray, w, first, end) ? 1u : 0u;
#else
    Hit hit = no_hit();
    if (first > 0u && bf_results[i].triangle >= 0) {
        hit.triangle = bf_results[i].triangle;
        hit.t = bf_results[i].t;
        hit.u = bf_results[i].u;
        hit.v = bf_results[i].v;
    }
    closest_hit_among(ray, w, first, end, hit);
    WavefrontTraceResult result;
    result.triangle = hit.triangle;
    result.t = hit.triangle >= 0 ? hit.t : 0.0;
    result.u = hit.triangle >= 0 ? hit.u : 0.0;
    result.v = hit.triangle >= 0 ? hit.v : 0.0;
    bf_results[i] = result;
#endif
    wf_flush_ray_tests(r);
    wf_check_loop_budget();
}
