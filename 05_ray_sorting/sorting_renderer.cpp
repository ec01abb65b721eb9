#include "sorting_renderer.h"

#include "02_raster_hybrid/rasterized_primary.h"
#include "common/gpu/gl/bindings.h"
#include "sort_auto.h"

namespace rt {

namespace {

void barrier() { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT); }

// 32-bit words per ray in a batch's results: a shadow ray's one, a traced ray's WavefrontTraceResult.
unsigned result_stride(bool shadow) { return shadow ? 1u : unsigned(sizeof(gpu::WavefrontTraceResult) / 4); }

// The gather and scatter passes' buffers (shaders/ray_sort.glsl: RS_STAGE_BINDING_0..2): the stage's own points,
// from the traversal's first (stage 04 rebinds its own before each of its passes).
constexpr unsigned kStageBinding[] = {gpu::kBindingWavefrontTraversalFirst + 0,
                                      gpu::kBindingWavefrontTraversalFirst + 1,
                                      gpu::kBindingWavefrontTraversalFirst + 2};

}  // namespace

SortedTraversal::SortedTraversal(SortOptions& options, std::unique_ptr<HierarchyTraversal> hierarchy)
    : options_(options), hierarchy_(std::move(hierarchy)) {}
SortedTraversal::~SortedTraversal() = default;

// One batch, --sort on: sort, gather, trace, scatter (--sort off: stage 04's trace as it is).
void SortedTraversal::trace_batch(const gpu::BatchTraceInputs& in, bool shadow) {
    if (!options_.sorts() || in.count == 0) return hierarchy_->trace_batch(in, shadow);
    {
        auto timed = timer().scope(sort_phase(shadow));
        sort(in, layout(shadow), shadow ? 1 : 0, order_);   // 1. the rays' keys, radix-sorted (ray_sort.h)
        gather(in);                                          // 2. the rays copied into that order
    }
    trace_sorted(in, shadow);   // 3. stage 04's hierarchy over the sorted rays
    scatter(in, shadow);        // 4. the results put back in queue order
}

void SortedTraversal::sort(const gpu::BatchTraceInputs& in, const RayKeyLayout& layout, std::size_t slot,
                           gpu::Buffer& order) {
    sorter_->layout = layout;   // ray_keys.h: which key suits which rays
    sorter_->tally_slot = slot;   // the chunk counts per batch kind, summed on the GPU
    sorter_->sort(in.rays, in.first, in.count, order);
    if (slot < 2) {
        stats_.batches[slot].batches += 1;
        stats_.batches[slot].rays += in.count;
    }
}

void SortedTraversal::gather(const gpu::BatchTraceInputs& in) {
    const std::size_t n = in.count;
    sorted_rays_.reserve(n * sizeof(gpu::WavefrontRay));
    gather_.set("rs_count", unsigned(n));
    in.rays.bind_range(kStageBinding[0], 0, (in.first + n) * sizeof(gpu::WavefrontRay));
    order_.bind_range(kStageBinding[1], 0, n * 4);
    sorted_rays_.bind_range(kStageBinding[2], 0, n * sizeof(gpu::WavefrontRay));
    gather_.dispatch_threads(n);
    barrier();
}

void SortedTraversal::trace_sorted(const gpu::BatchTraceInputs& in, bool shadow) {
    const std::size_t n = in.count;
    sorted_results_.reserve(n * result_stride(shadow) * 4);
    // The same runs: the key's group field (ray_keys.h) sorts the groups in the queue's order, each its whole self.
    hierarchy_->trace_batch(
        {sorted_rays_, 0, n, sorted_results_, in.tests_per_pixel, in.wavefront, in.runs, in.triangles}, shadow);
}

void SortedTraversal::scatter(const gpu::BatchTraceInputs& in, bool shadow) {
    const std::size_t n = in.count;
    const unsigned stride = result_stride(shadow);
    auto timed = timer().scope(sort_phase(shadow));
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

void SortedTraversal::add_options(CLI::App& app) {
    hierarchy_->add_options(app);
    add_sort_options(app, options_);
}

unsigned SortedTraversal::shadow_direction_bits() const {
    const unsigned k = options_.key_bits, d = options_.shadow_direction_bits;
    return d > k ? k / 2 : d;   // the default 12 under a short key: half of it, the origin still first
}

void SortedTraversal::compile() {
    if (sorter_) return;
    sorter_ = std::make_unique<RaySorter>();
    gather_ = gpu::Program::compute("05_ray_sorting/shaders/ray_gather.comp");
    scatter_ = gpu::Program::compute("05_ray_sorting/shaders/result_scatter.comp");
}

void SortedTraversal::build(const gpu::FrameInputs& frame) {
    hierarchy_->build(frame);
    timer_ = &frame.timer;
    stats_ = {};
    if (!options_.sorts()) return;
    compile();
    sorter_->reset_tally();
    const Bounds& box = frame.scene.bounds;
    const unsigned lights = unsigned(frame.scene.light_count());   // punctual and area: a group each
    layouts_[0] = make_key_layout(box.lo, box.hi, options_.key_bits, options_.direction_bits, lights,
                                  KeyOrder::direction_first);
    layouts_[1] = make_key_layout(box.lo, box.hi, options_.key_bits, shadow_direction_bits(), lights,
                                  KeyOrder::origin_first);
}

std::vector<std::string> SortedTraversal::programs() const {
    std::vector<std::string> programs = hierarchy_->programs();
    if (options_.sorts())
        for (const char* p : {"ray_keys.comp", "chunk_heads.comp", "chunks.comp", "chunk_tally.comp",
                              "chunk_sizes.comp", "skeleton.comp", "ray_gather.comp", "result_scatter.comp"})
            programs.push_back(std::string("05_ray_sorting/shaders/") + p);
    return programs;
}

void SortedTraversal::report(gpu::FrameReport& report) {
    hierarchy_->report(report);
    SortFrameStats& f = stats_;
    f.options = options_;
    f.shadow_direction_bits = shadow_direction_bits();
    f.layouts[0] = layouts_[0];
    f.layouts[1] = layouts_[1];
    // The chunk counts, summed on the GPU (ray_sort.h), read here once per frame.
    if (sorter_ && options_.sorts()) {
        const auto chunks = sorter_->chunk_tally();
        for (std::size_t k = 0; k < 2; ++k) f.batches[k].chunks = chunks[k];
        f.gpu_cpu_syncs += sorter_->syncs;
    }
    // --sort on keeps every sorted batch's order (--sort auto says which it kept: sort_auto.h).
    if (options_.mode == SortMode::on)
        for (std::size_t k = 0; k < 2; ++k) f.kept[k] = {f.batches[k].batches, f.batches[k].rays};
    for (std::size_t k = 0; k < 2; ++k) f.sort_ms[k] = report.pass_ms(sort_phase(k == 1));
    report.result.extra["ray_sorting"] = f;
    report.syncs += f.gpu_cpu_syncs;
}

RaySortingRenderer::RaySortingRenderer()
    : GpuStage(std::make_unique<RasterizedPrimary>(),
               std::make_unique<AutoSortTraversal>(
                   sort_options, std::make_unique<SortedTraversal>(
                                     sort_options, std::make_unique<HierarchyTraversal>(hierarchy_options)))) {}

}  // namespace rt
