#version 450 core
// After a shadow pass: the light's contribution, carried in the ray's weight, goes to the pixel when nothing blocks
// the ray.
#include "wavefront.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = WF_BINDING_RESULTS) readonly buffer WfOccluded { uint wf_occluded[]; };

void main() {
    const uint i = rt_global_index();
    if (i >= wf_input_count) return;
    if (wf_occluded[i] == 0u) {
        const WavefrontRay r = wf_rays_in[wf_input_first + i];
        wf_accumulate(r.pixel, r.weight);
    }
}
