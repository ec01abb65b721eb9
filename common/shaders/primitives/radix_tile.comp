#version 450 core
// Radix sort of an array of at most one tile (SORT_TILE keys) by one work group, every pass in one dispatch: arrays
// this short would take two dispatches a pass (radix_count.comp, radix_scatter.comp), and on llvmpipe a dispatch
// costs tens of microseconds whatever it holds (radix_sort.h). Each pass is radix_scatter.comp's with a single tile:
// the rank table (digits x threads), counted and scanned digit-major, gives each key its place directly (the tile's
// keys of smaller digits, plus those of its digit in earlier threads' runs, plus those earlier in its own run), so
// the order is the same as the multi-tile sort's (stable).
//
// The passes go back and forth between the caller's buffers (A: the *_IN bindings) and the scratch ones (B: *_OUT),
// A -> B -> A ...; after an odd number of passes the group copies B back to A, so the result is always in A.
// Between passes, memoryBarrierBuffer() and barrier() make one pass's writes visible to the whole group (a single
// group reads and writes the arrays: no other group can see them half-written).
#include "common/shaders/bindings.glsl"
#include "common/shaders/compute.glsl"
#include "radix_common.glsl"

layout(local_size_x = SORT_THREADS) in;

layout(std430, binding = RT_BINDING_SORT_KEYS_IN) coherent buffer KeysA { uint keys_a[]; };
layout(std430, binding = RT_BINDING_SORT_VALUES_IN) coherent buffer ValuesA { uint values_a[]; };
layout(std430, binding = RT_BINDING_SORT_KEYS_OUT) coherent buffer KeysB { uint keys_b[]; };
layout(std430, binding = RT_BINDING_SORT_VALUES_OUT) coherent buffer ValuesB { uint values_b[]; };

uniform uint key_bits;   // 1..32: ceil(key_bits / RADIX_BITS) passes, the last one over the bits left

shared uint rank[RADIX * SORT_THREADS];   // rank[d * SORT_THREADS + t]
shared uint thread_total[SORT_THREADS];

void main() {
    const uint t = gl_LocalInvocationID.x;
    const uint first = t * SORT_ITEMS;   // thread t's run of consecutive keys
    const uint count = window_count();   // n, or the GPU's count
    const uint passes = (key_bits + RADIX_BITS - 1u) / RADIX_BITS;
    for (uint p = 0u; p < passes; ++p) {
        const uint digit_shift = p * RADIX_BITS;
        const uint digit_mask = (1u << min(RADIX_BITS, key_bits - digit_shift)) - 1u;
        const bool from_b = (p & 1u) == 1u;

        for (uint d = 0u; d < RADIX; ++d) rank[d * SORT_THREADS + t] = 0u;
        for (uint k = 0u; k < SORT_ITEMS; ++k) {
            if (first + k >= count) break;
            const uint key = from_b ? keys_b[first + k] : keys_a[first + k];
            rank[((key >> digit_shift) & digit_mask) * SORT_THREADS + t] += 1u;
        }
        barrier();

        // Exclusive scan of the table, as in radix_scatter.comp: each thread sums RADIX consecutive entries, the
        // threads' totals are scanned (Hillis-Steele, inclusive), and each thread rewrites its entries as running sums.
        uint sum = 0u;
        for (uint j = 0u; j < RADIX; ++j) sum += rank[t * RADIX + j];
        thread_total[t] = sum;
        barrier();
        for (uint step = 1u; step < SORT_THREADS; step <<= 1) {
            const uint add = t >= step ? thread_total[t - step] : 0u;
            barrier();
            thread_total[t] += add;
            barrier();
        }
        uint running = thread_total[t] - sum;   // exclusive
        for (uint j = 0u; j < RADIX; ++j) {
            const uint c = rank[t * RADIX + j];
            rank[t * RADIX + j] = running;
            running += c;
        }
        barrier();

        // Only thread t touches column t of rank from here on: each key to its place in the other pair of buffers.
        for (uint k = 0u; k < SORT_ITEMS; ++k) {
            if (first + k >= count) break;
            const uint i = first + k;
            const uint key = from_b ? keys_b[i] : keys_a[i];
            const uint value = from_b ? values_b[i] : values_a[i];
            const uint d = (key >> digit_shift) & digit_mask;
            const uint destination = rank[d * SORT_THREADS + t];
            rank[d * SORT_THREADS + t] += 1u;
            if (from_b) {
                keys_a[destination] = key;
                values_a[destination] = value;
            } else {
                keys_b[destination] = key;
                values_b[destination] = value;
            }
        }
        memoryBarrierBuffer();
        barrier();
    }
    if ((passes & 1u) == 1u) {   // the last pass wrote B
        for (uint k = 0u; k < SORT_ITEMS; ++k) {
            const uint i = k * SORT_THREADS + t;
            if (i < count) {
                keys_a[i] = keys_b[i];
                values_a[i] = values_b[i];
            }
        }
    }
}
