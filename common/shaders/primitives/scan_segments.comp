#version 450 core
// Last step of the segmented inclusive scan (Scan::segmented_inclusive): with sums[i] = in[0] + ... + in[i] and
// head[i] = the index of the last head flag at or before i (0 when none), the sum of i's segment is
// sums[i] - sums[head[i] - 1]. The uint arithmetic wraps, so the difference is exact however large the sums grow.
#include "common/shaders/bindings.glsl"
#include "common/shaders/compute.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = RT_BINDING_SCAN_IN) readonly buffer Sums { uint sums[]; };
layout(std430, binding = RT_BINDING_SCAN_SUMS) readonly buffer Heads { uint heads[]; };
layout(std430, binding = RT_BINDING_SCAN_OUT) writeonly buffer ScanOut { uint scan_out[]; };

uniform uint n;

void main() {
    const uint i = rt_global_index();
    if (i >= n) return;
    const uint head = heads[i];
    scan_out[i] = sums[i] - (head > 0u ? sums[head - 1u] : 0u);
}
