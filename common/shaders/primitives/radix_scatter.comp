#version 450 core
// Radix sort, step 3 of a pass: every key (and its value) goes to its place. `offsets` is the exclusive scan of the
// counts (radix_count.comp): offsets[count_index(d, tile)] is where the tile's first key with digit d goes. Within
// the tile, a key goes after the tile's earlier keys of the same digit, so equal digits keep their order (stable).
// With few tiles (scan_here = 1, at most SCATTER_SCAN_TILES) the buffer holds the counts themselves, and each work
// group sums the few it needs (tile_start): the scan's dispatch is saved, the places are the same.
//
// Thread t owns the SORT_ITEMS consecutive keys from tile * SORT_TILE + t * SORT_ITEMS. rank[d][t] counts thread
// t's keys of digit d; one exclusive scan of the whole rank table (digit-major) turns it into the number of the
// tile's keys that come first: all keys of smaller digits, plus the keys of digit d of threads before t.
//
// The output is written through a window [out_begin, out_end) of it (a range of at most
// GL_MAX_SHADER_STORAGE_BLOCK_SIZE bytes, bound from out_begin): the host runs this once per window when the
// arrays are larger than one storage block, and each run writes the keys that land in its window. A tile none of
// whose keys land there returns at once: with digit-major offsets, the tile's keys of digit d go to
// [offsets[count_index(d, tile)], offsets[count_index(d, tile) + 1]) (the next entry; the total n after the last).
#include "common/shaders/bindings.glsl"
#include "common/shaders/compute.glsl"
#include "radix_common.glsl"

layout(local_size_x = SORT_THREADS) in;

layout(std430, binding = RT_BINDING_SORT_KEYS_IN) readonly buffer KeysIn { uint keys_in[]; };
layout(std430, binding = RT_BINDING_SORT_VALUES_IN) readonly buffer ValuesIn { uint values_in[]; };
layout(std430, binding = RT_BINDING_SORT_COUNTS) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = RT_BINDING_SORT_KEYS_OUT) writeonly buffer KeysOut { uint keys_out[]; };
layout(std430, binding = RT_BINDING_SORT_VALUES_OUT) writeonly buffer ValuesOut { uint values_out[]; };

uniform uint out_begin;
uniform uint out_end;
uniform uint total;                       // all elements (every window): the end of the last digit's last tile
                                          // (the GPU's count instead, with count_from_buffer)
uniform uint scan_here;                   // 1: `offsets` holds the counts, unscanned (tiles <= SCATTER_SCAN_TILES)

shared uint rank[RADIX * SORT_THREADS];   // rank[d * SORT_THREADS + t]
shared uint thread_total[SORT_THREADS];
shared uint digit_base[RADIX];            // offsets[...] minus the tile-local start of the digit
shared uint digit_total[RADIX];           // scan_here: keys of each digit in all tiles
shared bool lands_in_window;

// scan_here: where the tile's first key of digit d goes (what the scan would have written at count_index(d, tile)):
// the keys of all smaller digits, plus this digit's keys in the tiles before. Needs digit_total.
uint tile_start(uint d, uint tile) {
    uint start = 0u;
    for (uint smaller = 0u; smaller < d; ++smaller) start += digit_total[smaller];
    for (uint before = 0u; before < tile; ++before) start += offsets[count_index(d, before)];
    return start;
}

void main() {
    const uint tile = rt_group_index();
    const uint t = gl_LocalInvocationID.x;
    const uint first = tile * SORT_TILE + t * SORT_ITEMS;
    const uint count = window_count();
    const uint end_of_all = count_from_buffer != 0u ? min(sort_count, total) : total;

    if (t == 0u) lands_in_window = false;
    if (scan_here == 1u && t < RADIX) {
        uint sum = 0u;
        for (uint k = 0u; k < tiles; ++k) sum += offsets[count_index(t, k)];
        digit_total[t] = sum;
    }
    barrier();
    uint start = 0u;   // thread t < RADIX: where the tile's first key of digit t goes
    if (t < RADIX) {
        const uint i = count_index(t, tile);
        uint begin, end;
        if (scan_here == 1u) {
            begin = tile_start(t, tile);
            end = begin + offsets[i];
        } else {
            begin = offsets[i];
            end = i + 1u < RADIX * tiles ? offsets[i + 1u] : end_of_all;
        }
        start = begin;
        if (begin < end && begin < out_end && end > out_begin) lands_in_window = true;
    }
    barrier();
    if (!lands_in_window) return;

    for (uint d = 0u; d < RADIX; ++d) rank[d * SORT_THREADS + t] = 0u;
    for (uint k = 0u; k < SORT_ITEMS; ++k)
        if (first + k < count) rank[((keys_in[first + k] >> shift) & mask) * SORT_THREADS + t] += 1u;
    barrier();

    // Exclusive scan of the RADIX * SORT_THREADS table: each thread sums RADIX consecutive entries, the threads'
    // totals are scanned (Hillis-Steele, inclusive), and each thread rewrites its entries as running sums.
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
    if (t < RADIX) digit_base[t] = start - rank[t * SORT_THREADS];
    barrier();

    // Only thread t touches column t of rank from here on.
    for (uint k = 0u; k < SORT_ITEMS; ++k) {
        if (first + k >= count) break;
        const uint key = keys_in[first + k];
        const uint d = (key >> shift) & mask;
        const uint destination = digit_base[d] + rank[d * SORT_THREADS + t];
        rank[d * SORT_THREADS + t] += 1u;
        if (destination >= out_begin && destination < out_end) {
            keys_out[destination - out_begin] = key;
            values_out[destination - out_begin] = values_in[first + k];
        }
    }
}
