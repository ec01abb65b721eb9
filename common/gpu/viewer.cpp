#include "viewer.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "../app/exposure.h"
#include "../app/heatmap.h"

namespace rt::gpu {

namespace {
constexpr int kMaxViewerDepth = 64;           // as --max-depth
constexpr float kMoveSceneSizesPerSecond = 0.25f;
}  // namespace

std::string Viewer::key_help() {
    return "viewer controls:\n"
           "  left drag          orbit about the point in the middle of the view\n"
           "  right/middle drag  pan (or shift + left drag)\n"
           "  wheel              zoom toward that point\n"
           "  W A S D / Q E      move forward, left, back, right / down, up\n"
           "  R                  reset the camera to the scene's\n"
           "  1 2 3              toggle shadows, reflections, refractions (those the scene has)\n"
           "  + -                recursion depth up, down\n"
           "  H                  image / tests-per-pixel heatmap\n"
           "  space              pause / resume the animation\n"
           "  P                  save a screenshot (<stage>_view_NNNN.png in the current folder)\n"
           "  Esc                close\n";
}

void Viewer::say(const std::string& line) const {
    std::printf("%s: %s\n", stage_.c_str(), line.c_str());
    std::fflush(stdout);
}

const Scene& Viewer::scene_for_frame(const Scene& scene) {
    if (!paused_) paused_scene_.reset();
    else if (!paused_scene_) paused_scene_ = scene;
    const Scene& base = paused_scene_ ? *paused_scene_ : scene;
    scene_camera_ = base.camera;
    scene_bounds_ = base.bounds;
    if (!camera_moved_) return base;
    view_ = base;
    view_.camera = rig_.camera;
    return view_;
}

RenderSettings Viewer::settings_for_frame(const RenderSettings& requested) {
    RenderSettings settings = requested;
    available_ = requested.effects;
    settings.effects.shadows &= !off_.shadows;
    settings.effects.reflections &= !off_.reflections;
    settings.effects.refractions &= !off_.refractions;
    if (max_depth_ >= 0) settings.max_depth = max_depth_;
    if (heatmap_) settings.record_tests_per_pixel = true;
    if (settings.exposure.automatic) settings.need_image = true;   // its EV comes from the image, on the CPU
    return settings;
}

void Viewer::toggle(bool Effects::*effect, const char* name) {
    if (!(available_.*effect)) {
        say(std::string("this scene has no ") + name + " (--effects): nothing to toggle");
        return;
    }
    off_.*effect = !(off_.*effect);
    say(std::string(name) + (off_.*effect ? " off" : " on"));
}

std::string Viewer::next_screenshot_name() const {
    for (int i = 0;; ++i) {
        char name[64];
        std::snprintf(name, sizeof name, "_view_%04d.png", i);
        const std::string path = stage_ + name;
        if (!std::filesystem::exists(path)) return path;   // never replaces a file
    }
}

void Viewer::handle(const WindowInput& input) {
    const auto now = std::chrono::steady_clock::now();
    const float dt = std::min(std::chrono::duration<float>(now - last_input_).count(), 0.1f);
    last_input_ = now;
    const bool moves = input.orbit_drag != glm::vec2(0.0f) || input.pan_drag != glm::vec2(0.0f) ||
                       input.scroll != 0.0f || input.held != glm::vec3(0.0f);
    if (moves && !camera_moved_) {
        rig_ = make_rig(scene_camera_, scene_bounds_);
        camera_moved_ = true;
    }
    if (moves) {
        rig_ = orbit(rig_, input.orbit_drag);
        rig_ = pan(rig_, input.pan_drag, input.window_height);
        rig_ = zoom(rig_, input.scroll);
        const float size = scene_bounds_.empty() ? 1.0f : scene_bounds_.diagonal();
        if (input.held != glm::vec3(0.0f)) rig_ = move(rig_, input.held, kMoveSceneSizesPerSecond * size * dt);
    }
    for (const char key : input.keys) {
        switch (key) {
        case 'r': camera_moved_ = false; say("camera reset"); break;
        case '1': toggle(&Effects::shadows, "shadows"); break;
        case '2': toggle(&Effects::reflections, "reflections"); break;
        case '3': toggle(&Effects::refractions, "refractions"); break;
        case '+': case '-':
            max_depth_ = std::clamp(max_depth_ + (key == '+' ? 1 : -1), 0, kMaxViewerDepth);
            say("recursion depth " + std::to_string(max_depth_));
            break;
        case 'h': heatmap_ = !heatmap_; say(heatmap_ ? "showing tests per pixel" : "showing the image"); break;
        case ' ': paused_ = !paused_; say(paused_ ? "paused" : "playing"); break;
        case 'p': save_next_ = true; break;
        default: break;
        }
    }
}

bool Viewer::show(GpuContext& context, WindowPresenter& presenter, const Wavefront& wavefront,
                  const FrameResult& frame, const RenderSettings& settings, double frame_ms,
                  const std::string& screenshot) {
    if (max_depth_ < 0) max_depth_ = settings.max_depth;
    std::string save = screenshot;
    if (save.empty() && save_next_) save = next_screenshot_name();
    bool open = true;
    if (heatmap_)   // the tests per pixel were read back for the false colours (make_heatmap)
        open = presenter.present(
            context, make_heatmap(frame.tests_per_pixel, settings.width, settings.height, HeatmapScale::Linear).image, save);
    else if (settings.exposure.automatic)   // the EV depends on the image's percentile, computed on the CPU
        open = presenter.present(context, apply_exposure(frame.image, settings.exposure), save);
    else
        open = presenter.present_frame(context, wavefront, settings.exposure, save);
    if (save_next_ && screenshot.empty()) say("saved " + save);
    save_next_ = false;

    const double rays = double(frame.stats.traced_rays());
    char title[256];
    std::snprintf(title, sizeof title, "%s | %.1f ms | %.2f Mrays/s | %.1f tests/ray | depth %d%s%s%s%s%s",
                  stage_.c_str(), frame_ms, frame_ms > 0.0 ? rays / (frame_ms * 1e3) : 0.0,
                  rays > 0.0 ? double(frame.stats.counters.intersection_tests) / rays : 0.0, settings.max_depth,
                  settings.effects.shadows ? " | shadows" : "", settings.effects.reflections ? " | reflections" : "",
                  settings.effects.refractions ? " | refractions" : "", heatmap_ ? " | heatmap" : "",
                  paused_ ? " | paused" : "");
    context.set_title(title);
    handle(context.take_input());
    return open;
}

}  // namespace rt::gpu
