#include "brute_force_traversal.h"

#include <algorithm>
#include <stdexcept>

namespace rt::gpu {

BruteForceTraversal::BruteForceTraversal(std::size_t slice_triangles) : slice_(slice_triangles) {
    if (slice_ == 0) throw std::invalid_argument("BruteForceTraversal: a slice needs at least one triangle");
}

void BruteForceTraversal::trace_batch(const BatchTraceInputs& in, bool shadow) {
    if (!closest_ || in.wavefront.defines() != compiled_for_) {
        ShaderDefines any_defines = in.wavefront.defines();
        any_defines.emplace("ANY_HIT", "1");
        any_defines.emplace("RT_SHADOW_RAYS", "1");   // the shadow rule of the opacity test (opacity.glsl)
        closest_ = Program::compute("02_raster_hybrid/shaders/brute_force_slice.comp", in.wavefront.defines());
        any_ = Program::compute("02_raster_hybrid/shaders/brute_force_slice.comp", any_defines);
        compiled_for_ = in.wavefront.defines();
    }
    const Program& program = shadow ? any_ : closest_;
    in.rays.bind(kWavefrontBindingRaysIn);
    in.results.bind(kWavefrontBindingResults);
    if (in.tests_per_pixel) in.tests_per_pixel->bind(kWavefrontBindingTestsPerPixel);
    in.wavefront.set_uniforms(program);
    program.set("wf_input_first", unsigned(in.first));
    program.set("wf_input_count", unsigned(in.count));
    const std::size_t n = in.triangles;
    // Slice 0 always runs: it initializes every result (no hit / not blocked), even in a scene without triangles.
    for (std::size_t first = 0; first == 0 || first < n; first += slice_) {
        program.set("bf_slice_first", unsigned(first));
        program.set("bf_slice_count", unsigned(std::min(slice_, n - std::min(first, n))));
        program.dispatch_threads(in.count);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        ++dispatches_;
    }
}

}  // namespace rt::gpu
