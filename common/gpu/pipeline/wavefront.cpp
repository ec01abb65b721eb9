// The wavefront pipeline's scheduler (wavefront.h): a frame's variant and programs, then each sample's passes,
// bounce by bounce. Storage batching is in wavefront_storage.cpp, the recorded diagnostics (--dump-hits, --pixel)
// in wavefront_records.cpp.
#include "wavefront.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "common/gpu/gl/bindings.h"
#include "wavefront_detail.h"

namespace rt::gpu {

using namespace wavefront_detail;

Wavefront::Wavefront(Traversal& traversal)
    : traversal_(traversal),
      compact_(Program::compute("common/shaders/wavefront/compact_records.comp")),
      counters_(16) {}

void Wavefront::begin_frame(const GpuScene& scene, const RenderSettings& settings) {
    settings_ = settings;
    pixels_ = std::size_t(settings.width) * std::size_t(settings.height);   // before set_uniforms (wf_watch_base)
    triangles_ = scene.triangle_count();
    lights_ = unsigned(scene.light_count());
    punctual_lights_ = unsigned(scene.punctual_light_count());
    light_cells_ = scene.area_light_count() > 0 ? settings.light_grid.cells() : 1;
    samples_ = 0;
    pass_order_.clear();
    dispatches_.clear();
    syncs_ = 0;
    hit_records_.clear();

    // The variant: only the effects the scene calls for (settings.effects is already resolved from --effects).
    // Reflection and refraction rays need a bounce to go to; shadow rays need a light.
    Effects effects = settings.effects;
    if (settings.max_depth <= 0) effects.reflections = effects.refractions = false;
    shadows_ = effects.shadows && lights_ > 0;
    effects.shadows = shadows_;
    // BLEND coverage's transparency rays are secondary rays too, in a block of slots of their own (shade.comp).
    secondary_ = effects.reflections || effects.refractions || (effects.blend && settings.max_depth > 0);
    transparency_slots_ = secondary_ && effects.blend;
    ShaderDefines defines = effect_defines(effects);
    // shade.comp writes the secondary rays' slots only when they exist (BLEND shades with max_depth 0 too).
    if (secondary_) defines.insert_or_assign("WF_SECONDARY_RAYS", std::string("1"));
    defines.insert_or_assign("RT_INTERSECT_METHOD", std::string(settings.intersect == IntersectMethod::Watertight
                                                                    ? "RT_INTERSECT_WATERTIGHT"
                                                                    : "RT_INTERSECT_MOLLER"));
    if (count_tests || settings.record_tests_per_pixel) defines.insert_or_assign("COUNT_TESTS", std::string("1"));
    if (settings.record_tests_per_pixel) defines.insert_or_assign("RECORD_TESTS_PER_PIXEL", std::string("1"));
    if (settings.record_tests_per_pixel && settings.watch_pixel >= 0)
        defines.insert_or_assign("WATCH_PIXEL", std::string("1"));   // --pixel (wavefront.glsl, wf_watch)
    if (scene.has_environment()) defines.insert_or_assign("RT_ENVIRONMENT", std::string("1"));   // environment.glsl
    if (scene.has_vertex_colors()) defines.insert_or_assign("RT_VERTEX_COLORS", std::string("1"));   // scene.glsl
    if (scene.area_light_count() > 0) defines.insert_or_assign("RT_AREA_LIGHTS", std::string("1"));   // area_light.glsl
    if (scene.ambient() == AmbientModel::None) defines.insert_or_assign("RT_AMBIENT_NONE", std::string("1"));
    if (scene.ambient() == AmbientModel::Hemisphere)
        defines.insert_or_assign("RT_AMBIENT_HEMISPHERE", std::string("1"));   // shading.glsl, ambient_light
    for (const auto& [k, v] : traversal_.defines()) defines.insert_or_assign(k, v);
    std::string key;
    for (const auto& [k, v] : defines) key.append(k).append("=").append(v).append(";");
    if (key != compiled_key_) {
        defines_ = std::move(defines);
        compiled_key_ = key;
        compile_programs();
    }
    for (const Program* p : {&shade_, &shadow_, &trace_, &shadow_collect_, &trace_collect_, &resolve_, &camera_})
        if (*p) set_uniforms(*p);

    // Per-pixel buffers: this sample's radiance (fixed point) and the sum over samples.
    size_batches();
    const std::size_t tile_rows = (std::size_t(settings.height) + 7) / 8;
    const std::size_t band_rows = std::min(band_tile_rows_ * 8, std::size_t(settings.height));
    radiance_.resize(band_rows * std::size_t(settings.width) * kRadianceBytesPerPixel);
    radiance_.clear_u32(0);
    image_bands_.resize((tile_rows + band_tile_rows_ - 1) / band_tile_rows_);
    for (std::size_t b = 0; b < image_bands_.size(); ++b) {
        image_bands_[b].resize(band_pixels(b).second * sizeof(glm::vec4));
        image_bands_[b].clear_u32(0);   // 0x00000000 is 0.0f
    }
    if (settings.record_tests_per_pixel) {
        tests_per_pixel_.resize(tests_words() * sizeof(std::uint32_t));
        tests_per_pixel_.clear_u32(0);
        ray_work_.clear();
    } else {
        tests_per_pixel_ = Buffer();
    }
    if (!counts_) counts_ = Buffer(4 * sizeof(std::uint32_t));
    // One queue per depth, sized now: queue() hands out references that must stay valid through the recursion.
    // Queues of effects this variant does not simulate are not kept (without secondary rays: primary and shadow).
    queues_.resize(std::size_t(secondary_ ? std::max(settings.max_depth, 0) : 0) + 2);
    counters_.clear();
    scene.bind();
    counters_.bind();
    check_gl("wavefront: begin frame");
}

Program Wavefront::compile(const std::string& pass, bool with_traversal) const {
    std::string file = "common/shaders/wavefront/";
    file += pass;
    if (!with_traversal) return Program::compute(file, defines_);
    // The shadow pass traces shadow rays only: RT_SHADOW_RAYS gives them the shadow rule of the opacity test
    // (opacity.glsl: BLEND stays a cut-out for them).
    ShaderDefines defines = defines_;
    if (pass == "shadow.comp") defines.insert_or_assign("RT_SHADOW_RAYS", std::string("1"));
    // The traversal first (it defines trace_closest / trace_any), then the pass that calls it.
    std::string source = "// ";
    const std::string glsl = traversal_.glsl();
    source.append(file).append(" with the traversal ").append(glsl).append("\n");
    source.append("#include \"").append(glsl).append("\"\n");
    source.append("#include \"").append(file).append("\"\n");
    std::string name = file;
    name.append(" + ").append(glsl);
    return Program::compute_source(name, source, defines);
}

void Wavefront::compile_programs() {
    const bool batches = traversal_.traces_batches();   // then no trace and shadow passes of the pipeline's own
    shade_ = compile("shade.comp", false);
    resolve_ = compile("resolve.comp", false);
    shadow_ = shadows_ && !batches ? compile("shadow.comp", true) : Program();
    shadow_collect_ = shadows_ ? compile("shadow_collect.comp", false) : Program();
    trace_ = secondary_ && !batches ? compile("trace.comp", true) : Program();
    trace_collect_ = secondary_ ? compile("trace_collect.comp", false) : Program();
    camera_ = Program();   // compiled on first use (stages that trace primary rays)
}

std::vector<std::string> Wavefront::programs() const {
    std::vector<std::string> names;
    for (const Program* p :
         {&shade_, &shadow_, &trace_, &shadow_collect_, &trace_collect_, &resolve_, &camera_})
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
    p.set("wf_loop_probe", 2u);   // wf_check_loop_budget()
    p.set("wf_light_grid", unsigned(settings_.light_grid.n));   // shade.comp, with RT_AREA_LIGHTS
    p.set("wf_light_cells", unsigned(light_cells_));
    p.set("wf_light_jitter", settings_.light_grid.jitter ? 1 : 0);
    if (watching()) {
        p.set("wf_watch_pixel", unsigned(settings_.watch_pixel));
        p.set("wf_watch_base", unsigned(pixels_));
    }
}

void Wavefront::record_pass(const std::string& name) {
    if (dispatches_[name]++ == 0) pass_order_.push_back(name);
}

void Wavefront::bind_traversal() const {
    traversal_.bind();
}

// The rays of depth `depth` (then the shadow rays spawned at depth - 1); depth <= max_depth + 1.
Buffer& Wavefront::queue(int depth) { return queues_.at(std::size_t(depth)); }

// One sample, band by band: primary batches are runs of whole 8x8 tiles of the band, as many as one batch holds.
// A ray adds radiance only to its own pixel, so the band's sums are complete when its batches are done: resolve.
template <class F>
void Wavefront::for_each_tile_batch(F&& run_batch) {
    const std::size_t tiles_x = (std::size_t(settings_.width) + 7) / 8;
    const std::size_t tiles_y = (std::size_t(settings_.height) + 7) / 8;
    const std::size_t per_batch = std::max<std::size_t>(batch_ / kTilePixels, 1);
    for (std::size_t band = 0; band < image_bands_.size(); ++band) {
        const unsigned pixel_first = unsigned(band_pixels(band).first);
        for (const Program* p : {&shade_, &shadow_collect_, &trace_collect_})
            if (*p) p->set("wf_pixel_first", pixel_first);
        shade_.set("wf_sample_index", unsigned(samples_));   // --light-jitter's seed
        const std::size_t first_tile = band * band_tile_rows_ * tiles_x;
        const std::size_t end_tile = std::min(first_tile + band_tile_rows_ * tiles_x, tiles_x * tiles_y);
        for (std::size_t first = first_tile; first < end_tile; first += per_batch) {
            const std::size_t tiles = std::min(per_batch, end_tile - first);
            run_batch(first, tiles * kTilePixels, pixel_first);
            if (progress) progress->advance(long(tiles));
        }
        resolve(band);
    }
    if (watching()) drain_watch();
    ++samples_;
}

void Wavefront::shade_sample(const Program& primary_pass, const Program* deferred_rays) {
    // Cut-outs (stage 02): the primary pass defers the camera rays of pixels whose G-buffer candidate may be
    // transparent (a MASK or BLEND material) to its ray slots; they are traced with the traversal after the
    // rasterized hits.
    const bool defer = deferred_rays != nullptr;
    if (defer) prepare_camera_tracing();
    for_each_tile_batch([&](std::size_t first_tile, std::size_t slots, unsigned pixel_first) {
        hit_slots_.reserve(slots * sizeof(WavefrontHit));
        flags_.reserve(slots * sizeof(std::uint32_t));
        if (defer) {
            ray_slots_.reserve(slots * sizeof(WavefrontRay));
            ray_slots_.bind(kBindingWavefrontRaySlots);
        }
        set_uniforms(primary_pass);
        primary_pass.set("wf_tile_first", unsigned(first_tile));
        primary_pass.set("wf_pixel_first", pixel_first);
        primary_pass.set("wf_input_count", unsigned(slots));
        hit_slots_.bind(kBindingWavefrontHits);
        flags_.bind(kBindingWavefrontFlags);
        radiance_.bind(kBindingWavefrontRadiance);
        if (tests_per_pixel_) tests_per_pixel_.bind(kBindingWavefrontTestsPerPixel);   // tests it may make
        primary_pass.dispatch_threads(slots);
        record_pass("primary_hits");
        pass_barrier();
        check_gl("wavefront: primary hits");
        if (settings_.record_hits) record_primary_slots(slots);
        const std::size_t hits = compact(hit_slots_, slots, sizeof(WavefrontHit) / 4, hits_);
        // The deferred rays go to queue(0) (stage 02 has no other use for it) before shading overwrites the ray
        // slots and flags; they are traced once the rasterized hits and all their descendants are done.
        const std::size_t deferred = defer ? gather_deferred_rays(*deferred_rays, slots) : 0;
        if (hits > 0) process_hits(hits, 0);
        if (deferred > 0) run_rays(queue(0), {{0, deferred, RayKind::Primary, 0}}, 0);
    });
}

// Trace programs for camera rays: the stage's trace pass may not be compiled (a scene without reflections and
// refractions), but camera rays need it.
void Wavefront::prepare_camera_tracing() {
    if (!trace_ && !traversal_.traces_batches()) {
        trace_ = compile("trace.comp", true);
        set_uniforms(trace_);
    }
    if (!trace_collect_) {
        trace_collect_ = compile("trace_collect.comp", false);
        set_uniforms(trace_collect_);
    }
}

// Flags the primary pass' ray slots that hold a deferred camera ray and packs them into queue(0); returns how many.
std::size_t Wavefront::gather_deferred_rays(const Program& deferred_rays, std::size_t slots) {
    ray_slots_.bind(kBindingWavefrontRaySlots);
    flags_.bind(kBindingWavefrontFlags);
    deferred_rays.set("wf_input_count", unsigned(slots));
    deferred_rays.dispatch_threads(slots);
    record_pass("deferred_rays");
    pass_barrier();
    check_gl("wavefront: deferred rays");
    return compact(ray_slots_, slots, sizeof(WavefrontRay) / 4, queue(0));
}

void Wavefront::trace_camera_sample(glm::vec2 offset) {
    if (!camera_) {
        camera_ = compile("camera_rays.comp", false);
        set_uniforms(camera_);
    }
    prepare_camera_tracing();
    camera_.set("wf_sample_offset", offset);
    for_each_tile_batch([&](std::size_t first_tile, std::size_t slots, unsigned) {
        ray_slots_.reserve(slots * sizeof(WavefrontRay));
        flags_.reserve(slots * sizeof(std::uint32_t));
        camera_.set("wf_tile_first", unsigned(first_tile));
        camera_.set("wf_input_count", unsigned(slots));
        ray_slots_.bind(kBindingWavefrontRaySlots);
        flags_.bind(kBindingWavefrontFlags);
        PassTimer timed(timer, "camera_rays");
        camera_.dispatch_threads(slots);
        record_pass("camera_rays");
        pass_barrier();
        timed.end();
        Buffer& rays = queue(0);
        const std::size_t count = compact(ray_slots_, slots, sizeof(WavefrontRay) / 4, rays);
        if (count > 0) run_rays(rays, {{0, count, RayKind::Primary, 0}}, 0);
    });
}

// Shades `hits` hits (in hits_) of depth `depth`: their shadow rays are traced right away, their reflection and
// refraction rays go to queue(depth + 1) and are traced (with all their descendants) before this returns.
// Output slots of one shade run: [reflections | refractions (| transparency)] (secondary_) then one block of `hits`
// slots per light. When the lights' blocks do not all fit the storage limit, the lights are shaded in several runs;
// the last one also adds the local terms and spawns the reflection and refraction rays.
void Wavefront::process_hits(std::size_t hits, int depth) {
    const std::vector<SlotBlock> secondary_kinds = secondary_blocks();
    const std::size_t secondary_slots = secondary_kinds.size() * hits;
    Buffer& out = queue(depth + 1);
    std::vector<RayRun> secondary;
    if (!shadows_) {
        run_shade(hits, 0, lights_, true, 0);   // unshadowed lights are summed in the shade pass
        if (secondary_slots > 0) secondary = compact_blocks(hits, secondary_kinds, out);
    } else {
        // Runs of consecutive lights whose blocks fit beside the secondary slots (at least one light a run).
        const std::size_t slots_fit = storage_limit_ / sizeof(WavefrontRay);
        const std::size_t room = slots_fit > secondary_slots ? (slots_fit - secondary_slots) / hits : 0;
        for (unsigned first = 0; first < lights_;) {
            unsigned count = 1;
            std::size_t used = light_slots(first);
            while (first + count < lights_ && used + light_slots(first + count) <= room) used += light_slots(first + count++);
            const bool last = first + count == lights_;
            const std::size_t base = last ? secondary_slots : 0;
            run_shade(hits, first, count, last, base);
            std::vector<SlotBlock> blocks = last ? secondary_kinds : std::vector<SlotBlock>{};
            for (unsigned l = first; l < first + count; ++l) blocks.push_back({RayKind::Shadow, l, light_slots(l)});
            std::vector<RayRun> shadow;   // the runs after the secondary ones, from the first shadow ray on
            std::size_t shadow_first = 0;
            for (const RayRun& run : compact_blocks(hits, blocks, out)) {
                if (run.kind != RayKind::Shadow) {
                    secondary.push_back(run);
                    shadow_first = run.first + run.count;
                } else {
                    shadow.push_back(run);
                }
            }
            std::size_t shadow_count = 0;
            for (RayRun& run : shadow) {
                run.first -= shadow_first;
                shadow_count += run.count;
            }
            if (shadow_count > 0) run_shadow(out, shadow_first, shadow_count, std::move(shadow));
            first += count;
        }
    }
    if (!secondary.empty()) run_rays(out, secondary, depth + 1);
}

// The blocks of secondary slots a shade pass writes (shade.comp): reflections at i, refractions at n + i and, with
// BLEND, transparency rays at 2n + i.
std::vector<Wavefront::SlotBlock> Wavefront::secondary_blocks() const {
    if (!secondary_) return {};
    std::vector<SlotBlock> blocks = {{RayKind::Reflection, 0}, {RayKind::Refraction, 0}};
    if (transparency_slots_) blocks.push_back({RayKind::Transparency, 0});
    return blocks;
}

void Wavefront::run_shade(std::size_t hits, unsigned light_first, unsigned light_count, bool local,
                          std::size_t shadow_base) {
    const PassTimer timed(timer, "shade");
    std::size_t shadow_slots = 0;
    for (unsigned l = light_first; shadows_ && l < light_first + light_count; ++l) shadow_slots += light_slots(l) * hits;
    const std::size_t all_slots = std::max(shadow_base + shadow_slots,
                                           local ? secondary_blocks().size() * hits : std::size_t(0));
    ray_slots_.reserve(std::max<std::size_t>(all_slots, 1) * sizeof(WavefrontRay));
    flags_.reserve(std::max<std::size_t>(all_slots, 1) * sizeof(std::uint32_t));
    hits_.bind(kBindingWavefrontHits);
    ray_slots_.bind(kBindingWavefrontRaySlots);
    flags_.bind(kBindingWavefrontFlags);
    radiance_.bind(kBindingWavefrontRadiance);
    shade_.set("wf_input_count", unsigned(hits));
    shade_.set("wf_light_first", light_first);
    shade_.set("wf_light_count", light_count);
    shade_.set("wf_shadow_slot_base", unsigned(shadow_base));
    shade_.set("wf_shade_local", local ? 1 : 0);
    shade_.dispatch_threads(hits);
    record_pass("shade");
    pass_barrier();
    check_gl("wavefront: shade pass");
}

// Traces the rays of `runs` (queue order, from the queue's first ray) of depth `depth` from `rays`, in batches: the
// hits of each batch are shaded (and their descendants traced) before the next batch.
void Wavefront::run_rays(Buffer& rays, const std::vector<RayRun>& runs, int depth) {
    const std::size_t count = runs.empty() ? 0 : runs.back().first + runs.back().count;
    for (std::size_t first = 0; first < count; first += batch_) {
        const std::size_t n = std::min(batch_, count - first);
        std::vector<RayRun> batch_runs;   // the runs cut to the batch, from its first ray
        for (const RayRun& run : runs) {
            const std::size_t begin = std::max(run.first, first), end = std::min(run.first + run.count, first + n);
            if (begin < end) batch_runs.push_back({begin - first, end - begin, run.kind, run.light});
        }
        run_trace(rays, first, n, std::move(batch_runs));
        hit_slots_.reserve(n * sizeof(WavefrontHit));
        flags_.reserve(n * sizeof(std::uint32_t));
        hit_slots_.bind(kBindingWavefrontHits);
        flags_.bind(kBindingWavefrontFlags);
        run_collect(trace_collect_, rays, first, n);
        const std::size_t hits = compact(hit_slots_, n, sizeof(WavefrontHit) / 4, hits_);
        if (hits > 0) process_hits(hits, depth);
    }
}

void Wavefront::run_trace(Buffer& rays, std::size_t first, std::size_t count, std::vector<RayRun> runs) {
    run_traversal(false, rays, first, count, std::move(runs));
}

void Wavefront::run_shadow(Buffer& rays, std::size_t first, std::size_t count, std::vector<RayRun> runs) {
    run_traversal(true, rays, first, count, std::move(runs));
    run_collect(shadow_collect_, rays, first, count);
}

// The traversal of rays [first, first + count) into results_: closest hits (WavefrontTraceResult each) or, `shadow`,
// occlusion (a uint each); by the stage's batch callback, or by its GLSL in the trace or shadow pass.
void Wavefront::run_traversal(bool shadow, Buffer& rays, std::size_t first, std::size_t count,
                              std::vector<RayRun> runs) {
    const char* name = shadow ? "shadow" : "trace";
    const PassTimer timed(timer, name);
    results_.reserve(count * (shadow ? sizeof(std::uint32_t) : sizeof(WavefrontTraceResult)));
    if (traversal_.traces_batches()) {
        traversal_.trace_batch({rays, first, count, results_, tests_per_pixel_ ? &tests_per_pixel_ : nullptr, *this,
                                std::move(runs), triangles_},
                               shadow);
    } else {
        const Program& pass = shadow ? shadow_ : trace_;
        rays.bind(kBindingWavefrontRaysIn);
        results_.bind(kBindingWavefrontResults);
        if (tests_per_pixel_) tests_per_pixel_.bind(kBindingWavefrontTestsPerPixel);
        bind_traversal();
        pass.set("wf_input_first", unsigned(first));
        pass.set("wf_input_count", unsigned(count));
        pass.dispatch_threads(count);
    }
    record_pass(name);
    pass_barrier();
    check_gl(std::string("wavefront: ") + name + " pass");
    if (settings_.record_hits) record_rays(rays, first, count, shadow);
}

// The pass after a traversal: reads results_ (one per ray) and adds radiance (and, for trace, fills hit slots).
void Wavefront::run_collect(const Program& collect, Buffer& rays, std::size_t first, std::size_t count) {
    rays.bind(kBindingWavefrontRaysIn);
    results_.bind(kBindingWavefrontResults);
    radiance_.bind(kBindingWavefrontRadiance);
    collect.set("wf_input_first", unsigned(first));
    collect.set("wf_input_count", unsigned(count));
    collect.dispatch_threads(count);
    pass_barrier();
    check_gl("wavefront: collect pass");
}

void Wavefront::resolve(std::size_t band) {
    const PassTimer timed(timer, "resolve");
    radiance_.bind(kBindingWavefrontRadiance);
    image_bands_[band].bind(kBindingWavefrontImage);
    const std::size_t pixels = band_pixels(band).second;
    resolve_.set("wf_input_count", unsigned(pixels));
    resolve_.dispatch_threads(pixels);
    record_pass("resolve");
    pass_barrier();
    check_gl("wavefront: resolve pass");
}

Image Wavefront::finish_frame(RayCounters& counters) {
    Image image;
    if (settings_.need_image) image = Image(settings_.width, settings_.height);
    for (std::size_t band = 0; band < image_bands_.size() && settings_.need_image; ++band) {
        const auto [first, count] = band_pixels(band);
        const std::vector<glm::vec4> sums = image_bands_[band].download<glm::vec4>(count);
        ++syncs_;
        for (std::size_t i = 0; i < count; ++i)
            image.pixels[first + i] = glm::vec3(sums[i]) / float(std::max(samples_, 1));
    }
    const std::vector<std::uint64_t> all = counters_.read();
    ++syncs_;
    if (all[kCounterLoopsCut] != 0)
        throw std::runtime_error(
            "the GL driver ended the loops of " + std::to_string(all[kCounterLoopsCut]) +
            " shader invocations early, so this frame would be wrong: Mesa's llvmpipe stops an invocation after " +
            "65,535 loop iterations (docs/gpu.md, \"Known limit\"); render a smaller scene, or use a stage with an " +
            "acceleration structure or a hardware GPU");
    counters = counters_.ray_counters();
    // Primary rays are one per pixel and sample, whether the stage rasterized or traced them.
    counters.rays[int(RayKind::Primary)] = std::uint64_t(pixels_) * std::uint64_t(samples_);
    check_gl("wavefront: finish frame");
    return image;
}

std::vector<RayRun> ray_runs(const std::vector<WavefrontRay>& rays, std::size_t first, std::size_t count) {
    std::vector<RayRun> runs;
    for (std::size_t i = first; i < first + count && i < rays.size(); ++i) {
        const RayKind kind = RayKind(rays[i].depth_kind >> 16);
        const std::uint32_t light = kind == RayKind::Shadow ? rays[i].light : 0u;
        if (runs.empty() || runs.back().kind != kind || runs.back().light != light)
            runs.push_back({i - first, 0, kind, light});
        ++runs.back().count;
    }
    return runs;
}

}  // namespace rt::gpu
