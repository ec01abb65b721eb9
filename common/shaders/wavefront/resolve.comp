#version 450 core
// End of a sample: adds each pixel's fixed-point radiance to the float sum over samples and clears it for the
// next sample. One thread per pixel, no atomics, so the sum is the same on every run.
#include "wavefront.glsl"

layout(local_size_x = 64) in;

void main() {
    const uint pixel = rt_global_index();
    if (pixel >= uint(wf_image_size.x * wf_image_size.y)) return;
    const vec3 sample_radiance = vec3(wf_radiance[3u * pixel], wf_radiance[3u * pixel + 1u],
                                      wf_radiance[3u * pixel + 2u]) / WF_FIXED_SCALE;
    wf_image[pixel].rgb += sample_radiance;
    wf_radiance[3u * pixel] = 0;
    wf_radiance[3u * pixel + 1u] = 0;
    wf_radiance[3u * pixel + 2u] = 0;
}
