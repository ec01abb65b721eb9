#version 450 core
// Trace pass, per-ray traversal: one thread per ray of wf_rays_in[wf_input_first ..][0 .. wf_input_count)
// (reflection and refraction rays, or primary rays in stages that trace them). The closest hit goes to
// wf_trace_results[i]; trace_collect.comp then makes the hit queue. The stage's traversal (trace_closest) is included
// before this file by rt::gpu::Wavefront. A stage with a batch traversal (Traversal::trace_batch) replaces this pass
// and writes the same results.
#include "wavefront.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = WF_BINDING_RESULTS) writeonly buffer WfTraceResults {
    WavefrontTraceResult wf_trace_results[];
};

void main() {
    const uint i = rt_global_index();
    if (i >= wf_input_count) return;
    const WavefrontRay r = wf_rays_in[wf_input_first + i];
    Hit hit;
    WavefrontTraceResult result;
    result.triangle = -1;
    result.t = 0.0;
    result.u = 0.0;
    result.v = 0.0;
    if (trace_closest(wf_ray(r), hit)) {
        result.triangle = hit.triangle;
        result.t = hit.t;
        result.u = hit.u;
        result.v = hit.v;
    }
    wf_trace_results[i] = result;
    wf_flush_ray_tests(r);
    wf_check_loop_budget();
}
