#version 450 core
// End of a sample: adds each pixel's fixed-point radiance (wf_accumulate) to the float sum over samples and clears it
// for the next sample. One thread per pixel of the band (wf_input_count pixels from wf_pixel_first), no atomics, so
// the sum is the same on every run. A channel whose sticky bit is set saturated: it reads WF_RADIANCE_MAX.
#include "wavefront.glsl"

layout(local_size_x = 64) in;

float wf_fixed_value(uint base) {
    const uint top = wf_radiance[base + 2u];
    if ((top & 0x80000000u) != 0u) return WF_RADIANCE_MAX;
    // Exact in double up to 2^53 units, then rounded once to float.
    const double v = double(top) * 4294967296.0LF + double(wf_radiance[base + 1u]) +
                     double(wf_radiance[base]) * (1.0LF / 4294967296.0LF);
    return float(v);
}

void main() {
    const uint pixel = rt_global_index();   // in the band
    if (pixel >= wf_input_count) return;
    const uint base = 9u * pixel;
    wf_image[pixel].rgb += vec3(wf_fixed_value(base), wf_fixed_value(base + 3u), wf_fixed_value(base + 6u));
    for (uint k = 0u; k < 9u; ++k) wf_radiance[base + k] = 0u;
}
