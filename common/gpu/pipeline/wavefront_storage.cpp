// The Wavefront's storage (wavefront.h): how many hits or rays one batch holds under the storage block limit (the
// device's, Wavefront::max_storage_bytes or $RT_MAX_SSBO_BYTES), the image in bands of rows that fit one block, and
// the compaction that packs a pass' used slots into a queue.
#include "wavefront.h"

#include <algorithm>
#include <cstdlib>
#include <string>

#include "common/app/input_error.h"
#include "common/gpu/gl/bindings.h"
#include "wavefront_detail.h"

namespace rt::gpu {

using namespace wavefront_detail;

namespace {

std::size_t env_storage_limit() {
    const char* text = std::getenv("RT_MAX_SSBO_BYTES");
    if (!text || !*text) return 0;
    char* end = nullptr;
    const unsigned long long v = std::strtoull(text, &end, 10);
    if (*end != '\0' || v == 0) throw InputError("RT_MAX_SSBO_BYTES: expected a positive number of bytes");
    return std::size_t(v);
}

}  // namespace

std::size_t Wavefront::storage_block_limit() const {
    GLint64 gl_limit = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &gl_limit);
    std::size_t limit = gl_limit > 0 ? std::size_t(gl_limit) : std::size_t(128) << 20;
    if (max_storage_bytes > 0) limit = std::min(limit, max_storage_bytes);
    if (const std::size_t env = env_storage_limit(); env > 0) limit = std::min(limit, env);
    return limit;
}

// How many hits (or rays) one batch holds: every buffer a batch binds must fit the storage limit. Per hit of a
// batch: the hit (80 bytes), its hit slot, and its output slots (64 bytes per ray: reflection, refraction, with BLEND
// transparency, and at least one light's shadow rays, an area light's grid of them; more lights are shaded in several
// runs, see process_hits).
void Wavefront::size_batches() {
    storage_limit_ = storage_block_limit();
    // Per-pixel sums in bands of rows of tiles (the whole image when it fits); the test counts for the whole image.
    const std::size_t tile_row_bytes = kRadianceBytesPerPixel * std::size_t(settings_.width) * 8;
    const std::size_t tests_bytes = settings_.record_tests_per_pixel ? tests_words() * sizeof(std::uint32_t) : 0;
    if (tile_row_bytes > storage_limit_ || tests_bytes > storage_limit_)
        throw InputError("wavefront: a " + std::to_string(settings_.width) + "x" +
                         std::to_string(settings_.height) + " image needs " +
                         std::to_string(std::max(tile_row_bytes, tests_bytes)) +
                         " bytes of per-pixel storage in one block, more than the storage block limit of " +
                         std::to_string(storage_limit_) + " bytes (the device's, or RT_MAX_SSBO_BYTES)");
    band_tile_rows_ = storage_limit_ / tile_row_bytes;
    const std::size_t rays_per_hit = secondary_blocks().size() + (shadows_ ? light_cells_ : 0);
    const std::size_t per_hit = std::max({sizeof(WavefrontHit), rays_per_hit * sizeof(WavefrontRay)});
    batch_ = storage_limit_ / per_hit;
    if (batch_ < kTilePixels)
        throw InputError("wavefront: the storage block limit (" + std::to_string(storage_limit_) +
                         " bytes) cannot hold one 8x8 tile of rays");
}

// Packs the flagged slots of `slots` (n records of stride_uints) into `out`, keeping their order: an exclusive scan
// of the flags gives each used slot its place. Returns how many were used (one read-back).
std::uint32_t Wavefront::compact(const Buffer& slots, std::size_t n, unsigned stride_uints, Buffer& out) {
    offsets_.reserve(std::max<std::size_t>(n, 1) * sizeof(std::uint32_t));
    scan_.exclusive_flags(flags_, offsets_, n, &counts_, 0);
    std::uint32_t total = 0;
    counts_.download(&total, sizeof total);
    ++syncs_;
    scatter_slots(slots, n, stride_uints, total, out);
    return total;
}

// The used ones of n slots (flags_, scanned into offsets_; `total` of them) packed into `out`.
void Wavefront::scatter_slots(const Buffer& slots, std::size_t n, unsigned stride_uints, std::uint32_t total,
                              Buffer& out) {
    if (total == 0) return;
    out.reserve(std::size_t(total) * stride_uints * sizeof(std::uint32_t));
    flags_.bind(kBindingCompactFlags);
    offsets_.bind(kBindingCompactOffsets);
    slots.bind(kBindingCompactValues);
    out.bind(kBindingCompactOut);
    compact_.set("n", unsigned(n));
    compact_.set("stride", stride_uints);
    compact_.dispatch_threads(n * stride_uints);
    pass_barrier();
    check_gl("wavefront: compaction");
}

std::vector<RayRun> Wavefront::compact_blocks(std::size_t hits, const std::vector<SlotBlock>& blocks, Buffer& out) {
    std::vector<std::size_t> starts;   // each block's first slot
    std::size_t n = 0;
    for (const SlotBlock& b : blocks) starts.push_back(n), n += b.per_hit * hits;
    // The scan's total goes to word 0 of counts_, its value at each inner block boundary to the words after it: the
    // used slots before that block. All of them in one read-back.
    counts_.reserve(blocks.size() * sizeof(std::uint32_t));
    offsets_.reserve(std::max<std::size_t>(n, 1) * sizeof(std::uint32_t));
    scan_.exclusive_flags(flags_, offsets_, n, &counts_, 0);
    for (std::size_t b = 1; b < blocks.size(); ++b)
        offsets_.copy_to(counts_, sizeof(std::uint32_t), starts[b] * sizeof(std::uint32_t), b * sizeof(std::uint32_t));
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> words = counts_.download<std::uint32_t>(blocks.size());
    ++syncs_;
    const std::uint32_t total = words[0];
    std::vector<RayRun> runs;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        const std::uint32_t begin = b == 0 ? 0 : words[b], end = b + 1 < blocks.size() ? words[b + 1] : total;
        if (begin < end) runs.push_back({begin, end - begin, blocks[b].kind, blocks[b].light});
    }
    scatter_slots(ray_slots_, n, sizeof(WavefrontRay) / 4, total, out);
    return runs;
}

// The pixels of band b: the first one and how many (whole rows; the last band may be shorter).
std::pair<std::size_t, std::size_t> Wavefront::band_pixels(std::size_t band) const {
    const std::size_t width = std::size_t(settings_.width), height = std::size_t(settings_.height);
    const std::size_t first_row = std::min(band * band_tile_rows_ * 8, height);
    const std::size_t end_row = std::min(first_row + band_tile_rows_ * 8, height);
    return {first_row * width, (end_row - first_row) * width};
}

std::vector<Wavefront::ImageBand> Wavefront::image_bands() const {
    std::vector<ImageBand> bands;
    for (std::size_t b = 0; b < image_bands_.size(); ++b) bands.push_back({image_bands_[b], band_pixels(b).first, band_pixels(b).second});
    return bands;
}

}  // namespace rt::gpu
