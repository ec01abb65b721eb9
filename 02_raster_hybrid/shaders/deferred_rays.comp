#version 450 core
// Stage 02 with cut-outs (ENABLE_CUTOUTS): flags the ray slots primary_hits.comp filled with a deferred camera ray
// (a pixel whose closest candidate is a MASK or BLEND surface), so that compaction packs them, in primary order,
// into the queue of depth 0 that the stage's traversal then traces (rt::gpu::Wavefront::shade_sample).
#include "common/shaders/wavefront/wavefront.glsl"

layout(local_size_x = 64) in;

void main() {
    const uint slot = rt_global_index();
    if (slot >= wf_input_count) return;
    wf_flags[slot] = wf_ray_slots[slot].pixel != WF_NO_PIXEL ? 1u : 0u;
}
