// The shared base of the GPU stages (02-05): everything a GPU stage does that is not its technique. It creates the
// GL context from the GPU options (--backend, --window, --screenshot, --gl-debug), uploads the scene, runs the
// wavefront pipeline (wavefront.h) with the stage's traversal, times every phase with GPU timer queries, presents
// the frame in the window (and the screenshot), and fills the stats every GPU stage reports.
//
// A stage derives from it and writes only its per-frame code:
//   build()          its acceleration structure over the uploaded scene (optional: brute force has none),
//   render_sample()  one sample: its primary hits and the passes after them,
// and says what it adds to the stats (its own programs, whether its primary rays are rasterized). Stages 02-05
// rasterize their primary rays: they derive from stage 02's RasterizedPrimaryStage
// (02_raster_hybrid/rasterized_primary_stage.h), which derives from this class.
//
// A frame: upload (timed "upload") -> wavefront().begin_frame -> build() -> render_sample() per sample -> the
// image. Phases are GPU time (GL timestamps) of the passes in them: the stage times its own ("build", "raster"),
// wavefront() times its passes ("trace", "shadow", "shade", "resolve", "camera_rays").
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
#include "wavefront.h"
#include "common/gpu/viewer/viewer.h"
#include "common/gpu/viewer/window_presenter.h"

namespace rt::gpu {

class GpuStage : public Renderer {
public:
    explicit GpuStage(Traversal traversal);
    ~GpuStage() override;

    void add_options(CLI::App& app) override;     // --backend, --window, --screenshot, --gl-debug
    void initialize() override;                   // creates the GL context (headless, or a window)
    std::string renderer_name() const override;   // GL_RENDERER
    // Without initialize() (unit tests), renders with whatever GL context is current.
    FrameResult render(const Scene& scene, const RenderSettings& settings) final;
    // --window without --screenshot: the window stays open (and animated scenes loop) until it is closed.
    bool interactive() const override { return gpu_options.window && gpu_options.screenshot.empty() && !closed_; }

    GpuOptions gpu_options;

    // How the phases timed by the GPU timer add up to the stats' time_ms (the rest appear only in pass_time_ms):
    // "upload", "build", "raster" as they are; "trace" and "shadow" into trace; "shade", "resolve" and
    // "camera_rays" into shade.
    static void add_phase_times(const std::vector<std::pair<std::string, double>>& phases, FrameStats& stats);
    // A phase's GPU time in a finished frame (its pass_time_ms entry, "rh_build.shadow" say); 0 when it did not run.
    static double pass_ms(const FrameResult& result, const std::string& phase);
    // Adds a stage's read-backs of the frame to the stats' gpu_cpu_syncs (the pipeline's are there already).
    static void add_syncs(FrameResult& result, std::uint64_t syncs);

protected:
    // The stage's acceleration structure over the uploaded scene (gpu_scene()); time its passes with
    // timer().scope("build").
    virtual void build(const Scene& scene, const RenderSettings& settings);
    // One sample through `offset` in each pixel (0.5, 0.5 = the centre): wavefront().trace_camera_sample(offset)
    // traces the camera rays through the traversal; stage 02's RasterizedPrimaryStage rasterizes them instead.
    virtual void render_sample(const Scene& scene, const RenderSettings& settings, glm::vec2 offset) = 0;
    // True when the primary rays are rasterized, not traced (rays.rasterized, and left out of mrays_per_s).
    virtual bool rasterizes_primary_rays() const { return false; }
    // Programs of the stage's own passes, added to the stats' `programs`.
    virtual std::vector<std::string> stage_programs() const { return {}; }
    // The stage's work at the end of a frame, before its stats: what it reads back to remember for the next frames.
    virtual void end_frame() {}
    // The stage's own stats (e.g. stage 03's grid), added to result.extra after the frame.
    virtual void add_stage_stats(FrameResult& /*result*/) {}

    // The GL objects every stage uses (created with the first frame, once a context is current).
    GpuScene& gpu_scene();
    // Replaces the traversal given to the constructor; only before the first frame (stage 02's refers to a member).
    void set_traversal(Traversal traversal);
    Wavefront& wavefront();
    GpuTimer& timer();

private:
    struct Shared;
    CLI::App* app_ = nullptr;
    GpuContext context_;               // declared before the GL objects: destroyed after them
    Traversal traversal_;
    std::unique_ptr<Shared> shared_;
    WindowPresenter window_;           // --window only
    std::unique_ptr<Viewer> viewer_;   // --window only: mouse and keys between frames (viewer.h)
    bool closed_ = false;              // the user closed the window
};

}  // namespace rt::gpu
