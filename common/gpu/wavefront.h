// The wavefront Whitted pipeline every GPU stage shares (Laine, Karras & Aila 2013, "Megakernels Considered
// Harmful"): instead of one thread recursing through a ray tree as stage 01 does, rays wait in queues on the GPU and
// each pass handles one kind of work for all of them:
//
//   primary hits ──> shade ──> shadow rays ──> shadow pass (any hit) ──> light contributions
//        ^              └───> reflection/refraction rays ──> trace pass (closest hit) ──┐
//        └──────────────────────────────── hits of the next bounce <───────────────────┘
//
// The stage supplies two things: the primary hits (stage 02 rasterizes them; stages 03-05 trace camera rays with
// trace_camera_sample) and the traversal, a GLSL file that defines
//
//   bool trace_closest(Ray ray, out Hit hit);   // the nearest hit with 0 < t < ray.tmax (hit.triangle = -1 if none)
//   bool trace_any(Ray ray);                    // whether anything is hit with 0 < t < ray.tmax (may stop early)
//
// and calls wf_count_tests(n) for the ray/triangle tests it makes. It should #include "wavefront/wavefront.glsl"
// (rays, hits, the counting hook; RT_INTERSECT_METHOD says which ray/triangle test to use) and keep its own buffers
// at WF_BINDING_TRAVERSAL_FIRST and up. The pipeline compiles its trace and shadow passes with that file included
// first. Queues are appended with atomic counters and read back after each pass (4 uints), so each dispatch is sized
// to the rays that exist and each queue is allocated for exactly what the previous pass can produce.
//
// Effects the scene does not call for cost nothing: no shadow pass, shadow queue or shadow code without shadows, no
// trace pass, ray queues or reflection/refraction code without reflections and refractions (or with max_depth 0).
// The image is a per-pixel sum in fixed point (wavefront.glsl, wf_accumulate), so it is the same on every run.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "../app/image.h"
#include "../app/renderer.h"
#include "buffer.h"
#include "gpu_scene.h"
#include "shader.h"

namespace rt::gpu {

// First SSBO binding a traversal may use for its own data (wavefront.glsl: WF_BINDING_TRAVERSAL_FIRST).
constexpr unsigned kWavefrontBindingTraversalFirst = 24;
// The primary-hit pass of a stage may bind its own textures from here (02 binds its G-buffer).
constexpr unsigned kWavefrontFirstFreeTextureUnit = 1;

// std430 mirrors of wavefront.glsl.
struct WavefrontRay {
    glm::vec3 origin;    float tmax;
    glm::vec3 direction; std::uint32_t pixel;
    glm::vec3 weight;    std::uint32_t depth_kind;   // depth | kind << 16
};
static_assert(sizeof(WavefrontRay) == 48);
struct WavefrontHit {
    WavefrontRay ray;
    std::int32_t triangle; float t, u, v;
};
static_assert(sizeof(WavefrontHit) == 64);

// The stage's traversal (see above).
struct Traversal {
    std::string glsl;                 // relative to the shader root, e.g. "02_raster_hybrid/brute_force.glsl"
    ShaderDefines defines;            // extra defines it needs
    std::function<void()> bind;       // binds its buffers before the trace and shadow passes (may be empty)
};

class Wavefront {
public:
    explicit Wavefront(Traversal traversal);

    // Start of a frame: compiles the passes the settings call for (kept while they stay the same), sizes the
    // per-pixel buffers, clears the image and the counters, binds the scene. The scene must be uploaded.
    void begin_frame(const GpuScene& scene, const RenderSettings& settings);

    // One sample with primary hits from the stage: empties the hit queue, sizes it for `max_hits`, and binds the
    // hit queue, the queue counters and the radiance accumulator, so the stage's pass can append with wf_push_hit()
    // and add the background of empty pixels with wf_accumulate(). Then shade_sample() does the rest.
    void begin_primary_hits(std::size_t max_hits);
    void shade_sample();

    // One sample with traced primary rays (stages 03-05): camera rays through `offset` in each pixel, traced with
    // the traversal, then shaded as above.
    void trace_camera_sample(glm::vec2 offset);

    // End of the frame: the image (the mean over the samples) and the counters. Waits for the GPU.
    Image finish_frame(RayCounters& counters);

    // The defines the passes were compiled with (effects, RT_INTERSECT_METHOD, COUNT_TESTS, the traversal's).
    const ShaderDefines& defines() const { return defines_; }
    // Programs compiled for this frame's variant, e.g. "wavefront/shade.comp".
    std::vector<std::string> programs() const;
    // Passes dispatched since begin_frame, in first-run order, and how many dispatches each.
    const std::vector<std::string>& passes() const { return pass_order_; }
    const std::map<std::string, int>& dispatches() const { return dispatches_; }
    // The settings uniforms on a stage's own pass (wf_max_depth, wf_image_size, ...), for primary-hit passes.
    void set_uniforms(const Program& program) const;
    // Records a stage pass in passes() (e.g. "gbuffer").
    void record_pass(const std::string& name);

    // Count tests (COUNT_TESTS, default on): exact stats for one atomic per thread. Off for timing runs.
    bool count_tests = true;
    // When set, each pass is timed on it as "shade", "shadow", "trace", "resolve" or "camera_rays".
    GpuTimer* timer = nullptr;

private:
    Program compile(const std::string& pass, bool with_traversal) const;
    void compile_programs();
    std::uint32_t read_queue_count(unsigned index) const;
    void clear_queue_counts();
    void run_shade(std::size_t hits);
    void run_shadow(std::size_t rays);
    void run_trace(std::size_t rays);
    void resolve();
    void bind_traversal() const;

    Traversal traversal_;
    RenderSettings settings_;
    std::size_t pixels_ = 0;
    int samples_ = 0;
    unsigned lights_ = 0;
    bool shadows_ = false, secondary_ = false;
    ShaderDefines defines_;
    std::string compiled_key_;
    Program shade_, shadow_, trace_, resolve_, camera_;
    Buffer rays_in_, rays_out_, hits_, shadow_rays_, radiance_, image_, queue_counts_;
    CounterBuffer counters_;
    std::vector<std::string> pass_order_;
    std::map<std::string, int> dispatches_;
};

}  // namespace rt::gpu
