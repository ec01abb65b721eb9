#version 450 core
// Exclusive (or inclusive) prefix sum of one block of SCAN_BLOCK uints per work group, by raking (Merrill & Grimshaw
// 2009; CUB's BlockScan): each of SCAN_RAKE_THREADS threads sums a run of SCAN_ITEMS consecutive elements in
// registers, one thread scans the runs' totals in shared memory, and each thread writes its run's prefixes from its
// run's start. Four barriers in all (the tree scan of Blelloch 1990 needs two per level of the block, 18 for 512),
// and the serial parts are what a SIMD core does best (on llvmpipe, a vector of lanes each walking its own run).
// Writes the block's total to scan_sums[block_base + block]; the host scans those sums recursively and adds them
// back (scan_add.comp). The arrays are bound from the window's first element (n elements); block_base is its first
// block. With `whole` = 1 one work group scans all n elements, block after block from a running total, and writes
// that total to scan_sums[block_base]: for short arrays (scan.h: kScanWhole), one dispatch instead of three.
// Defines: SCAN_FLAGS: scan (in != 0 ? 1 : 0) instead of in (stream compaction's flag scan).
//          SCAN_HEADS: scan (in != 0 ? i : 0), the index of each head flag (with SCAN_MAX: the segmented scan).
//          SCAN_MAX: the operator is max instead of + (scan_common.glsl: SCAN_OP).
//          SCAN_INCLUSIVE: out[i] includes in[i] (the block total and the sums are the same either way).
#include "common/shaders/bindings.glsl"
#include "common/shaders/compute.glsl"
#include "scan_common.glsl"

#define SCAN_RAKE_THREADS 64u
#define SCAN_ITEMS (SCAN_BLOCK / SCAN_RAKE_THREADS)   // 8 consecutive elements per thread
// One padding word after every run, so the threads' runs start in different banks (stride SCAN_ITEMS + 1).
#define SCAN_RUN_PAD(i) ((i) + (i) / SCAN_ITEMS)

layout(local_size_x = SCAN_RAKE_THREADS) in;

layout(std430, binding = RT_BINDING_SCAN_IN) readonly buffer ScanIn { uint scan_in[]; };
layout(std430, binding = RT_BINDING_SCAN_OUT) writeonly buffer ScanOut { uint scan_out[]; };
layout(std430, binding = RT_BINDING_SCAN_SUMS) writeonly buffer ScanSums { uint scan_sums[]; };

uniform uint n;
uniform uint block_base;
uniform uint whole;   // 1: one work group, every block of the window in turn (scan.h: kScanWhole)

shared uint tile[SCAN_BLOCK + SCAN_BLOCK / SCAN_ITEMS];
shared uint run_start[SCAN_RAKE_THREADS];
shared uint block_total;

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
    const uint t = gl_LocalInvocationID.x;
    const uint blocks = whole == 1u ? (n + SCAN_BLOCK - 1u) / SCAN_BLOCK : 1u;   // the same for every thread
    uint carry = 0u;   // whole: the total of the blocks before (0, the identity of + and of max over uints)
    for (uint b = 0u; b < blocks; ++b) {
        const uint block = whole == 1u ? b : rt_group_index();
        const uint base = block * SCAN_BLOCK;
        // Loads and stores go through shared memory so that neighbouring threads touch neighbouring words
        // (coalesced).
        for (uint k = 0u; k < SCAN_ITEMS; ++k) {
            const uint i = t + k * SCAN_RAKE_THREADS;
            tile[SCAN_RUN_PAD(i)] = load(base + i);
        }
        barrier();
        // The thread's run [t SCAN_ITEMS, (t + 1) SCAN_ITEMS): its total.
        uint run[SCAN_ITEMS];
        uint total = 0u;
        for (uint k = 0u; k < SCAN_ITEMS; ++k) {
            run[k] = tile[SCAN_RUN_PAD(t * SCAN_ITEMS + k)];
            total = SCAN_OP(total, run[k]);
        }
        run_start[t] = total;
        barrier();
        // The runs' totals, scanned by one thread (64 additions): each run's start, and the block's total.
        if (t == 0u) {
            uint sum = 0u;
            for (uint r = 0u; r < SCAN_RAKE_THREADS; ++r) {
                const uint x = run_start[r];
                run_start[r] = sum;
                sum = SCAN_OP(sum, x);
            }
            block_total = sum;
            if (whole == 0u) scan_sums[block_base + block] = sum;
        }
        barrier();
        uint sum = SCAN_OP(carry, run_start[t]);
        for (uint k = 0u; k < SCAN_ITEMS; ++k) {
#ifdef SCAN_INCLUSIVE
            sum = SCAN_OP(sum, run[k]);
            tile[SCAN_RUN_PAD(t * SCAN_ITEMS + k)] = sum;
#else
            tile[SCAN_RUN_PAD(t * SCAN_ITEMS + k)] = sum;
            sum = SCAN_OP(sum, run[k]);
#endif
        }
        carry = SCAN_OP(carry, block_total);
        barrier();
        for (uint k = 0u; k < SCAN_ITEMS; ++k) {
            const uint i = t + k * SCAN_RAKE_THREADS;
            if (base + i < n) scan_out[base + i] = tile[SCAN_RUN_PAD(i)];
        }
        if (whole == 1u) barrier();   // the tile and block_total are the next block's
    }
    if (whole == 1u && t == 0u) scan_sums[block_base] = carry;
}
