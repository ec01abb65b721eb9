// For pipeline tests of common/ code: the wavefront pipeline (wavefront.h) with a traversal of their own
// (common/shaders/testing/every_triangle.glsl), so that they depend on no stage. Needs test_context().
#pragma once

#include <string>
#include <vector>

#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/pipeline/traversal.h"
#include "common/gpu/pipeline/wavefront.h"
#include "common/scene/effects.h"

namespace rt::gpu {

inline Traversal& every_triangle_traversal() {
    static GlslTraversal traversal("common/shaders/testing/every_triangle.glsl");
    return traversal;
}

// width x height, the effects the scene calls for.
inline RenderSettings fixture_settings(const Scene& scene, int width, int height) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.effects = analyze_effects(scene);
    return settings;
}

// What the pipeline compiles for a scene: its defines after begin_frame (nothing traced).
inline ShaderDefines compiled_defines(const GpuScene& scene, const RenderSettings& settings) {
    Wavefront wavefront(every_triangle_traversal());
    wavefront.begin_frame(scene, settings);
    return wavefront.defines();
}

// One sample of camera rays through the pixel centres, traced, shaded and bounced; with the pipeline's defines and
// programs.
struct TracedFrame {
    FrameResult result;
    ShaderDefines defines;
    std::vector<std::string> programs;
};
inline TracedFrame traced_frame(const GpuScene& scene, const RenderSettings& settings) {
    Wavefront wavefront(every_triangle_traversal());
    wavefront.begin_frame(scene, settings);
    wavefront.trace_camera_sample(glm::vec2(0.5f));
    TracedFrame frame;
    wavefront.finish_frame(frame.result);
    frame.defines = wavefront.defines();
    frame.programs = wavefront.programs();
    return frame;
}

}  // namespace rt::gpu
