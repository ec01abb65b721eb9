// The one interface every stage implements, and the settings the shared command line gives it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/scene/effects.h"
#include "common/scene/scene.h"
#include "common/trace/area_light.h"
#include "common/trace/intersect.h"
#include "common/trace/offset.h"
#include "common/trace/shading.h"
#include "exposure.h"
#include "common/trace/hit_record.h"
#include "image.h"
#include "stats.h"

namespace CLI { class App; }

namespace rt {

// Everything the shared command line decides about a frame (see common/app/options.cpp for the flags).
struct RenderSettings {
    int width = 640;
    int height = 480;
    int max_depth = 5;                                   // Whitted recursion depth (0 = primary hits only)
    int spp = 1;                                         // samples per pixel (anti-aliasing)
    float cutoff = kDefaultCutoff;                       // contribution cut-off on a path's weight
    FresnelMode fresnel = FresnelMode::Exact;
    IntersectMethod intersect = IntersectMethod::Watertight;
    OffsetMethod offset = OffsetMethod::Robust;
    float epsilon = kDefaultEpsilon;                     // used by --offset epsilon
    Effects effects;                                     // what to simulate (already resolved from --effects)
    LightGrid light_grid;                                // --light-grid, --light-jitter: area lights' samples
    int threads = 0;                                     // 0 = all hardware threads
    bool quiet = false;
    Exposure exposure;                                   // display only (exposure.h): the driver applies it to the
                                                         // saved image, a window to what it shows; not to shading
    // Diagnostics, off unless asked for (they cost time and memory):
    bool record_hits = false;             // --dump-hits: fill FrameResult::hits with every traced ray
    bool record_tests_per_pixel = false;  // --heatmap: fill FrameResult::tests_per_pixel
    std::int64_t watch_pixel = -1;        // --pixel X,Y: y * width + x; fill FrameResult::ray_work for its rays
    std::int64_t record_hits_pixel = -1;  // with record_hits: only this pixel's rays (--pixel without --dump-hits)
    bool need_image = true;               // false: a frame only a window shows; FrameResult::image may stay empty
                                          // (GPU stages then leave it on the GPU: no read-back)
};

struct FrameResult {
    Image image;
    FrameStats stats;
    nlohmann::json extra = nlohmann::json::object();     // stage-specific stats keys
    std::vector<HitRecord> hits;                         // with settings.record_hits (hit_record.h)
    std::vector<std::uint32_t> tests_per_pixel;          // with settings.record_tests_per_pixel: ray/triangle
                                                         // tests of all rays of each pixel's tree, y * width + x
    std::vector<RayWork> ray_work;                       // with settings.watch_pixel: what its rays cost
    std::string ray_work_steps;                          // what RayWork::steps counts in this stage ("" none)
};

class Renderer {
public:
    virtual ~Renderer() = default;
    // Adds the stage's own flags (e.g. --precision for 01, --backend for GPU stages). Called before parsing.
    virtual void add_options(CLI::App& /*app*/) {}
    // Called once after parsing, before the first frame (create GL contexts here). Throws on failure.
    virtual void initialize() {}
    // CPU model or GL_RENDERER.
    virtual std::string renderer_name() const = 0;
    // Renders one frame of a flattened scene.
    virtual FrameResult render(const Scene& scene, const RenderSettings& settings) = 0;
    // What this stage cannot do for this scene and these settings, said before anything renders (the driver then
    // exits 2 with this line); empty when it can.
    virtual std::string unsupported(const Scene& /*scene*/, const RenderSettings& /*settings*/) const { return {}; }
    // An interactive window that stays open after the requested frames: the driver keeps rendering (animated
    // scenes loop) until this turns false (the user closed the window).
    virtual bool interactive() const { return false; }
};

}  // namespace rt
