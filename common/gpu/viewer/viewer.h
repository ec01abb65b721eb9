// The interactive viewer of the GPU stages (--window): between frames it reads the window's mouse and keys and
// decides what the next frame renders (camera, paused animation, effects, recursion depth) and shows (the image
// or the tests-per-pixel heatmap). The camera math is common/app/camera_control.h; GLFW stays in context_glfw.cpp.
//
// A key toggles only an effect the scene calls for (--effects), and a toggle changes the frame's Effects, so the
// wavefront recompiles its passes for the new variant: an effect that is off has no code, exactly as in a headless
// run with that --effects list (which renders the same image).
//
// Interactive on a software renderer: while the camera moves, each frame renders at 1/r of the resolution per axis
// with one sample per pixel, shown scaled up; r (1, 2, 4, 8 or 16) is chosen from the measured frame times so a
// moving frame takes about kMovingTargetMs. kSettleSeconds after the last movement the view renders once at full
// resolution, and then nothing renders until an input (or a playing animation) changes the frame. Frames the run
// writes (--frames, --screenshot) and frames the P key saves are always full resolution.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "common/app/camera_control.h"
#include "common/app/renderer.h"
#include "common/gpu/gl/context.h"
#include "window_presenter.h"

namespace rt::gpu {

class Viewer {
public:
    // moving_scale: --moving-scale (0: auto, else the fixed 1/N of a moving frame).
    explicit Viewer(std::string stage, int moving_scale = 0)
        : stage_(std::move(stage)), fixed_reduction_(moving_scale), reduction_(moving_scale) {}
    ~Viewer();   // prints the frame times (summary()), as it prints what each key did

    static constexpr double kMovingTargetMs = 66.0;   // 15 frames per second
    static constexpr double kSettleSeconds = 0.25;
    static constexpr int kMaxReduction = 16;

    // The mouse and key list, one control a line (printed when the window opens; README.md has the same).
    static std::string key_help();

    // Before a frame: the scene it renders (the viewer's camera once the user moved it; the frame paused on) and
    // its settings (effects turned off, the depth chosen, tests per pixel for the heatmap).
    const Scene& scene_for_frame(const Scene& scene);
    RenderSettings settings_for_frame(const RenderSettings& settings);

    // After the frame: shows it (the wavefront's image with the exposure applied, straight from the GPU; or the
    // heatmap), writes the stage, resolution, frame time, rays per second and tests per ray into the title, saves the
    // screenshot asked for (`screenshot`, else one the P key asked for), then takes the input for the next frame.
    // Returns false once the user closed the window.
    bool show(GpuContext& context, WindowPresenter& presenter, const Wavefront& wavefront, const FrameResult& frame,
              const RenderSettings& settings, double frame_ms, const std::string& screenshot);

    // Before a frame only the window shows: returns at once when an input changed the view (or the scene is
    // animated and playing); else sleeps until one does, or until a reduced view has settled (the frame then
    // refines it). False when the user closed the window meanwhile (nothing to render).
    bool wait_for_change(GpuContext& context, const Scene& scene);

    // The stage cannot count tests per pixel for this scene (Renderer::unsupported): the H key's heatmap goes off.
    void heatmap_unavailable(const std::string& why);

    // "N frames while moving (median X ms at WxH), M at full resolution (median Y ms at WxH)": what a user (and
    // scripts/viewer-bench) reads off a session.
    std::string summary() const;

private:
    void handle(const WindowInput& input);
    void toggle(bool Effects::*effect, const char* name);
    std::string next_screenshot_name() const;
    void say(const std::string& line) const;
    void choose_reduction(double frame_ms);

    std::string stage_;
    int fixed_reduction_ = 0;             // --moving-scale N; 0: chosen from the frame times
    // The camera: the scene's own until the user moves it, then the rig's.
    bool camera_moved_ = false;
    CameraRig rig_;
    Camera scene_camera_;
    Bounds scene_bounds_;
    Scene view_;                          // the scene with the viewer's camera
    std::optional<Scene> paused_scene_;
    bool paused_ = false;
    // What the frame renders and shows.
    Effects available_, off_;             // the effects --effects asked for; those the user turned off
    int max_depth_ = -1;                  // -1: --max-depth
    bool heatmap_ = false;
    bool save_next_ = false;              // P: save the next frame (rendered with every input before it)
    std::chrono::steady_clock::time_point last_input_ = std::chrono::steady_clock::now();
    // Interactive speed (see the top of this file).
    using Clock = std::chrono::steady_clock;
    Clock::time_point last_motion_{};     // the last input that moved the camera
    bool dirty_ = true;                   // an input changed what the next frame shows
    bool reduced_ = false;                // the frame being rendered (then shown) is a reduced one
    int reduction_ = 0;                   // r of the next moving frame (0: not chosen yet)
    struct Tally {
        std::vector<double> ms;
        int width = 0, height = 0;
    };
    Tally moving_, full_;
};

}  // namespace rt::gpu
