// The interactive viewer of the GPU stages (--window): between frames it reads the window's mouse and keys and
// decides what the next frame renders (camera, paused animation, effects, recursion depth) and shows (the image
// or the tests-per-pixel heatmap). The camera math is common/app/camera_control.h; GLFW stays in context_glfw.cpp.
//
// A key toggles only an effect the scene calls for (--effects), and a toggle changes the frame's Effects, so the
// wavefront recompiles its passes for the new variant: an effect that is off has no code, exactly as in a headless
// run with that --effects list (which renders the same image).
#pragma once

#include <chrono>
#include <optional>
#include <string>

#include "../app/camera_control.h"
#include "../app/renderer.h"
#include "context.h"
#include "window_presenter.h"

namespace rt::gpu {

class Viewer {
public:
    explicit Viewer(std::string stage) : stage_(std::move(stage)) {}

    // The mouse and key list, one control a line (printed when the window opens; README.md has the same).
    static std::string key_help();

    // Before a frame: the scene it renders (the viewer's camera once the user moved it; the frame paused on) and
    // its settings (effects turned off, the depth chosen, tests per pixel for the heatmap).
    const Scene& scene_for_frame(const Scene& scene);
    RenderSettings settings_for_frame(const RenderSettings& settings);

    // After the frame: shows it (the wavefront's image with the exposure applied, straight from the GPU; or the
    // heatmap), writes the stage, frame time, Mrays/s and tests per ray into the title, saves the screenshot asked
    // for (`screenshot`, else one the P key asked for), then takes the input for the next frame. Returns false once
    // the user closed the window.
    bool show(GpuContext& context, WindowPresenter& presenter, const Wavefront& wavefront, const FrameResult& frame,
              const RenderSettings& settings, double frame_ms, const std::string& screenshot);

private:
    void handle(const WindowInput& input);
    void toggle(bool Effects::*effect, const char* name);
    std::string next_screenshot_name() const;
    void say(const std::string& line) const;

    std::string stage_;
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
};

}  // namespace rt::gpu
