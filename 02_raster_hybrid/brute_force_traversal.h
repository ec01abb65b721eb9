// Stage 02's traversal: brute force, every ray against every triangle (02_raster_hybrid/shaders/brute_force.glsl), traced as a
// batch traversal in slices of triangles (02_raster_hybrid/shaders/brute_force_slice.comp): one dispatch per slice over the
// pass' whole queue, each ray's closest hit (or blocked flag) carried from slice to slice. The result, the ties and
// the test counts are exactly those of one loop over all triangles per ray; no invocation loops over more than one
// slice, which keeps a large scene within what a GPU invocation may loop (llvmpipe: 65,535 iterations in all).
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include "common/gpu/gl/shader.h"
#include "common/gpu/pipeline/wavefront.h"

namespace rt::gpu {

class BruteForceTraversal {
public:
    static constexpr std::size_t kSliceTriangles = 16384;

    // triangle_count: the uploaded scene's triangles, asked for at each pass (the scene changes between frames).
    explicit BruteForceTraversal(std::function<std::size_t()> triangle_count,
                                 std::size_t slice_triangles = kSliceTriangles);

    // The Traversal to give the wavefront pipeline (valid while this object lives).
    Traversal traversal();
    // Dispatches of the slice passes so far (tests).
    int dispatches() const { return dispatches_; }

private:
    void run(bool any_hit, const BatchTraceInputs& in);

    std::function<std::size_t()> triangle_count_;
    std::size_t slice_;
    Program closest_, any_;
    ShaderDefines compiled_for_;   // the wavefront defines the programs were compiled with
    int dispatches_ = 0;
};

}  // namespace rt::gpu
