// A GPU stage (02-05): a primary visibility and a traversal, composed, plus everything a GPU stage does that is not
// its technique. It creates the GL context from the GPU options (--backend, --window, --screenshot, --gl-debug),
// uploads the scene, runs the wavefront pipeline (wavefront.h) with the traversal, times every phase with GPU timer
// queries, presents the frame in the window (and the screenshot), and fills the stats every GPU stage reports.
//
// A stage is the pair it is built from, e.g. stage 04:
//   GpuStage(std::make_unique<RasterizedPrimary>(), std::make_unique<HierarchyTraversal>())
// Its technique lives in the traversal (traversal.h: options, build, trace a batch, report); nothing derives from a
// stage to change what it does.
//
// A frame: upload (timed "upload") -> wavefront().begin_frame -> traversal.build() -> per sample the primary
// visibility's render_sample() -> the image -> traversal.end_frame() and report(). Phases are GPU time (GL
// timestamps) of the passes in them: the parts time their own ("build", "raster"), the pipeline its passes ("trace",
// "shadow", "shade", "resolve", "camera_rays").
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "common/app/renderer.h"
#include "common/gpu/gl/buffer.h"
#include "common/gpu/gl/context.h"
#include "gpu_scene.h"
#include "primary_visibility.h"
#include "traversal.h"
#include "wavefront.h"
#include "common/gpu/viewer/viewer.h"
#include "common/gpu/viewer/window_presenter.h"

namespace rt::gpu {

class GpuStage : public Renderer {
public:
    GpuStage(std::unique_ptr<PrimaryVisibility> primary, std::unique_ptr<Traversal> traversal);
    ~GpuStage() override;

    void add_options(CLI::App& app) final;     // --backend, --window, --screenshot, --gl-debug, the traversal's
    void initialize() final;                   // creates the GL context (headless, or a window)
    std::string renderer_name() const final;   // GL_RENDERER
    std::string unsupported(const Scene& scene, const RenderSettings& settings) const final;   // the traversal's
    // Without initialize() (unit tests), renders with whatever GL context is current.
    FrameResult render(const Scene& scene, const RenderSettings& settings) final;
    // --window without --screenshot: the window stays open (and animated scenes loop) until it is closed.
    bool interactive() const final { return gpu_options.window && gpu_options.screenshot.empty() && !closed_; }

    GpuOptions gpu_options;

    // How the phases timed by the GPU timer add up to the stats' time_ms (the rest appear only in pass_time_ms):
    // "upload", "build", "raster" as they are; "trace" and "shadow" into trace; "shade", "resolve" and
    // "camera_rays" into shade.
    static void add_phase_times(const std::vector<std::pair<std::string, double>>& phases, FrameStats& stats);

private:
    struct Shared;
    CLI::App* app_ = nullptr;
    GpuContext context_;               // declared before the GL objects: destroyed after them
    std::unique_ptr<PrimaryVisibility> primary_;
    std::unique_ptr<Traversal> traversal_;
    std::unique_ptr<Shared> shared_;
    WindowPresenter window_;           // --window only
    std::unique_ptr<Viewer> viewer_;   // --window only: mouse and keys between frames (viewer.h)
    bool closed_ = false;              // the user closed the window
};

}  // namespace rt::gpu
