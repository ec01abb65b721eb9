#version 450 core
// Shadow pass: one thread per shadow ray. Any hit before the light (t < tmax) blocks it, so the traversal may stop
// at the first hit it finds (trace_any); when nothing blocks it, the light's contribution, carried in the ray's
// weight, goes to the pixel. Compiled only when the scene calls for shadows, with the stage's traversal (which
// defines trace_any) included before this file by rt::gpu::Wavefront.
#include "wavefront.glsl"

layout(local_size_x = 64) in;

void main() {
    const uint i = rt_global_index();
    if (i < wf_input_count) {
        const WavefrontRay r = wf_shadow_rays[i];
        if (!trace_any(wf_ray(r))) wf_accumulate(r.pixel, r.weight);
    }
    wf_flush_tests();
}
