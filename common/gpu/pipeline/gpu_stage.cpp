#include "gpu_stage.h"

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include <CLI/CLI.hpp>

#include "common/app/pixel_samples.h"
#include "common/gpu/gl/gl_counters.h"
#include "common/gpu/gl/shader.h"

namespace rt::gpu {

struct GpuStage::Shared {
    explicit Shared(Traversal& traversal) : wavefront(traversal) {}
    GpuScene scene;
    Wavefront wavefront;
    GpuTimer timer;
};

GpuStage::GpuStage(std::unique_ptr<PrimaryVisibility> primary, std::unique_ptr<Traversal> traversal)
    : primary_(std::move(primary)), traversal_(std::move(traversal)) {}

GpuStage::~GpuStage() {
    shared_.reset();   // GL objects go before the context (the traversal's and primary's by declaration order)
}

void GpuStage::add_options(CLI::App& app) {
    add_gpu_options(app, gpu_options);
    traversal_->add_options(app);
    app_ = &app;
}

std::string GpuStage::unsupported(const Scene& scene, const RenderSettings& settings) const {
    return traversal_->unsupported(scene, settings);
}

void GpuStage::initialize() {
    if (gpu_options.window && app_) {
        // The window shows the image pixel for pixel (so --screenshot equals the headless image).
        gpu_options.window_width = app_->get_option("--width")->as<int>();
        gpu_options.window_height = app_->get_option("--height")->as<int>();
    }
    context_ = create_context(gpu_options);
    if (context_.is_window()) {
        const bool quiet = app_ && app_->get_option("--quiet")->as<bool>();
        viewer_ = std::make_unique<Viewer>(app_ ? app_->get_name() : "gpu stage", gpu_options.moving_scale);
        if (!quiet) {
            std::printf("%s", Viewer::key_help().c_str());
            std::fflush(stdout);
        }
    }
}

std::string GpuStage::renderer_name() const {
    if (context_.valid()) return context_.renderer();
    const GLubyte* name = glGetString ? glGetString(GL_RENDERER) : nullptr;
    return name ? reinterpret_cast<const char*>(name) : "unknown";
}

void GpuStage::add_phase_times(const std::vector<std::pair<std::string, double>>& phases, FrameStats& stats) {
    const std::map<std::string, double FrameStats::*> bucket = {
        {"upload", &FrameStats::upload_ms}, {"build", &FrameStats::build_ms},   {"raster", &FrameStats::raster_ms},
        {"trace", &FrameStats::trace_ms},   {"shadow", &FrameStats::trace_ms},  {"shade", &FrameStats::shade_ms},
        {"resolve", &FrameStats::shade_ms}, {"camera_rays", &FrameStats::shade_ms}};
    for (const auto& [phase, ms] : phases) {
        const auto it = bucket.find(phase);
        if (it != bucket.end()) stats.*(it->second) += ms;
    }
}

FrameResult GpuStage::render(const Scene& requested_scene, const RenderSettings& requested_settings) {
    // A frame only the window shows waits until something changes it (viewer.h); none once the window closed.
    if (viewer_ && !requested_settings.need_image && !viewer_->wait_for_change(context_, requested_scene)) {
        closed_ = true;
        return {};
    }
    const auto start = std::chrono::steady_clock::now();
    // In a window the viewer may render another camera, a paused frame, other effects or depth (viewer.h).
    const Scene& scene = viewer_ ? viewer_->scene_for_frame(requested_scene) : requested_scene;
    RenderSettings settings = viewer_ ? viewer_->settings_for_frame(requested_settings) : requested_settings;
    if (viewer_ && settings.record_tests_per_pixel && !requested_settings.record_tests_per_pixel) {
        // The H key asked for a heatmap this stage cannot count for this scene: say why, show the image.
        if (const std::string why = unsupported(scene, settings); !why.empty()) {
            viewer_->heatmap_unavailable(why);
            settings.record_tests_per_pixel = false;
        }
    }
    if (context_.valid()) context_.make_current();
    if (!shared_) shared_ = std::make_unique<Shared>(*traversal_);
    Shared& s = *shared_;
    s.timer.reset();
    s.wavefront.timer = &s.timer;
    const double compile_before = shader_compile_ms();
    const GlCounters start_counts = gl_counters();
    FrameResult result;

    // The scene goes to the GPU when it changed (a still scene stays resident: gpu_scene.h), then the stage's
    // structure.
    std::size_t scene_bytes = 0;
    {
        auto upload = s.timer.scope("upload");
        scene_bytes = s.scene.upload(scene);
    }
    s.wavefront.begin_frame(s.scene, settings);   // compiles the passes when the variant changes
    const FrameInputs frame{scene, settings, s.scene, s.timer, !primary_->rasterized()};
    traversal_->build(frame);
    {
        // Progress over every sample's 8x8 tiles, shown once the frame has taken a second (not in a window, whose
        // title says what a frame costs; not with --quiet).
        const long tiles = long((settings.width + 7) / 8) * long((settings.height + 7) / 8) * long(settings.spp);
        Progress progress(app_ ? app_->get_name() : "gpu stage", tiles, !settings.quiet && !viewer_);
        s.wavefront.progress = &progress;
        for (const glm::vec2& offset : pixel_sample_offsets(settings.spp))
            primary_->render_sample(frame, s.wavefront, offset);
        s.wavefront.progress = nullptr;
        progress.finish();
    }
    const GlCounters mid_frame = gl_counters();
    s.wavefront.finish_frame(result);   // image, counters, and the hits and per-pixel tests when asked for

    // Stats every GPU stage reports.
    const std::vector<std::pair<std::string, double>> phases = s.timer.results();
    add_phase_times(phases, result.stats);
    result.stats.compile_ms = shader_compile_ms() - compile_before;
    if (primary_->rasterized()) result.stats.rasterized_rays = result.stats.counters.rays[int(RayKind::Primary)];
    nlohmann::json pass_times = nlohmann::json::object();
    for (const auto& [phase, ms] : phases) pass_times[phase] = ms;
    result.extra["pass_time_ms"] = pass_times;
    result.extra["backend"] = context_.valid() ? context_.backend() : "current";
    result.extra["passes"] = s.wavefront.passes();
    result.extra["pass_dispatches"] = s.wavefront.dispatches();
    nlohmann::json defines = nlohmann::json::object();
    for (const auto& [k, v] : s.wavefront.defines()) defines[k] = v;
    result.extra["shader_defines"] = defines;
    std::vector<std::string> programs = s.wavefront.programs();
    for (std::vector<std::string> own : {primary_->programs(), traversal_->programs()})
        for (std::string& p : own) programs.push_back(std::move(p));
    result.extra["programs"] = programs;
    // The traversal's stats section; the frame's read-backs (each a wait for the GPU) are the pipeline's and the
    // traversal's (which says how many in its own section).
    traversal_->end_frame();
    FrameReport report{result};
    traversal_->report(report);
    result.extra["gpu_cpu_syncs"] = s.wavefront.syncs() + report.syncs;
    // What the CPU asked of the GPU this frame (gl_counters.h): dispatches, waits inside the frame and after its last
    // pass, and the bytes sent (the scene's, and the rest: the scene block, uniforms of the passes' own buffers).
    const GlCounters& end = gl_counters();
    result.extra["gl_dispatches"] = end.dispatches - start_counts.dispatches;
    result.extra["read_backs"] = {{"mid_frame", mid_frame.read_backs - start_counts.read_backs},
                                  {"frame_end", end.read_backs - mid_frame.read_backs}};
    result.extra["upload_bytes"] = {{"scene", scene_bytes},
                                    {"other", end.upload_bytes - start_counts.upload_bytes - scene_bytes}};

    if (viewer_) {
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        closed_ = !viewer_->show(context_, window_, s.wavefront, result, settings, ms, gpu_options.screenshot);
    }
    return result;
}

}  // namespace rt::gpu
