#include "hybrid_renderer.h"

#include "brute_force_traversal.h"
#include "rasterized_primary.h"

namespace rt {

// The G-buffer gives the primary hits; every ray after them is tested against every triangle, in slices of
// triangles (brute_force_traversal.h).
HybridRenderer::HybridRenderer()
    : GpuStage(std::make_unique<RasterizedPrimary>(), std::make_unique<gpu::BruteForceTraversal>()) {}

}  // namespace rt
