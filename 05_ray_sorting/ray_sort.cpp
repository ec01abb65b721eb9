#include "ray_sort.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/gpu/gl/bindings.h"

namespace rt {

namespace {

constexpr const char* kShaders = "05_ray_sorting/shaders/";

// The passes' bindings (shaders/ray_sort.glsl: RS_BINDING_0..6): the common primitives' points 8..14.
constexpr unsigned kBinding[] = {gpu::kBindingScanIn,        gpu::kBindingScanOut,       gpu::kBindingScanSums,
                                 gpu::kBindingCompactFlags,  gpu::kBindingCompactOffsets, gpu::kBindingCompactValues,
                                 gpu::kBindingCompactOut};

void bind_uints(const gpu::Buffer& b, unsigned slot, std::size_t n) {
    b.bind_range(kBinding[slot], 0, std::max<std::size_t>(n, 1) * 4);
}

void barrier() { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT); }

gpu::Program pass(const char* name) { return gpu::Program::compute(std::string(kShaders) + name); }

}  // namespace

RaySorter::RaySorter()
    : keys_pass_(pass("ray_keys.comp")), heads_pass_(pass("chunk_heads.comp")), chunks_pass_(pass("chunks.comp")),
      tally_pass_(pass("chunk_tally.comp")), sizes_pass_(pass("chunk_sizes.comp")),
      skeleton_pass_(pass("skeleton.comp")), total_(sizeof(std::uint32_t)), tally_(kTallySlots * sizeof(std::uint64_t)) {
    reset_tally();
}

std::size_t RaySorter::chunk_count() {
    ++syncs;
    return total_.download_value<std::uint32_t>();
}

std::array<std::uint64_t, RaySorter::kTallySlots> RaySorter::chunk_tally() {
    ++syncs;
    const std::vector<std::uint32_t> words = tally_.download<std::uint32_t>(2 * kTallySlots);
    std::array<std::uint64_t, kTallySlots> sums{};
    for (std::size_t s = 0; s < kTallySlots; ++s) sums[s] = words[2 * s] | std::uint64_t(words[2 * s + 1]) << 32;
    return sums;
}

void RaySorter::reset_tally() {
    tally_.clear_u32(0);
    syncs = 0;
}

void RaySorter::sort(const gpu::Buffer& rays, std::size_t first, std::size_t count, gpu::Buffer& order) {
    compute_keys(rays, first, count);
    sort_keys(keys_, count, layout.sort_bits, std::uint32_t(first), order);
}

void RaySorter::compute_keys(const gpu::Buffer& rays, std::size_t first, std::size_t count) {
    gpu::check_storage_block("RaySorter keys", count);
    keys_.reserve(std::max<std::size_t>(count, 1) * 4);
    if (count == 0) return;
    const gpu::Program& p = keys_pass_;
    p.set("rs_box_min", layout.box_min);
    p.set("rs_origin_scale", layout.origin_scale);
    glProgramUniform3ui(p.id(), p.uniform_location("rs_origin_bits"), layout.origin_bits.x, layout.origin_bits.y,
                        layout.origin_bits.z);
    p.set("rs_direction_bits", layout.direction_bits);
    p.set("rs_origin_total", layout.origin_total);
    p.set("rs_direction_total", layout.direction_total);
    p.set("rs_hash_drop", layout.hash_drop);
    p.set("rs_hash_bits", layout.hash_bits);
    p.set("rs_group_count", layout.group_count);
    p.set("rs_direction_major", layout.direction_major ? 1u : 0u);
    p.set("rs_first", unsigned(first));
    p.set("rs_count", unsigned(count));
    rays.bind_range(kBinding[0], 0, (first + count) * sizeof(gpu::WavefrontRay));
    bind_uints(keys_, 1, count);
    p.dispatch_threads(count);
    barrier();
    gpu::check_gl("RaySorter: keys");
}

void RaySorter::sort_keys(const gpu::Buffer& keys, std::size_t n, unsigned sort_bits, std::uint32_t first,
                          gpu::Buffer& order) {
    gpu::check_storage_block("RaySorter keys", n);
    if (tally_slot >= kTallySlots) throw std::out_of_range("RaySorter: tally slot " + std::to_string(tally_slot));
    const std::size_t bytes = std::max<std::size_t>(n, 1) * 4;
    order.reserve(bytes);
    if (n == 0) {
        total_.clear_u32(0);
        return;
    }
    for (gpu::Buffer* b : {&heads_, &chunk_of_, &chunk_keys_, &chunk_ids_, &chunk_bases_, &chunk_ends_, &sizes_})
        b->reserve(bytes);

    // Compression: head flags, their exclusive scan (the chunk numbers and, as the total, the chunk count), chunks.
    heads_pass_.set("rs_count", unsigned(n));
    bind_uints(keys, 0, n);
    bind_uints(heads_, 1, n);
    heads_pass_.dispatch_threads(n);
    barrier();
    scan_.exclusive(heads_, chunk_of_, n, &total_);
    chunks_pass_.set("rs_count", unsigned(n));
    const gpu::Buffer* chunk_inputs[] = {&keys, &heads_, &chunk_of_, &chunk_keys_, &chunk_ids_, &chunk_bases_,
                                         &chunk_ends_};
    for (unsigned slot = 0; slot < 7; ++slot) bind_uints(*chunk_inputs[slot], slot, n);
    chunks_pass_.dispatch_threads(n);
    barrier();
    bind_uints(total_, 0, 1);
    tally_.bind_range(kBinding[1], 0, kTallySlots * sizeof(std::uint64_t));
    tally_pass_.set("rs_slot", unsigned(tally_slot));
    tally_pass_.dispatch(1);
    barrier();

    // Sorting: the chunks by key, their ids along. Only the GPU knows how many chunks there are (total_); the
    // passes from here on are sized for n, a bound of it, and read the count there.
    radix_.sort(chunk_keys_, chunk_ids_, n, total_, sort_bits);

    // Decompression: sizes in sorted order, where each chunk starts, the skeleton, the segmented scan. Sizes past
    // the chunk count are not written, and the exclusive scan's first chunk-count entries do not read them.
    bind_uints(chunk_ids_, 0, n);
    bind_uints(chunk_bases_, 1, n);
    bind_uints(chunk_ends_, 2, n);
    bind_uints(sizes_, 3, n);
    bind_uints(total_, 5, 1);
    sizes_pass_.dispatch_threads(n);
    barrier();
    scan_.exclusive(sizes_, sizes_, n);   // in place: sizes_ now holds the starts
    order.clear_u32(1);                   // the skeleton is built in `order`, scanned in place
    heads_.clear_u32(0);
    barrier();
    skeleton_pass_.set("rs_first", unsigned(first));
    bind_uints(chunk_ids_, 0, n);
    bind_uints(chunk_bases_, 1, n);
    bind_uints(sizes_, 2, n);
    bind_uints(order, 3, n);
    bind_uints(heads_, 4, n);
    bind_uints(total_, 5, 1);
    skeleton_pass_.dispatch_threads(n);
    barrier();
    scan_.segmented_inclusive(order, heads_, order, n);
    gpu::check_gl("RaySorter: sort_keys");
}

}  // namespace rt
