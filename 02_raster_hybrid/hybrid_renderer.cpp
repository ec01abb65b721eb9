#include "hybrid_renderer.h"

#include <chrono>

#include <CLI/CLI.hpp>

#include "common/app/pixel_samples.h"
#include "common/gpu/gbuffer.h"
#include "common/gpu/gpu_scene.h"
#include "common/gpu/wavefront.h"

namespace rt {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The traversal stage 02 plugs into the wavefront pipeline: every ray against every triangle.
gpu::Traversal brute_force_traversal() { return {"common/brute_force.glsl", {}, {}}; }

}  // namespace

struct HybridRenderer::Gpu {
    gpu::GpuScene scene;
    gpu::GBuffer gbuffer;
    gpu::Wavefront wavefront{brute_force_traversal()};
};

HybridRenderer::HybridRenderer() = default;
HybridRenderer::~HybridRenderer() {
    gpu_.reset();   // GL objects go before the context
}

void HybridRenderer::add_options(CLI::App& app) {
    gpu::add_gpu_options(app, gpu_options);
    app_ = &app;
}

void HybridRenderer::initialize() {
    if (gpu_options.window && app_) {
        // The window shows the image pixel for pixel (so --screenshot equals the headless image).
        gpu_options.window_width = app_->get_option("--width")->as<int>();
        gpu_options.window_height = app_->get_option("--height")->as<int>();
    }
    context_ = gpu::create_context(gpu_options);
}

std::string HybridRenderer::renderer_name() const {
    if (context_.valid()) return context_.renderer();
    const GLubyte* name = glGetString ? glGetString(GL_RENDERER) : nullptr;
    return name ? reinterpret_cast<const char*>(name) : "unknown";
}

FrameResult HybridRenderer::render(const Scene& scene, const RenderSettings& settings) {
    if (context_.valid()) context_.make_current();
    if (!gpu_) gpu_ = std::make_unique<Gpu>();
    Gpu& g = *gpu_;
    FrameResult result;

    // Build: the scene goes to the GPU (once per frame; animated scenes change every frame).
    auto start = Clock::now();
    g.scene.upload(scene);
    g.wavefront.begin_frame(g.scene, settings);
    glFinish();
    double build_ms = ms_since(start), trace_ms = 0.0;

    for (const glm::vec2& offset : pixel_sample_offsets(settings.spp)) {
        // Pass 1: primary visibility by rasterization (counted as build time: it replaces the primary rays'
        // acceleration structure and traversal).
        start = Clock::now();
        g.gbuffer.render(g.scene, scene.camera, scene.bounds, settings.width, settings.height, offset);
        g.wavefront.record_pass("gbuffer");
        glFinish();
        build_ms += ms_since(start);
        // Passes 2..n: primary hits, then shading and the secondary rays, bounce by bounce.
        start = Clock::now();
        g.scene.bind();
        g.gbuffer.shade_sample(g.wavefront, offset);
        glFinish();
        trace_ms += ms_since(start);
    }
    g.wavefront.finish_frame(result);
    result.stats.build_ms = build_ms;
    result.stats.trace_ms = trace_ms;

    result.extra["backend"] = context_.valid() ? context_.backend() : "current";
    result.extra["passes"] = g.wavefront.passes();
    result.extra["pass_dispatches"] = g.wavefront.dispatches();
    nlohmann::json defines = nlohmann::json::object();
    for (const auto& [k, v] : g.wavefront.defines()) defines[k] = v;
    result.extra["shader_defines"] = defines;
    std::vector<std::string> programs = g.wavefront.programs();
    programs.push_back("raster/primary_hits.comp");
    result.extra["programs"] = programs;

    if (context_.is_window()) closed_ = !window_.present(context_, result.image, gpu_options.screenshot);
    return result;
}

}  // namespace rt
