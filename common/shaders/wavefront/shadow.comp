#version 450 core
// Shadow pass, per-ray traversal: one thread per shadow ray of wf_rays_in[wf_input_first ..][0 .. wf_input_count).
// Any hit before the light (t < tmax) blocks it, so the traversal may stop at the first hit it finds (trace_any):
// wf_occluded[i] = 1 if blocked. shadow_collect.comp then adds the unblocked lights. Compiled only when the scene
// calls for shadows, with the stage's traversal (which defines trace_any) included before this file by
// rt::gpu::Wavefront. A batch traversal (Traversal::trace_batch, traversal.h) replaces this pass.
#include "wavefront.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = WF_BINDING_RESULTS) writeonly buffer WfOccluded { uint wf_occluded[]; };

void main() {
    const uint i = rt_global_index();
    if (i >= wf_input_count) return;
    const WavefrontRay r = wf_rays_in[wf_input_first + i];
    wf_occluded[i] = trace_any(wf_ray(r)) ? 1u : 0u;
    wf_flush_ray_tests(r);
    wf_check_loop_budget();
}
