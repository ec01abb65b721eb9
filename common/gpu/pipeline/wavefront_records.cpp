// What the Wavefront records besides the image (wavefront.h): --dump-hits (one HitRecord per ray, read back after
// each pass), --pixel (the watched pixel's ray tree, drained after each sample) and the per-pixel test counts of
// --heatmap, handed over in finish_frame(FrameResult&).
#include "wavefront.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "wavefront_detail.h"

namespace rt::gpu {

using namespace wavefront_detail;

namespace {

HitRecord make_record(const WavefrontRay& ray, int sample, RayKind kind, std::int32_t triangle, float t) {
    HitRecord r;
    r.sample = std::uint32_t(sample);
    r.pixel = ray.pixel;
    r.path = ray.path;
    r.kind_light = kind == RayKind::Shadow ? pack_kind_light(kind, ray.light, ray.light_sample) : std::uint32_t(kind);
    r.triangle = triangle;
    r.t = t;
    for (int k = 0; k < 3; ++k) {
        r.origin[k] = ray.origin[k];
        r.direction[k] = ray.direction[k];
    }
    return r;
}

}  // namespace

// --pixel: the per-pixel counts, then the watch list (wavefront.glsl, wf_watch): its count and its entries.
std::size_t Wavefront::tests_words() const {
    return pixels_ + (watching() ? 1 + kWatchCapacity * kWatchEntryWords : 0);
}

// After each sample: the watched pixel's entries become RayWork of that sample, and the list starts empty again.
void Wavefront::drain_watch() {
    std::uint32_t used = 0;
    tests_per_pixel_.download(&used, sizeof used, pixels_ * sizeof(std::uint32_t));
    ++syncs_;
    if (used > kWatchCapacity)
        throw std::runtime_error("--pixel: the pixel's rays make more than " + std::to_string(kWatchCapacity) +
                                 " parts of a ray tree in one sample; watch a simpler pixel or use fewer lights");
    if (used == 0) return;
    std::vector<std::uint32_t> words(std::size_t(used) * kWatchEntryWords);
    tests_per_pixel_.download(words.data(), words.size() * sizeof(std::uint32_t),
                              (pixels_ + 1) * sizeof(std::uint32_t));
    ++syncs_;
    for (std::uint32_t e = 0; e < used; ++e) {
        const std::uint32_t* w = &words[std::size_t(e) * kWatchEntryWords];
        const std::uint64_t tests = std::uint64_t(w[2]) | std::uint64_t(w[3]) << 32;
        ray_work_.push_back(RayWork{std::uint32_t(samples_), w[0], w[1], tests, w[4]});
    }
    std::fill(words.begin(), words.end(), 0u);
    const std::uint32_t zero = 0;
    tests_per_pixel_.upload(&zero, sizeof zero, pixels_ * sizeof(std::uint32_t));
    tests_per_pixel_.upload(words.data(), words.size() * sizeof(std::uint32_t), (pixels_ + 1) * sizeof(std::uint32_t));
}

// --dump-hits: every slot of a primary batch inside the image is a primary ray (triangle -1 where the G-buffer is
// empty).
void Wavefront::record_primary_slots(std::size_t slots) {
    ++syncs_;
    for (const WavefrontHit& h : hit_slots_.download<WavefrontHit>(slots))
        if (h.ray.pixel != kNoPixel && recorded(h.ray.pixel))
            hit_records_.push_back(make_record(h.ray, samples_, RayKind::Primary, h.triangle,
                                               h.triangle >= 0 ? h.t : 0.0f));
}

// --dump-hits: the rays of a trace or shadow pass with their results.
void Wavefront::record_rays(const Buffer& rays, std::size_t first, std::size_t count, bool shadow) {
    const std::vector<WavefrontRay> queue = rays.download<WavefrontRay>(count, first);
    syncs_ += 2;   // the rays, then their results
    if (shadow) {
        const std::vector<std::uint32_t> occluded = results_.download<std::uint32_t>(count);
        for (std::size_t i = 0; i < count; ++i)
            if (recorded(queue[i].pixel))
                hit_records_.push_back(
                    make_record(queue[i], samples_, RayKind::Shadow, occluded[i] ? 1 : -1, 0.0f));
        return;
    }
    const std::vector<WavefrontTraceResult> results = results_.download<WavefrontTraceResult>(count);
    for (std::size_t i = 0; i < count; ++i) {
        if (!recorded(queue[i].pixel)) continue;
        const auto kind = RayKind(queue[i].depth_kind >> 16);
        hit_records_.push_back(make_record(queue[i], samples_, kind, results[i].triangle,
                                           results[i].triangle >= 0 ? results[i].t : 0.0f));
    }
}

void Wavefront::finish_frame(FrameResult& result) {
    result.image = finish_frame(result.stats.counters);
    if (settings_.record_hits) result.hits = std::move(hit_records_);
    hit_records_.clear();
    if (settings_.record_tests_per_pixel) {
        result.tests_per_pixel = tests_per_pixel_.download<std::uint32_t>(pixels_);
        ++syncs_;
    }
    result.ray_work = std::move(ray_work_);
    ray_work_.clear();
    result.ray_work_steps = traversal_.steps();
}

}  // namespace rt::gpu
