#include "wavefront.h"

#include <algorithm>
#include <optional>
#include <utility>

#include "bindings.h"

namespace rt::gpu {

namespace {

// Binding points of wavefront.glsl.
constexpr unsigned kBindingRaysIn = kBindingStageFirst + 0;
constexpr unsigned kBindingHits = kBindingStageFirst + 1;
constexpr unsigned kBindingRaysOut = kBindingStageFirst + 2;
constexpr unsigned kBindingShadowRays = kBindingStageFirst + 3;
constexpr unsigned kBindingRadiance = kBindingStageFirst + 4;
constexpr unsigned kBindingQueueCounts = kBindingStageFirst + 5;
constexpr unsigned kBindingImage = kBindingStageFirst + 6;
static_assert(kWavefrontBindingTraversalFirst == kBindingStageFirst + 8);

// Indices into the queue counters (wavefront.glsl: WfQueueCounts).
constexpr unsigned kQueueHits = 0, kQueueRaysOut = 1, kQueueShadowRays = 2;

// Between passes: shader writes become visible to the next pass, to read-backs and to buffer clears.
void pass_barrier() { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT); }

// Times a pass on the stage's GpuTimer, when it gave one, until end() or the end of the scope.
struct PassTimer {
    std::optional<GpuTimer::Scope> scope;
    PassTimer(GpuTimer* timer, const char* phase) {
        if (timer) scope.emplace(*timer, phase);
    }
    void end() { scope.reset(); }
};

void bind_if(const Buffer& b, unsigned binding) {
    if (b) b.bind(binding);
}

}  // namespace

Wavefront::Wavefront(Traversal traversal) : traversal_(std::move(traversal)), counters_(16) {}

void Wavefront::begin_frame(const GpuScene& scene, const RenderSettings& settings) {
    settings_ = settings;
    lights_ = unsigned(scene.light_count());
    samples_ = 0;
    pass_order_.clear();
    dispatches_.clear();

    // The variant: only the effects the scene calls for (settings.effects is already resolved from --effects).
    // Reflection and refraction rays need a bounce to go to; shadow rays need a light.
    Effects effects = settings.effects;
    if (settings.max_depth <= 0) effects.reflections = effects.refractions = false;
    shadows_ = effects.shadows && lights_ > 0;
    effects.shadows = shadows_;
    secondary_ = effects.reflections || effects.refractions;
    ShaderDefines defines = effect_defines(effects);
    defines.insert_or_assign("RT_INTERSECT_METHOD", std::string(settings.intersect == IntersectMethod::Watertight
                                                                    ? "RT_INTERSECT_WATERTIGHT"
                                                                    : "RT_INTERSECT_MOLLER"));
    if (count_tests) defines.insert_or_assign("COUNT_TESTS", std::string("1"));
    for (const auto& [k, v] : traversal_.defines) defines.insert_or_assign(k, v);
    std::string key;
    for (const auto& [k, v] : defines) key.append(k).append("=").append(v).append(";");
    if (key != compiled_key_) {
        defines_ = std::move(defines);
        compiled_key_ = key;
        compile_programs();
    }
    for (const Program* p : {&shade_, &shadow_, &trace_, &resolve_, &camera_})
        if (*p) set_uniforms(*p);

    // Per-pixel buffers: this sample's radiance (fixed point) and the sum over samples.
    pixels_ = std::size_t(settings.width) * std::size_t(settings.height);
    radiance_.resize(pixels_ * 3 * sizeof(std::int32_t));
    radiance_.clear_u32(0);
    image_.resize(pixels_ * sizeof(glm::vec4));
    image_.clear_u32(0);   // 0x00000000 is 0.0f
    if (!queue_counts_) queue_counts_ = Buffer(4 * sizeof(std::uint32_t));
    // Queues of effects this variant does not simulate are not kept.
    if (!shadows_) shadow_rays_ = Buffer();
    if (!secondary_) rays_out_ = Buffer();
    counters_.clear();
    scene.bind();
    counters_.bind();
    check_gl("wavefront: begin frame");
}

Program Wavefront::compile(const std::string& pass, bool with_traversal) const {
    std::string file = "wavefront/";
    file += pass;
    if (!with_traversal) return Program::compute(file, defines_);
    // The traversal first (it defines trace_closest / trace_any), then the pass that calls it.
    std::string source = "// ";
    source.append(file).append(" with the traversal ").append(traversal_.glsl).append("\n");
    source.append("#include \"").append(traversal_.glsl).append("\"\n");
    source.append("#include \"").append(file).append("\"\n");
    std::string name = file;
    name.append(" + ").append(traversal_.glsl);
    return Program::compute_source(name, source, defines_);
}

void Wavefront::compile_programs() {
    shade_ = compile("shade.comp", false);
    resolve_ = compile("resolve.comp", false);
    shadow_ = shadows_ ? compile("shadow.comp", true) : Program();
    trace_ = secondary_ ? compile("trace.comp", true) : Program();
    camera_ = Program();   // compiled on first use (stages that trace primary rays)
}

std::vector<std::string> Wavefront::programs() const {
    std::vector<std::string> names;
    for (const Program* p : {&shade_, &shadow_, &trace_, &resolve_, &camera_})
        if (*p) names.push_back(p->name());
    return names;
}

void Wavefront::set_uniforms(const Program& p) const {
    p.set("wf_max_depth", settings_.max_depth);
    p.set("wf_cutoff", settings_.cutoff);
    p.set("wf_fresnel", int(settings_.fresnel));      // RT_FRESNEL_SCHLICK = 0, RT_FRESNEL_EXACT = 1, as FresnelMode
    p.set("wf_offset", int(settings_.offset));        // RT_OFFSET_EPSILON = 0, RT_OFFSET_ROBUST = 1, as OffsetMethod
    p.set("wf_epsilon", settings_.epsilon);
    p.set("wf_image_size", glm::ivec2(settings_.width, settings_.height));
}

void Wavefront::record_pass(const std::string& name) {
    if (dispatches_[name]++ == 0) pass_order_.push_back(name);
}

void Wavefront::bind_traversal() const {
    if (traversal_.bind) traversal_.bind();
}

void Wavefront::clear_queue_counts() { queue_counts_.clear_u32(0); }

std::uint32_t Wavefront::read_queue_count(unsigned index) const {
    return queue_counts_.download_value<std::uint32_t>(index);
}

void Wavefront::begin_primary_hits(std::size_t max_hits) {
    hits_.reserve(std::max<std::size_t>(max_hits, 1) * sizeof(WavefrontHit));
    clear_queue_counts();
    pass_barrier();
    hits_.bind(kBindingHits);
    queue_counts_.bind(kBindingQueueCounts);
    radiance_.bind(kBindingRadiance);
    counters_.bind();
}

void Wavefront::trace_camera_sample(glm::vec2 offset) {
    if (!camera_) {
        camera_ = compile("camera_rays.comp", false);
        set_uniforms(camera_);
    }
    if (!trace_) {
        trace_ = compile("trace.comp", true);
        set_uniforms(trace_);
    }
    rays_in_.reserve(pixels_ * sizeof(WavefrontRay));
    rays_in_.bind(kBindingRaysIn);
    camera_.set("wf_sample_offset", offset);
    const glm::uvec3 local = camera_.local_size();
    PassTimer timed(timer, "camera_rays");
    camera_.dispatch((unsigned(settings_.width) + local.x - 1) / local.x,
                     (unsigned(settings_.height) + local.y - 1) / local.y);
    record_pass("camera_rays");
    pass_barrier();
    timed.end();
    run_trace(pixels_);
    shade_sample();
}

void Wavefront::shade_sample() {
    pass_barrier();
    std::size_t hits = read_queue_count(kQueueHits);
    // One bounce per iteration: shade the hits, trace their shadow rays, then their reflection/refraction rays.
    // The shade pass spawns no ray at depth max_depth, so the loop ends after at most max_depth + 1 shade passes.
    while (hits > 0) {
        run_shade(hits);
        const std::vector<std::uint32_t> counts = queue_counts_.download<std::uint32_t>(4);
        if (counts[kQueueShadowRays] > 0) run_shadow(counts[kQueueShadowRays]);
        const std::size_t rays = counts[kQueueRaysOut];
        if (rays == 0) break;
        std::swap(rays_in_, rays_out_);   // this bounce's output is the next trace pass' input
        run_trace(rays);
        hits = read_queue_count(kQueueHits);
    }
    resolve();
    ++samples_;
}

void Wavefront::run_shade(std::size_t hits) {
    const PassTimer timed(timer, "shade");
    // Every hit spawns at most one reflection and one refraction ray, and one shadow ray per light.
    if (secondary_) rays_out_.reserve(2 * hits * sizeof(WavefrontRay));
    if (shadows_) shadow_rays_.reserve(std::size_t(lights_) * hits * sizeof(WavefrontRay));
    clear_queue_counts();
    pass_barrier();
    hits_.bind(kBindingHits);
    bind_if(rays_out_, kBindingRaysOut);
    bind_if(shadow_rays_, kBindingShadowRays);
    radiance_.bind(kBindingRadiance);
    queue_counts_.bind(kBindingQueueCounts);
    shade_.set("wf_input_count", unsigned(hits));
    shade_.dispatch_threads(hits);
    record_pass("shade");
    pass_barrier();
    check_gl("wavefront: shade pass");
}

void Wavefront::run_shadow(std::size_t rays) {
    const PassTimer timed(timer, "shadow");
    shadow_rays_.bind(kBindingShadowRays);
    radiance_.bind(kBindingRadiance);
    bind_traversal();
    shadow_.set("wf_input_count", unsigned(rays));
    shadow_.dispatch_threads(rays);
    record_pass("shadow");
    pass_barrier();
    check_gl("wavefront: shadow pass");
}

void Wavefront::run_trace(std::size_t rays) {
    const PassTimer timed(timer, "trace");
    hits_.reserve(rays * sizeof(WavefrontHit));   // at most one hit per ray
    clear_queue_counts();
    pass_barrier();
    rays_in_.bind(kBindingRaysIn);
    hits_.bind(kBindingHits);
    radiance_.bind(kBindingRadiance);
    queue_counts_.bind(kBindingQueueCounts);
    bind_traversal();
    trace_.set("wf_input_count", unsigned(rays));
    trace_.dispatch_threads(rays);
    record_pass("trace");
    pass_barrier();
    check_gl("wavefront: trace pass");
}

void Wavefront::resolve() {
    const PassTimer timed(timer, "resolve");
    radiance_.bind(kBindingRadiance);
    image_.bind(kBindingImage);
    resolve_.dispatch_threads(pixels_);
    record_pass("resolve");
    pass_barrier();
    check_gl("wavefront: resolve pass");
}

Image Wavefront::finish_frame(RayCounters& counters) {
    Image image(settings_.width, settings_.height);
    const std::vector<glm::vec4> sums = image_.download<glm::vec4>(pixels_);
    for (std::size_t i = 0; i < pixels_; ++i) image.pixels[i] = glm::vec3(sums[i]) / float(std::max(samples_, 1));
    counters = counters_.ray_counters();
    // Primary rays are one per pixel and sample, whether the stage rasterized or traced them.
    counters.rays[int(RayKind::Primary)] = std::uint64_t(pixels_) * std::uint64_t(samples_);
    check_gl("wavefront: finish frame");
    return image;
}

}  // namespace rt::gpu
