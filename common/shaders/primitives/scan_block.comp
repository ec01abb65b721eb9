#version 450 core
// Work-efficient exclusive prefix sum of one block of SCAN_BLOCK uints per work group (Blelloch 1990; GPU Gems 3,
// ch. 39): up-sweep (reduce) and down-sweep in shared memory, padded against bank conflicts. Writes the block's
// total to scan_sums[block_base + block]; the host scans those sums recursively and adds them back (scan_add.comp).
// The arrays are bound from the window's first element (n elements); block_base is its first block.
// Defines: SCAN_FLAGS: scan (in != 0 ? 1 : 0) instead of in (stream compaction's flag scan).
//          SCAN_HEADS: scan (in != 0 ? i : 0), the index of each head flag (with SCAN_MAX: the segmented scan).
//          SCAN_MAX: the operator is max instead of + (scan_common.glsl: SCAN_OP).
//          SCAN_INCLUSIVE: out[i] includes in[i] (the block total and the sums are the same either way).
#include "common/shaders/bindings.glsl"
#include "common/shaders/compute.glsl"
#include "scan_common.glsl"

layout(local_size_x = SCAN_THREADS) in;

layout(std430, binding = RT_BINDING_SCAN_IN) readonly buffer ScanIn { uint scan_in[]; };
layout(std430, binding = RT_BINDING_SCAN_OUT) writeonly buffer ScanOut { uint scan_out[]; };
layout(std430, binding = RT_BINDING_SCAN_SUMS) writeonly buffer ScanSums { uint scan_sums[]; };

uniform uint n;
uniform uint block_base;

shared uint temp[SCAN_BLOCK + (SCAN_BLOCK >> SCAN_LOG_BANKS)];

uint load(uint i) {
    if (i >= n) return 0u;
#if defined(SCAN_FLAGS)
    return scan_in[i] != 0u ? 1u : 0u;
#elif defined(SCAN_HEADS)
    return scan_in[i] != 0u ? block_base * SCAN_BLOCK + i : 0u;   // the index in the whole array
#else
    return scan_in[i];
#endif
}

void main() {
    const uint block = rt_group_index();
    const uint t = gl_LocalInvocationID.x;
    const uint base = block * SCAN_BLOCK;
    const uint ai = t, bi = t + SCAN_THREADS;
    const uint a_in = load(base + ai), b_in = load(base + bi);
    temp[SCAN_PAD(ai)] = a_in;
    temp[SCAN_PAD(bi)] = b_in;

    // Up-sweep: build partial sums in place up the tree.
    uint offset = 1u;
    for (uint d = SCAN_BLOCK >> 1; d > 0u; d >>= 1) {
        memoryBarrierShared();
        barrier();
        if (t < d) {
            const uint i = offset * (2u * t + 1u) - 1u;
            const uint j = offset * (2u * t + 2u) - 1u;
            temp[SCAN_PAD(j)] = SCAN_OP(temp[SCAN_PAD(j)], temp[SCAN_PAD(i)]);
        }
        offset <<= 1;
    }
    memoryBarrierShared();
    barrier();
    if (t == 0u) {
        scan_sums[block_base + block] = temp[SCAN_PAD(SCAN_BLOCK - 1u)];
        temp[SCAN_PAD(SCAN_BLOCK - 1u)] = 0u;
    }
    // Down-sweep: traverse back down, swapping and adding.
    for (uint d = 1u; d < SCAN_BLOCK; d <<= 1) {
        offset >>= 1;
        memoryBarrierShared();
        barrier();
        if (t < d) {
            const uint i = SCAN_PAD(offset * (2u * t + 1u) - 1u);
            const uint j = SCAN_PAD(offset * (2u * t + 2u) - 1u);
            const uint x = temp[i];
            temp[i] = temp[j];
            temp[j] = SCAN_OP(temp[j], x);
        }
    }
    memoryBarrierShared();
    barrier();
#ifdef SCAN_INCLUSIVE
    if (base + ai < n) scan_out[base + ai] = SCAN_OP(temp[SCAN_PAD(ai)], a_in);
    if (base + bi < n) scan_out[base + bi] = SCAN_OP(temp[SCAN_PAD(bi)], b_in);
#else
    if (base + ai < n) scan_out[base + ai] = temp[SCAN_PAD(ai)];
    if (base + bi < n) scan_out[base + bi] = temp[SCAN_PAD(bi)];
#endif
}
