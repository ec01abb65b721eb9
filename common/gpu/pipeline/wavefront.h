// The wavefront Whitted pipeline every GPU stage shares (Laine, Karras & Aila 2013, "Megakernels Considered
// Harmful"): instead of one thread recursing through a ray tree as stage 01 does, rays wait in queues on the GPU and
// each pass handles one kind of work for all of them:
//
//   primary hits ──> shade ──> shadow rays ──> shadow pass (any hit) ──> light contributions
//        ^              └───> reflection/refraction rays ──> trace pass (closest hit) ──┐
//        └──────────────────────────────── hits of the next bounce <───────────────────┘
//
// The stage supplies two things: the primary hits (primary_visibility.h: every GPU stage rasterizes them by default,
// as stage 02 does; stage 03 with --primary trace traces camera rays with trace_camera_sample) and the traversal
// (traversal.h): a GLSL file that defines
//
//   bool trace_closest(Ray ray, out Hit hit);   // the nearest hit with 0 < t < ray.tmax (hit.triangle = -1 if none)
//   bool trace_any(Ray ray);                    // whether anything is hit with 0 < t < ray.tmax (may stop early)
//
// and calls wf_count_tests(n) for the ray/triangle tests it makes. It should
// #include "common/shaders/wavefront/wavefront.glsl" (rays, hits, the counting hook; RT_INTERSECT_METHOD says which ray/triangle test to use) and keep its own buffers
// at WF_BINDING_TRAVERSAL_FIRST and up. The pipeline compiles its trace and shadow passes with that file included
// first. A traversal that traces a whole queue at once (stages 02, 04, 05: many dispatches per pass) has no GLSL file
// and a trace_batch instead, which writes one result per ray (BatchTraceInputs).
//
// Queues are ordered, never appended to: each pass writes its outputs to fixed slots and a prefix sum packs them
// (docs/gpu.md, "Queue order"), so queue contents, stats and images are the same on every run. Work is done in
// batches small enough that no buffer the pipeline binds exceeds GL_MAX_SHADER_STORAGE_BLOCK_SIZE (or
// max_storage_bytes / $RT_MAX_SSBO_BYTES, when smaller); a bounce whose rays do not fit is traced in parts, its
// children first (depth first over batches), so nothing is ever dropped.
//
// Effects the scene does not call for cost nothing: no shadow pass, shadow slots or shadow code without shadows, no
// trace pass, ray queues or reflection/refraction code without reflections and refractions (or with max_depth 0).
// The image is a per-pixel sum in 96-bit fixed point (wavefront.glsl, wf_accumulate): exact, so the same on every
// run, and saturating, never wrapping, beyond 2^63.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "common/trace/hit_record.h"
#include "common/app/image.h"
#include "common/app/progress.h"
#include "common/app/renderer.h"
#include "common/gpu/gl/bindings.h"
#include "common/gpu/gl/buffer.h"
#include "gpu_scene.h"
#include "traversal.h"
#include "common/gpu/primitives/scan.h"
#include "common/gpu/gl/shader.h"

namespace rt::gpu {

// SSBO bindings of wavefront.glsl a batch traversal's passes use (WF_BINDING_RAYS_IN, _RESULTS, _TESTS_PER_PIXEL).
constexpr unsigned kWavefrontBindingRaysIn = kBindingWavefrontRaysIn;
constexpr unsigned kWavefrontBindingResults = kBindingWavefrontResults;
constexpr unsigned kWavefrontBindingTestsPerPixel = kBindingWavefrontTestsPerPixel;
// First SSBO binding a traversal may use for its own data (wavefront.glsl: WF_BINDING_TRAVERSAL_FIRST).
constexpr unsigned kWavefrontBindingTraversalFirst = kBindingWavefrontTraversalFirst;
// The primary-hit pass of a stage may bind its own textures from here (02 binds its G-buffer).
constexpr unsigned kWavefrontFirstFreeTextureUnit = 1;

// std430 mirrors of wavefront.glsl.
struct WavefrontRay {
    glm::vec3 origin;    float tmax;
    glm::vec3 direction; std::uint32_t pixel;
    glm::vec3 weight;    std::uint32_t depth_kind;   // depth | kind << 16
    std::uint32_t path, light, light_sample, pad1;   // the ray in its tree (hit_record.h); light and its grid
                                                     // cell: shadow rays
};
static_assert(sizeof(WavefrontRay) == 64);
struct WavefrontHit {
    WavefrontRay ray;
    std::int32_t triangle; float t, u, v;
};
static_assert(sizeof(WavefrontHit) == 80);
// One trace-pass result per ray: the closest hit, triangle -1 for a miss.
struct WavefrontTraceResult {
    std::int32_t triangle; float t, u, v;
};
static_assert(sizeof(WavefrontTraceResult) == 16);

class Wavefront;

// The maximal runs of rays[first, first + count) (from `first`): what the pipeline hands a batch traversal for them,
// worked out from the rays themselves (for callers outside the pipeline: tests).
std::vector<RayRun> ray_runs(const std::vector<WavefrontRay>& rays, std::size_t first, std::size_t count);

class Wavefront {
public:
    explicit Wavefront(Traversal& traversal);   // kept by reference: it must outlive the pipeline

    // Start of a frame: compiles the passes the settings call for (kept while they stay the same), sizes the
    // per-pixel buffers, clears the image and the counters, binds the scene. The scene must be uploaded.
    void begin_frame(const GpuScene& scene, const RenderSettings& settings);

    // One sample with primary hits from the stage: for each batch of 8x8 pixel tiles, `primary_pass` (a program of
    // the stage, compiled with defines(); the stage binds its own inputs first) runs one thread per slot of the
    // batch: it writes wf_hits[slot] and wf_flags[slot] for pixel wf_tile_pixel(wf_tile_first * 64 + slot) and adds
    // the background of empty pixels with wf_accumulate() (stage 02's shaders/primary_hits.comp). Then the hits are
    // shaded and every bounce traced. With `deferred_rays` (the stage's, compiled with defines(): stage 02's
    // shaders/deferred_rays.comp, for cut-outs) the pass may instead defer a pixel's camera ray to
    // wf_ray_slots[slot] (pixel WF_NO_PIXEL in every slot it does not defer); `deferred_rays` flags those slots, and
    // their rays are traced as in trace_camera_sample after the batch's hits.
    void shade_sample(const Program& primary_pass, const Program* deferred_rays = nullptr);

    // One sample with traced primary rays (stage 03 with --primary trace): camera rays through `offset` in each
    // pixel, traced with the traversal, then shaded as above.
    void trace_camera_sample(glm::vec2 offset);

    // End of the frame: the image (the mean over the samples; empty when settings.need_image is false, the image
    // then stays on the GPU: image_bands()) and the counters. Waits for the GPU.
    Image finish_frame(RayCounters& counters);
    // The same into a FrameResult, with the diagnostics the settings asked for: `hits` (record_hits: one HitRecord
    // per traced or rasterized ray) and `tests_per_pixel` (record_tests_per_pixel).
    void finish_frame(FrameResult& result);

    // The frame's image where it is, on the GPU (a window shows it without a read-back): band by band, the float
    // sums over samples() samples (vec4 per pixel) of the pixels [first, first + count), row-major from the top.
    struct ImageBand {
        const Buffer& sums;
        std::size_t first, count;
    };
    std::vector<ImageBand> image_bands() const;
    int samples() const { return samples_; }
    int width() const { return settings_.width; }
    int height() const { return settings_.height; }

    // The defines the passes were compiled with (effects, RT_INTERSECT_METHOD, COUNT_TESTS, the traversal's).
    const ShaderDefines& defines() const { return defines_; }
    // Programs compiled for this frame's variant, e.g. "common/shaders/wavefront/shade.comp".
    std::vector<std::string> programs() const;
    // Passes dispatched since begin_frame, in first-run order, and how many dispatches each (a pass' compaction and
    // its collect step count with it: "trace" is trace.comp or trace_batch, trace_collect.comp and the scan).
    const std::vector<std::string>& passes() const { return pass_order_; }
    const std::map<std::string, int>& dispatches() const { return dispatches_; }
    // Read-backs since begin_frame, each a wait for the GPU: one per compaction (the next pass' length), the image
    // and the counters at the end, and what --dump-hits, --pixel and --heatmap read. A stage's own come on top.
    std::uint64_t syncs() const { return syncs_; }
    // The settings uniforms on a stage's own pass (wf_max_depth, wf_image_size, ...), for primary-hit passes.
    void set_uniforms(const Program& program) const;
    // Records a stage pass in passes() (e.g. "gbuffer").
    void record_pass(const std::string& name);

    // Count tests (COUNT_TESTS, default on): exact stats for one atomic per thread. Off for timing runs.
    bool count_tests = true;
    // The largest buffer the pipeline may bind, when smaller than GL_MAX_SHADER_STORAGE_BLOCK_SIZE (0 = no extra
    // limit; $RT_MAX_SSBO_BYTES does the same). Tests set it tiny to force batches.
    std::size_t max_storage_bytes = 0;
    // When set, each pass is timed on it as "shade", "shadow", "trace", "resolve" or "camera_rays".
    GpuTimer* timer = nullptr;
    // When set, advanced by the 8x8 tiles of each primary batch once its rays and all their descendants are done:
    // a long frame shows a progress bar (common/app/progress.h) instead of looking hung.
    Progress* progress = nullptr;
    // The limit this frame runs with, and how many hits or rays one batch holds.
    std::size_t storage_limit() const { return storage_limit_; }
    std::size_t batch_size() const { return batch_; }

private:
    Program compile(const std::string& pass, bool with_traversal) const;
    void compile_programs();
    std::size_t storage_block_limit() const;
    void size_batches();
    std::pair<std::size_t, std::size_t> band_pixels(std::size_t band) const;
    template <class F> void for_each_tile_batch(F&& run_batch);
    std::uint32_t compact(const Buffer& slots, std::size_t n, unsigned stride_uints, Buffer& out);
    void scatter_slots(const Buffer& slots, std::size_t n, unsigned stride_uints, std::uint32_t total, Buffer& out);
    // A shade run's slots, `blocks` blocks of `hits` each, packed into `out`: the runs of the blocks (empty ones left
    // out), from one read-back of the scan at every block boundary.
    struct SlotBlock {
        RayKind kind;
        std::uint32_t light;
        std::size_t per_hit = 1;   // slots per hit: an area light's cells, else 1
    };
    std::vector<RayRun> compact_blocks(std::size_t hits, const std::vector<SlotBlock>& blocks, Buffer& out);
    std::vector<SlotBlock> secondary_blocks() const;   // reflection, refraction (and transparency) slots
    Buffer& queue(int depth);
    void process_hits(std::size_t hits, int depth);
    void run_shade(std::size_t hits, unsigned light_first, unsigned light_count, bool local, std::size_t shadow_base);
    // Shadow slots light l takes per hit: 1 for a punctual light, its grid's cells for an area light.
    std::size_t light_slots(unsigned l) const { return l < punctual_lights_ ? 1 : light_cells_; }
    void run_rays(Buffer& rays, const std::vector<RayRun>& runs, int depth);
    void run_shadow(Buffer& rays, std::size_t first, std::size_t count, std::vector<RayRun> runs);
    void run_trace(Buffer& rays, std::size_t first, std::size_t count, std::vector<RayRun> runs);
    void run_traversal(bool shadow, Buffer& rays, std::size_t first, std::size_t count, std::vector<RayRun> runs);
    void run_collect(const Program& collect, Buffer& rays, std::size_t first, std::size_t count);
    void record_primary_slots(std::size_t slots);
    void record_rays(const Buffer& rays, std::size_t first, std::size_t count, bool shadow);
    void resolve(std::size_t band);
    void bind_traversal() const;
    void prepare_camera_tracing();
    std::size_t gather_deferred_rays(const Program& deferred_rays, std::size_t slots);   // (shade_sample)
    // --pixel (settings.watch_pixel; the driver asks for the per-pixel counts with it): the watch list of
    // wavefront.glsl after the per-pixel counts, WF_WATCH_CAPACITY entries of WF_WATCH_ENTRY words.
    bool recorded(std::uint32_t pixel) const {   // --dump-hits: every pixel; --pixel alone: that one
        return settings_.record_hits_pixel < 0 || std::int64_t(pixel) == settings_.record_hits_pixel;
    }
    bool watching() const { return settings_.record_tests_per_pixel && settings_.watch_pixel >= 0; }
    static constexpr std::size_t kWatchCapacity = 65536, kWatchEntryWords = 6;
    std::size_t tests_words() const;
    void drain_watch();

    Traversal& traversal_;
    RenderSettings settings_;
    std::size_t pixels_ = 0;
    int samples_ = 0;
    std::size_t triangles_ = 0;      // the uploaded scene's (a batch traversal's BatchTraceInputs::triangles)
    unsigned lights_ = 0;            // punctual and area (GpuScene::light_count)
    unsigned punctual_lights_ = 0;
    std::size_t light_cells_ = 1;    // an area light's cells (settings.light_grid), with area lights
    bool shadows_ = false, secondary_ = false;
    bool transparency_slots_ = false;   // BLEND's transparency rays have their own block (secondary_ only)
    std::size_t storage_limit_ = 0, batch_ = 0;
    std::size_t band_tile_rows_ = 0;   // rows of 8x8 tiles whose radiance sums fit one storage block
    ShaderDefines defines_;
    std::string compiled_key_;
    Program shade_, shadow_, trace_, shadow_collect_, trace_collect_, resolve_, camera_, compact_;
    Scan scan_;
    // Shared by all depths: the hits being shaded, the output slots of a pass with their flags and scan, results.
    Buffer hits_, hit_slots_, ray_slots_, flags_, offsets_, counts_, results_;
    std::vector<Buffer> queues_;   // queues_[d]: the rays of depth d (then the shadow rays of depth d - 1)
    Buffer radiance_, tests_per_pixel_;   // radiance_: one band of rows (wf_accumulate)
    std::vector<Buffer> image_bands_;     // the float sum over samples, band by band
    CounterBuffer counters_;
    std::vector<HitRecord> hit_records_;
    std::vector<RayWork> ray_work_;   // --pixel, drained after each sample
    std::vector<std::string> pass_order_;
    std::map<std::string, int> dispatches_;
    std::uint64_t syncs_ = 0;
};

}  // namespace rt::gpu
