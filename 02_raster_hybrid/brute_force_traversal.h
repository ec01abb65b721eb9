// Stage 02's traversal: brute force, every ray against every triangle (02_raster_hybrid/shaders/brute_force.glsl), traced as a
// batch traversal in slices of triangles (02_raster_hybrid/shaders/brute_force_slice.comp): one dispatch per slice over the
// pass' whole queue, each ray's closest hit (or blocked flag) carried from slice to slice. The result, the ties and
// the test counts are exactly those of one loop over all triangles per ray; no invocation loops over more than one
// slice, which keeps a large scene within what a GPU invocation may loop (llvmpipe: 65,535 iterations in all).
#pragma once

#include <cstddef>
#include <string>

#include "common/gpu/gl/shader.h"
#include "common/gpu/pipeline/traversal.h"
#include "common/gpu/pipeline/wavefront.h"

namespace rt::gpu {

class BruteForceTraversal final : public Traversal {
public:
    static constexpr std::size_t kSliceTriangles = 16384;

    explicit BruteForceTraversal(std::size_t slice_triangles = kSliceTriangles);

    // A batch traversal: each pass, a closest-hit or any-hit slice program over the queue, slice after slice.
    void trace_batch(const BatchTraceInputs& in, bool shadow) override;
    // Dispatches of the slice passes so far (tests).
    int dispatches() const { return dispatches_; }

private:
    std::size_t slice_;
    Program closest_, any_;
    ShaderDefines compiled_for_;   // the wavefront defines the programs were compiled with
    int dispatches_ = 0;
};

}  // namespace rt::gpu
