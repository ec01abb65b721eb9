// The one interface a GPU stage's technique fills: how rays find their hits. Stage 02's brute force, 03's grid, 04's
// ray-space hierarchy and 05's sorted hierarchy are each a Traversal; a GPU stage (gpu_stage.h) owns one, beside its
// primary visibility (primary_visibility.h), and a wrapper (05's sorting) is a Traversal that calls another.
//
// Two parts. Per pass, the wavefront pipeline (wavefront.h) traces a queue of rays either through glsl() (a GLSL file
// compiled into its trace and shadow passes, defining trace_closest and trace_any) or, when glsl() is empty, through
// trace_batch() (a whole queue at once, any number of the traversal's own dispatches). Per frame, the stage calls
// build() before the first sample, end_frame() after the last, and report() for the stats.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/app/renderer.h"
#include "common/gpu/gl/buffer.h"
#include "common/gpu/gl/shader.h"

namespace CLI { class App; }

namespace rt::gpu {

class GpuScene;
class Wavefront;

// Consecutive rays of a batch of one kind (and, for shadow rays, one light). Every kind a shade pass spawns, and every
// light's shadow rays, has its own block of output slots (shade.comp), so the queues hold them in runs, and the
// pipeline knows each run's length from the compaction's read-back of its block boundaries: a stage that builds a
// structure per run (stage 04's hierarchies) reads nothing back to find them.
struct RayRun {
    std::size_t first = 0, count = 0;   // rays [first, first + count) of the batch (0 = its first ray)
    RayKind kind = RayKind::Primary;
    std::uint32_t light = 0;            // shadow rays: the light they go to
};

// What a batch traversal gets for one pass: trace rays[first, first + count) (WavefrontRay) and write result i for
// ray first + i: WavefrontTraceResult (closest hit) or, for shadow rays, a uint, 1 = occluded (any hit). It must add
// its ray/triangle tests to RT_COUNTER_INTERSECTION_TESTS (the counters stay bound at RT_BINDING_COUNTERS) and, when
// tests_per_pixel is given, to tests_per_pixel[ray.pixel] (wf_flush_tests does both in a pass that includes
// wavefront.glsl). Every buffer it is given fits one storage block.
struct BatchTraceInputs {
    const Buffer& rays;
    std::size_t first = 0, count = 0;
    Buffer& results;
    const Buffer* tests_per_pixel = nullptr;   // uint per pixel, only when settings.record_tests_per_pixel
    const Wavefront& wavefront;                // defines(), set_uniforms() for the batch's own programs
    std::vector<RayRun> runs;                  // the batch's rays as maximal runs, in order, covering [0, count)
    std::size_t triangles = 0;                 // the uploaded scene's triangles
};

// The frame a traversal builds for: the scene as given and as uploaded, and the timer its passes are timed with.
struct FrameInputs {
    const Scene& scene;
    const RenderSettings& settings;
    GpuScene& gpu_scene;
    GpuTimer& timer;
    bool primary_traced = false;   // the camera rays go through the traversal too (03's --primary trace)
};

// What a traversal says of its frame: its own stats section in result.extra, and how many times it read the GPU
// back (the stage sums them into gpu_cpu_syncs).
struct FrameReport {
    FrameResult& result;
    std::uint64_t syncs = 0;
    // A phase's GPU time in the frame (its pass_time_ms entry, "rh_build.shadow" say); 0 when it did not run.
    double pass_ms(const std::string& phase) const;
};

class Traversal {
public:
    virtual ~Traversal() = default;

    // Per pass (wavefront.h). A GLSL traversal: its file (relative to the shader root), the defines it needs, and
    // bind(), called before the trace and shadow passes. A batch traversal leaves glsl() empty.
    virtual std::string glsl() const { return {}; }
    bool traces_batches() const { return glsl().empty(); }   // a batch traversal: trace_batch replaces the passes
    virtual ShaderDefines defines() const { return {}; }
    virtual void bind() const {}
    // A batch traversal's pass: shadow rays (any hit) or traced rays (closest hit).
    virtual void trace_batch(const BatchTraceInputs& in, bool shadow);
    // --pixel: what the traversal's wf_count_steps counts per ray ("" when it counts none; RayWork::steps).
    virtual std::string steps() const { return {}; }

    // Per frame (gpu_stage.h).
    virtual void add_options(CLI::App& /*app*/) {}
    virtual std::string unsupported(const Scene& /*scene*/, const RenderSettings& /*settings*/) const { return {}; }
    // Its structure over the uploaded scene (time its passes with frame.timer.scope("build")).
    virtual void build(const FrameInputs& /*frame*/) {}
    // After the frame's last pass: what it reads back once to remember for the next frames.
    virtual void end_frame() {}
    virtual void report(FrameReport& /*report*/) {}
    // The programs of its own passes, for the stats' `programs`.
    virtual std::vector<std::string> programs() const { return {}; }
};

// A GLSL traversal with nothing to build or bind (tests: 02's brute_force.glsl traced per ray).
class GlslTraversal : public Traversal {
public:
    explicit GlslTraversal(std::string glsl, ShaderDefines defines = {})
        : glsl_(std::move(glsl)), defines_(std::move(defines)) {}
    std::string glsl() const override { return glsl_; }
    ShaderDefines defines() const override { return defines_; }

private:
    std::string glsl_;
    ShaderDefines defines_;
};

}  // namespace rt::gpu
