#include "sorting_renderer.h"

#include <cmath>

#include <glm/glm.hpp>

#include "common/gpu/gl/bindings.h"

namespace rt {

namespace {

// Timer phases per batch kind (pass_time_ms in the stats).
const char* const kSortPhase[2] = {"rs_sort.trace", "rs_sort.shadow"};

void barrier() { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT); }

// 32-bit words per ray in a batch's results: a shadow ray's one, a traced ray's WavefrontTraceResult.
unsigned result_stride(bool shadow) { return shadow ? 1u : unsigned(sizeof(gpu::WavefrontTraceResult) / 4); }

// The gather and scatter passes' buffers (shaders/ray_sort.glsl: RS_STAGE_BINDING_0..2): the stage's own points,
// from the traversal's first (stage 04 rebinds its own before each of its passes).
constexpr unsigned kStageBinding[] = {gpu::kBindingWavefrontTraversalFirst + 0,
                                      gpu::kBindingWavefrontTraversalFirst + 1,
                                      gpu::kBindingWavefrontTraversalFirst + 2};

}  // namespace

RaySortingRenderer::RaySortingRenderer() = default;
RaySortingRenderer::~RaySortingRenderer() = default;

void RaySortingRenderer::add_options(CLI::App& app) {
    RayHierarchyRenderer::add_options(app);
    add_sort_options(app, sort_options);
}

unsigned RaySortingRenderer::shadow_direction_bits() const {
    const unsigned k = sort_options.key_bits, d = sort_options.shadow_direction_bits;
    return d > k ? k / 2 : d;   // the default 12 under a short key: half of it, the origin still first
}

unsigned RaySortingRenderer::fine_direction_bits() const {
    const unsigned f = sort_options.fine_direction_bits;
    if (sort_options.mode != SortMode::automatic || f > sort_options.key_bits || f == sort_options.direction_bits)
        return 0;
    return f;
}

void RaySortingRenderer::compile() {
    if (sorter_) return;
    sorter_ = std::make_unique<RaySorter>();
    gather_ = gpu::Program::compute("05_ray_sorting/shaders/ray_gather.comp");
    scatter_ = gpu::Program::compute("05_ray_sorting/shaders/result_scatter.comp");
}

void RaySortingRenderer::build(const Scene& scene, const RenderSettings& settings) {
    RayHierarchyRenderer::build(scene, settings);
    batch_stats_ = {};
    batch_index_ = {};
    kept_ = {};
    if (!sort_options.sorts()) return;
    compile();
    choice_.reset_tally();
    sorter_->reset_tally();
    const float diagonal = glm::length(scene.bounds.hi - scene.bounds.lo);
    diagonal_ = std::isfinite(diagonal) && diagonal > 0.0f ? diagonal : 1.0f;
    if (sort_options.mode == SortMode::automatic) {   // the width cap (order_choice.h)
        const GpuRayHierarchy::LeafSpheres leaves = hierarchy().leaf_spheres();
        choice_.set_leaves(*leaves.buffer, leaves.count, leaves.stride);
    }
    const unsigned lights = unsigned(scene.light_count());   // punctual and area: a group each
    layouts_[0] = make_key_layout(scene.bounds.lo, scene.bounds.hi, sort_options.key_bits, sort_options.direction_bits,
                                  lights, KeyOrder::direction_first);
    layouts_[1] = make_key_layout(scene.bounds.lo, scene.bounds.hi, sort_options.key_bits, shadow_direction_bits(),
                                  lights, KeyOrder::origin_first);
    layouts_[2] = make_key_layout(scene.bounds.lo, scene.bounds.hi, sort_options.key_bits, fine_direction_bits(),
                                  lights, KeyOrder::direction_first);
}

// One batch: sort, gather, trace, scatter (or, when --sort auto's memory says so, stage 04's trace unsorted).
void RaySortingRenderer::trace_batch(const gpu::BatchTraceInputs& in, bool shadow) {
    if (!sort_options.sorts() || in.count == 0) return RayHierarchyRenderer::trace_batch(in, shadow);
    const std::size_t kind = shadow ? 1 : 0;
    const std::uint32_t slot = batch_index_[kind]++;
    const BatchPlan plan = memory_.plan(kind, slot, sort_options);
    if (!plan_sorts(plan)) return trace_unsorted(in, shadow, slot, plan);
    {
        auto timed = timer().scope(kSortPhase[kind]);
        sort(in, kind, slot, plan);   // 1. the rays' keys, radix-sorted: order_ (ray_sort.h)
        gather(in);                   // 2. the rays copied into that order
    }
    trace_sorted(in, shadow, slot, plan);   // 3. stage 04's hierarchy over the sorted rays
    scatter(in, shadow);                    // 4. the results put back in queue order
}

void RaySortingRenderer::sort(const gpu::BatchTraceInputs& in, std::size_t kind, std::uint32_t slot, BatchPlan plan) {
    // ray_keys.h: which key suits which rays; a remembered fine order is sorted by the fine key alone.
    sorter_->layout = layouts_[plan == BatchPlan::fine ? 2 : kind];
    sorter_->tally_slot = kind;   // the chunk counts per batch kind, summed on the GPU
    sorter_->sort(in.rays, in.first, in.count, order_);
    batch_stats_[kind].batches += 1;
    batch_stats_[kind].rays += in.count;
    if (plan != BatchPlan::measure) {   // a sorted order won when last measured: keep it, unmeasured
        kept_[kind].batches += 1;
        kept_[kind].rays += in.count;
        if (plan == BatchPlan::fine) kept_[kind].fine_batches += 1;
    } else if (sort_options.mode == SortMode::automatic) {
        // Reflection and refraction rays: a second order by the finer direction cell, for the choice.
        const bool fine = kind == 0 && fine_direction_bits() > 0;
        if (fine) {
            sorter_->layout = layouts_[2];
            sorter_->tally_slot = 2;   // not reported: a batch's chunks are those of its first key
            sorter_->sort(in.rays, in.first, in.count, fine_order_);
        }
        choice_.choose(in.wavefront.defines(), in.rays, in.first, in.count, order_, fine ? &fine_order_ : nullptr,
                       hierarchy_options.branching, diagonal_, int(kind), slot);
        batch_stats_[kind].measured_batches += 1;
        memory_.measured(kind, slot, in.count);   // what its sort cost, for the check
    }
}

void RaySortingRenderer::gather(const gpu::BatchTraceInputs& in) {
    const std::size_t n = in.count;
    sorted_rays_.reserve(n * sizeof(gpu::WavefrontRay));
    gather_.set("rs_count", unsigned(n));
    in.rays.bind_range(kStageBinding[0], 0, (in.first + n) * sizeof(gpu::WavefrontRay));
    order_.bind_range(kStageBinding[1], 0, n * 4);
    sorted_rays_.bind_range(kStageBinding[2], 0, n * sizeof(gpu::WavefrontRay));
    gather_.dispatch_threads(n);
    barrier();
}

void RaySortingRenderer::trace_sorted(const gpu::BatchTraceInputs& in, bool shadow, std::uint32_t slot,
                                      BatchPlan plan) {
    const std::size_t n = in.count, kind = shadow ? 1 : 0;
    sorted_results_.reserve(n * result_stride(shadow) * 4);
    // A measured batch's pairs, for the check of its choice (sort_memory.h).
    const bool record = plan == BatchPlan::measure && checks_sorts();
    if (record) choice_.record_work(hierarchy(), int(kind), slot, false);
    // The same runs: the key's group field (ray_keys.h) sorts the groups in the queue's order, each its whole self.
    RayHierarchyRenderer::trace_batch({sorted_rays_, 0, n, sorted_results_, in.tests_per_pixel, in.wavefront, in.runs},
                                      shadow);
    if (record) choice_.record_work(hierarchy(), int(kind), slot, true);
}

void RaySortingRenderer::scatter(const gpu::BatchTraceInputs& in, bool shadow) {
    const std::size_t n = in.count;
    const unsigned stride = result_stride(shadow);
    auto timed = timer().scope(kSortPhase[shadow ? 1 : 0]);
    scatter_.set("rs_count", unsigned(n));
    scatter_.set("rs_first", unsigned(in.first));
    scatter_.set("rs_stride", stride);
    order_.bind_range(kStageBinding[0], 0, n * 4);
    sorted_results_.bind_range(kStageBinding[1], 0, n * stride * 4);
    in.results.bind_range(kStageBinding[2], 0, n * stride * 4);
    scatter_.dispatch_threads(n);
    barrier();
    gpu::check_gl("05_ray_sorting: sorted batch");
}

void RaySortingRenderer::trace_unsorted(const gpu::BatchTraceInputs& in, bool shadow, std::uint32_t slot,
                                        BatchPlan plan) {
    const std::size_t kind = shadow ? 1 : 0;
    SortBatchStats& stats = batch_stats_[kind];
    stats.skipped_batches += 1;
    stats.skipped_rays += in.count;
    const bool check = plan == BatchPlan::check_queue;   // what the queue's order tests, against the kept sort's
    if (check) {
        stats.checked_batches += 1;
        choice_.record_work(hierarchy(), int(kind), slot, false);
    }
    RayHierarchyRenderer::trace_batch(in, shadow);
    if (check) choice_.record_work(hierarchy(), int(kind), slot, true);
}

void RaySortingRenderer::end_frame() {
    RayHierarchyRenderer::end_frame();
    sorts_dropped_ = {};
    if (sort_options.mode != SortMode::automatic) return;
    // The measured batches' choices and the recorded pairs, tallied on the GPU and read here once per frame.
    tally_ = choice_.tally();
    sorts_dropped_ = memory_.learn(tally_, sort_options);
}

std::vector<std::string> RaySortingRenderer::stage_programs() const {
    std::vector<std::string> programs = RayHierarchyRenderer::stage_programs();
    if (sort_options.sorts())
        for (const char* p : {"ray_keys.comp", "chunk_heads.comp", "chunks.comp", "chunk_tally.comp",
                              "chunk_sizes.comp", "skeleton.comp", "ray_gather.comp", "result_scatter.comp"})
            programs.push_back(std::string("05_ray_sorting/shaders/") + p);
    if (sort_options.mode == SortMode::automatic)
        for (const char* p : {"order_cost.comp", "order_choice.comp"})
            programs.push_back(std::string("05_ray_sorting/shaders/") + p);
    return programs;
}

void RaySortingRenderer::add_stage_stats(FrameResult& result) {
    RayHierarchyRenderer::add_stage_stats(result);
    SortFrameStats f;
    f.options = sort_options;
    f.shadow_direction_bits = shadow_direction_bits();
    f.fine_direction_bits = fine_direction_bits();
    f.layouts = layouts_;
    f.batches = batch_stats_;
    // The chunk counts, summed on the GPU (ray_sort.h), read here once per frame.
    if (sorter_ && sort_options.sorts()) {
        const auto chunks = sorter_->chunk_tally();
        for (std::size_t k = 0; k < 2; ++k) f.batches[k].chunks = chunks[k];
        f.gpu_cpu_syncs = sorter_->syncs;
    }
    // Batches (and their rays) whose sorted order was kept, and of them those that kept the fine key's: every sorted
    // batch with --sort on; with auto the measured batches' choices (end_frame's read) and those sorted by a
    // remembered order (kept_).
    if (sort_options.mode == SortMode::automatic) {
        ++f.gpu_cpu_syncs;   // end_frame's read
        for (std::size_t k = 0; k < 2; ++k) {
            const GpuOrderChoice::Tally& t = tally_.kept[k];
            f.kept[k] = {t.batches + kept_[k].batches, t.rays + kept_[k].rays, t.fine_batches + kept_[k].fine_batches};
            f.batches[k].sorts_dropped = sorts_dropped_[k];
        }
    }
    if (sort_options.mode == SortMode::on)
        for (std::size_t k = 0; k < 2; ++k) f.kept[k] = {batch_stats_[k].batches, batch_stats_[k].rays};
    for (std::size_t k = 0; k < 2; ++k) f.sort_ms[k] = pass_ms(result, kSortPhase[k]);
    result.extra["ray_sorting"] = f;
    add_syncs(result, f.gpu_cpu_syncs);
}

}  // namespace rt
