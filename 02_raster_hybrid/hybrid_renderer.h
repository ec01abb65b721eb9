// Stage 02: the raster/ray-tracing hybrid (Roger, Assarsson & Holzschuch 2007, "Whitted Ray-Tracing for Dynamic
// Scenes using a Ray-Space Hierarchy on the GPU"; Reis). Primary rays give exactly what rasterization gives, so
// the GPU rasterizes them into a G-buffer (rasterized_primary.h, gbuffer.h), and only the secondary rays (shadow,
// reflection, refraction) are traced, by the wavefront pipeline of common/gpu/pipeline/wavefront.h with a brute-force
// traversal (shaders/brute_force.glsl, traced in slices of triangles: brute_force_traversal.h).
// Context, options, window, timers and stats come from common/gpu/pipeline/gpu_stage.h; this is the pair.
#pragma once

#include "common/gpu/pipeline/gpu_stage.h"

namespace rt {

// Rasterized primary visibility + brute force.
class HybridRenderer : public gpu::GpuStage {
public:
    HybridRenderer();
};

}  // namespace rt
