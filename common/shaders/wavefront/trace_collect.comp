#version 450 core
// After a trace pass: ray i of the pass with a hit becomes hit slot i (flag 1), so compaction keeps the hits in the
// order of their rays; a ray that leaves the scene brings the background or the environment in its direction
// (environment.glsl), weighted by its path weight.
#include "wavefront.glsl"
#include "common/shaders/trace/scene.glsl"
#include "common/shaders/trace/environment.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = WF_BINDING_RESULTS) readonly buffer WfTraceResults {
    WavefrontTraceResult wf_trace_results[];
};

void main() {
    const uint i = rt_global_index();
    if (i >= wf_input_count) return;
    const WavefrontRay r = wf_rays_in[wf_input_first + i];
    const WavefrontTraceResult result = wf_trace_results[i];
    if (result.triangle >= 0) {
        WavefrontHit e;
        e.ray = r;
        e.triangle = result.triangle;
        e.t = result.t;
        e.u = result.u;
        e.v = result.v;
        wf_hits[i] = e;
        wf_flags[i] = 1u;
    } else {
        wf_accumulate(r.pixel, r.weight * rt_miss_radiance(r.direction));   // environment.glsl
        wf_flags[i] = 0u;
    }
}
