#include "viewer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "common/app/exposure.h"
#include "common/app/heatmap.h"

namespace rt::gpu {

namespace {
constexpr int kMaxViewerDepth = 64;           // as --max-depth
constexpr float kMoveSceneSizesPerSecond = 0.25f;
double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

Viewer::~Viewer() {
    if (!moving_.ms.empty() || !full_.ms.empty()) say("viewer: " + summary());
}

std::string Viewer::summary() const {
    char line[256];
    std::snprintf(line, sizeof line,
                  "%zu frames while moving (median %.1f ms at %dx%d), %zu at full resolution (median %.1f ms at %dx%d)",
                  moving_.ms.size(), median(moving_.ms), moving_.width, moving_.height, full_.ms.size(),
                  median(full_.ms), full_.width, full_.height);
    return line;
}

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
    const bool writes_frame = requested.need_image;   // the driver writes this frame: full resolution, as headless
    const double since_motion = std::chrono::duration<double>(Clock::now() - last_motion_).count();
    reduced_ = !writes_frame && !save_next_ && since_motion < kSettleSeconds && reduction_ > 1;
    if (reduced_) {
        settings.width = std::max(1, (requested.width + reduction_ - 1) / reduction_);
        settings.height = std::max(1, (requested.height + reduction_ - 1) / reduction_);
        settings.spp = 1;
    }
    if (settings.exposure.automatic) settings.need_image = true;   // its EV comes from the image, on the CPU
    dirty_ = false;
    return settings;
}

void Viewer::choose_reduction(double frame_ms) {
    // Time grows about with the pixel count, so 1/r per axis costs about 1/r^2 of a full frame. The first guess
    // comes from the full frame's time; later moving frames correct it by a factor of 2 either way.
    if (fixed_reduction_ > 0) return;
    if (!reduced_) {
        if (reduction_ == 0) {
            reduction_ = 1;
            while (reduction_ < kMaxReduction && frame_ms / double(reduction_ * reduction_) > kMovingTargetMs)
                reduction_ *= 2;
        }
        return;
    }
    if (frame_ms > kMovingTargetMs && reduction_ < kMaxReduction) reduction_ *= 2;
    else if (reduction_ > 1 && frame_ms * 4.0 < kMovingTargetMs) reduction_ /= 2;   // 4x the pixels still fit
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
    const bool moves = input.moves_camera();
    if (moves) {
        last_motion_ = now;
        dirty_ = true;
    }
    if (!input.keys.empty()) dirty_ = true;   // every key changes the frame, or asks for one (P)
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

    const int shown_reduction = reduction_;
    Tally& tally = reduced_ ? moving_ : full_;
    tally.ms.push_back(frame_ms);
    tally.width = settings.width;
    tally.height = settings.height;
    choose_reduction(std::max(0.0, frame_ms - frame.stats.compile_ms));   // a shader compile is not the frame's cost

    // The title: what this frame was and what it cost.
    const double rays = double(frame.stats.traced_rays());
    char resolution[64], speed[64];
    if (reduced_)
        std::snprintf(resolution, sizeof resolution, "moving: %dx%d (1/%d)", settings.width, settings.height,
                      shown_reduction);
    else
        std::snprintf(resolution, sizeof resolution, "%dx%d", settings.width, settings.height);
    if (rays > 0.0 && frame_ms > 0.0)
        std::snprintf(speed, sizeof speed, "%.2f M traced rays/s | %.1f ray-triangle tests per ray",
                      rays / (frame_ms * 1e3), double(frame.stats.counters.intersection_tests) / rays);
    else
        std::snprintf(speed, sizeof speed, "no rays traced");
    char title[320];
    std::snprintf(title, sizeof title, "%s | %s | %.1f ms per frame | %s | depth %d%s%s%s%s%s", stage_.c_str(),
                  resolution, frame_ms, speed, settings.max_depth, settings.effects.shadows ? " | shadows" : "",
                  settings.effects.reflections ? " | reflections" : "",
                  settings.effects.refractions ? " | refractions" : "", heatmap_ ? " | heatmap" : "",
                  paused_ ? " | paused" : "");
    context.set_title(title);
    handle(context.take_input());

    return open && !context.should_close();
}

void Viewer::heatmap_unavailable(const std::string& why) {
    heatmap_ = false;
    say("no heatmap: " + why);
}

bool Viewer::wait_for_change(GpuContext& context, const Scene& scene) {
    // A still, refined view waits for input; a reduced one until it settles (then the frame refines it).
    const bool animating = scene.animated && !paused_;
    while (!dirty_ && !animating && !context.should_close()) {
        if (reduced_) {
            const double left = kSettleSeconds - std::chrono::duration<double>(Clock::now() - last_motion_).count();
            if (left <= 0.0) break;
            context.wait_events(left);
        } else {
            context.wait_events(0.5);
        }
        handle(context.take_input());
    }
    return !context.should_close();
}

}  // namespace rt::gpu
