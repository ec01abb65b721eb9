// Stage 02: the raster/ray-tracing hybrid (Roger, Assarsson & Holzschuch 2007, "Whitted Ray-Tracing for Dynamic
// Scenes using a Ray-Space Hierarchy on the GPU"; Reis). Primary rays give exactly what rasterization gives, so
// the GPU rasterizes them into a G-buffer, and only the secondary rays (shadow, reflection, refraction) are traced,
// by the wavefront pipeline of common/gpu/wavefront.h with a brute-force traversal (common/shaders/brute_force.glsl).
#pragma once

#include <memory>
#include <string>

#include "common/app/renderer.h"
#include "common/gpu/context.h"
#include "common/gpu/window_presenter.h"

namespace rt {

class HybridRenderer : public Renderer {
public:
    HybridRenderer();
    ~HybridRenderer() override;

    void add_options(CLI::App& app) override;       // --backend, --window, --screenshot, --gl-debug
    void initialize() override;                     // creates the GL context (headless, or a window)
    std::string renderer_name() const override;     // GL_RENDERER
    // Without initialize() (unit tests), renders with whatever GL context is current.
    FrameResult render(const Scene& scene, const RenderSettings& settings) override;
    // --window without --screenshot: the window stays open (and animated scenes loop) until it is closed.
    bool interactive() const override { return gpu_options.window && gpu_options.screenshot.empty() && !closed_; }

    gpu::GpuOptions gpu_options;

private:
    struct Gpu;   // everything that needs a context: scene upload, G-buffer, pipeline
    CLI::App* app_ = nullptr;
    gpu::GpuContext context_;    // declared before gpu_: destroyed after it
    std::unique_ptr<Gpu> gpu_;
    gpu::WindowPresenter window_;   // --window only
    bool closed_ = false;           // the user closed the window
};

}  // namespace rt
