#version 450 core
// Second half of a multi-level scan: adds the scanned block sums back, data[i] += sums[block of i] (max() instead of
// + with SCAN_MAX).
#include "common/shaders/bindings.glsl"
#include "common/shaders/compute.glsl"
#include "scan_common.glsl"

layout(local_size_x = SCAN_THREADS) in;

layout(std430, binding = RT_BINDING_SCAN_OUT) buffer ScanOut { uint scan_out[]; };
layout(std430, binding = RT_BINDING_SCAN_SUMS) readonly buffer ScanSums { uint scan_sums[]; };

uniform uint n;            // elements of this window (bound from its first element)
uniform uint block_base;   // the window's first block

void main() {
    const uint block = rt_group_index();
    if (block_base + block == 0u) return;   // the first block's offset is 0
    const uint add = scan_sums[block_base + block];
    const uint base = block * SCAN_BLOCK + gl_LocalInvocationID.x;
    if (base < n) scan_out[base] = SCAN_OP(scan_out[base], add);
    if (base + SCAN_THREADS < n) scan_out[base + SCAN_THREADS] = SCAN_OP(scan_out[base + SCAN_THREADS], add);
}
