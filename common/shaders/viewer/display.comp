#version 450 core
// The viewer's display pass (common/gpu/viewer/window_presenter.cpp): turns one band of the wavefront's image, the
// float sums over the samples, into the window's RGBA8 texture without a read-back, encoded exactly as a PNG file
// stores it.
//   linear = sum / samples, times 2^EV (--exposure; then the tone curve), then sRGB 8-bit.
// The sRGB encoding is a table lookup, not pow(): display_threshold[k] is the smallest linear value that to_srgb8()
// (common/app/image.cpp) encodes as k or more, computed on the CPU, so each byte equals the file's bit for bit.
#include "common/shaders/bindings.glsl"
#include "common/shaders/compute.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = RT_BINDING_SCAN_IN) readonly buffer DisplaySums { vec4 display_sums[]; };
layout(std430, binding = RT_BINDING_SCAN_OUT) readonly buffer DisplayThresholds { float display_threshold[256]; };
layout(rgba8, binding = 0) writeonly uniform image2D display_image;

uniform uint display_first;      // the band's first pixel in the image (row-major from the top)
uniform uint display_count;      // its pixels
uniform uint display_width;
uniform uint display_height;
uniform float display_samples;
uniform bool display_expose;     // false: exposure 0 without a tone curve (the values as they are)
uniform float display_scale;     // 2^EV
uniform bool display_aces;

const float FLT_MAX = 3.402823466e38;

// Narkowicz's ACES fit, as aces_curve() in common/app/exposure.cpp.
float aces(float x) {
    x = max(x, 0.0);
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

// The largest k with display_threshold[k] <= v (0 for none, NaN or Inf, as to_srgb8 writes 0 for those).
float encode(float v) {
    if (isnan(v) || isinf(v)) return 0.0;
    uint k = 0u;
    for (uint step = 128u; step > 0u; step >>= 1u)
        if (k + step <= 255u && display_threshold[k + step] <= v) k += step;
    return float(k) / 255.0;
}

void main() {
    const uint i = rt_global_index();
    if (i >= display_count) return;
    vec3 v = display_sums[i].rgb / display_samples;
    if (display_expose) {
        v = min(v * display_scale, vec3(FLT_MAX));
        if (display_aces) v = vec3(aces(v.r), aces(v.g), aces(v.b));
    }
    const uint pixel = display_first + i;
    const uint x = pixel % display_width, y = pixel / display_width;
    // GL rows run bottom-up.
    imageStore(display_image, ivec2(x, display_height - 1u - y), vec4(encode(v.r), encode(v.g), encode(v.b), 1.0));
}
